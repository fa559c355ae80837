"""Line and rectangle tools from Python (docs/metrics.md#tool-shapes): scored by the same engines as the command
line, with the hand values of tests/metrics/line_tool_test.cpp, and checked with the same message."""
import math
import os
import sys
import unittest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "python"))

import coverbench  # noqa: E402

# A 2 x 1 m wall without obstacles.
WALL = {"name": "strip", "boundary": [[0, 0], [2, 0], [2, 1], [0, 1]]}


class ToolShape(unittest.TestCase):
    def test_a_right_angle_turn_of_a_line_sweeps_its_hand_area_in_both_engines(self):
        # East 1 m, north 0.5 m, s = 0.2 m: 0.2 + 0.1 - 0.1^2 + pi 0.1^2 / 4.
        hand = 0.29 + math.pi * 0.01 / 4
        m = coverbench.score(WALL, [[0.5, 0.3], [1.5, 0.3], [1.5, 0.8]], [True, True], tool_width=0.2,
                             tool_shape="line", judge="exact")
        self.assertTrue(m["valid"])
        self.assertTrue(m["exact"]["valid"])
        self.assertAlmostEqual(m["swept_area"], hand, delta=5e-6)
        self.assertAlmostEqual(m["reachable_area"], 2.0, delta=1e-9)  # a line's R: the whole wall
        disk = coverbench.score(WALL, [[0.5, 0.3], [1.5, 0.3], [1.5, 0.8]], [True, True], tool_width=0.2)
        self.assertLess(disk["reachable_area"], 2.0)

    def test_a_pass_to_the_walls_edge_is_valid_for_a_line_only(self):
        path = [[0.5, 0.5], [2.0, 0.5]]
        self.assertTrue(coverbench.score(WALL, path, [True], tool_width=0.2, tool_shape="line")["valid"])
        self.assertFalse(coverbench.score(WALL, path, [True], tool_width=0.2)["valid"])

    def test_plan_says_it_planned_for_the_circumscribed_disk(self):
        p = coverbench.plan(WALL, "spiral", tool_width=0.2, tool_shape="line")
        self.assertEqual(p["status"], "ok")
        self.assertTrue(p["valid"])
        self.assertIn("circumscribed disk", p["reason"])
        # zigzag plans the line itself, and says nothing of a disk.
        z = coverbench.plan(WALL, "zigzag", tool_width=0.2, tool_shape="line")
        self.assertTrue(z["valid"])
        self.assertNotIn("circumscribed", z["reason"])

    def test_a_right_angle_turn_of_a_rectangle_sweeps_its_hand_area_in_both_engines(self):
        # s = 0.2, d = 0.1: the moves' rectangles d longer, and the four corners' sectors
        # (tests/metrics/line_tool_test.cpp, RectangleTool.ARightAngleTurnSweepsFourCornerSectors).
        h, e = 0.1, 0.05
        r2, a = h * h + e * e, math.atan(e / h)
        hand = (2 * h * 1.1 + 2 * h * 0.6 - (h + e) ** 2 + 2 * (r2 * a - h * e) + r2 * (math.pi / 2 - 2 * a) / 2
                - e * (h - e))
        m = coverbench.score(WALL, [[0.5, 0.3], [1.5, 0.3], [1.5, 0.8]], [True, True], tool_width=0.2,
                             tool_shape="rectangle", tool_depth=0.1, judge="exact")
        self.assertTrue(m["valid"])
        self.assertTrue(m["exact"]["valid"])
        self.assertAlmostEqual(m["swept_area"], hand, delta=5e-6)
        p = coverbench.plan(WALL, "spiral", tool_width=0.2, tool_shape="rectangle", tool_depth=0.1)
        self.assertEqual(p["status"], "ok")
        self.assertTrue(p["valid"])
        self.assertIn("rectangle tool's circumscribed disk", p["reason"])

    def test_a_rectangle_needs_its_depth_and_only_a_rectangle_has_one(self):
        with self.assertRaises(ValueError) as e:
            coverbench.score(WALL, [[0.5, 0.5], [1, 0.5]], [True], tool_shape="rectangle")
        self.assertEqual(str(e.exception), "tool: tool_depth: is missing: a rectangle tool's depth along the heading, m")
        with self.assertRaises(ValueError) as e:
            coverbench.score(WALL, [[0.5, 0.5], [1, 0.5]], [True], tool_depth=0.1)
        self.assertEqual(str(e.exception), "tool: tool_depth: a depth belongs to a rectangle; a disk has none")

    def test_an_unknown_shape_is_one_line(self):
        with self.assertRaises(ValueError) as e:
            coverbench.score(WALL, [[0.5, 0.5], [1, 0.5]], [True], tool_shape="square")
        self.assertEqual(str(e.exception), "tool_shape: tool.shape: must be disk, line or rectangle, got 'square'")


if __name__ == "__main__":
    unittest.main()
