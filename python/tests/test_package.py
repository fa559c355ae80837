"""`import coverbench`: walls, planners, both judges and an experiment's runs from Python, checked
against the command line's own answers."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "python"))

import coverbench  # noqa: E402

WALL = os.path.join(ROOT, "datasets", "canonical", "living_room_north.json")
BINARY = os.environ.get("COVERBENCH_BINARY", os.path.join(ROOT, "build", "coverbench"))


class Package(unittest.TestCase):
    def test_planners_are_the_registry(self):
        out = subprocess.run([BINARY, "planners"], capture_output=True, text=True, check=True).stdout
        names = [p["name"] for p in coverbench.planners()]
        self.assertEqual(len(names), 6)
        for name in names:
            self.assertIn(name, out)
        zigzag = next(p for p in coverbench.planners() if p["name"] == "zigzag")
        overlap = next(s for s in zigzag["params"] if s["name"] == "overlap")
        self.assertEqual((overlap["type"], overlap["min"], overlap["max"]), ("number", 0.0, 0.9))

    def test_a_plan_is_the_commands_plan_and_both_judges_score_it(self):
        ours = coverbench.plan(WALL, "zigzag", {"overlap": 0.1})
        with tempfile.TemporaryDirectory() as d:
            subprocess.run([BINARY, "plan", "--wall", WALL, "--planner", "zigzag", "--param", "overlap=0.1", "--out",
                            os.path.join(d, "p.json")], capture_output=True, check=True)
            with open(os.path.join(d, "p.json"), encoding="utf-8") as f:
                theirs = json.load(f)
        self.assertEqual(ours["waypoints"], theirs["waypoints"])
        self.assertEqual(ours["tool_on"], theirs["tool_on"])
        # Where it follows F's round boundary (round the obstacles' corners) the path is arcs.
        self.assertEqual(ours["bulge"], theirs["bulge"])
        self.assertGreater(sum(b != 0 for b in ours["bulge"]), 0)
        m = coverbench.score(WALL, ours["waypoints"], ours["tool_on"], bulge=ours["bulge"], judge="exact")
        self.assertTrue(m["valid"])
        self.assertTrue(m["exact"]["valid"])
        lo, hi = m["exact"]["coverage_reachable"]
        self.assertLessEqual(lo, hi)
        self.assertGreater(m["coverage_reachable"], 0.99)
        # A path through the window: both judges say invalid.
        bad = coverbench.score(WALL, [[0.2, 1.0], [4.0, 1.0]], [True], judge="exact")
        self.assertFalse(bad["valid"])
        self.assertFalse(bad["exact"]["valid"])

    def test_bad_input_is_a_value_error_with_the_one_line_message(self):
        with self.assertRaisesRegex(ValueError, "boundary: needs at least 3 distinct points"):
            coverbench.check_wall({"name": "x", "boundary": [[0, 0], [1, 0]]})
        with self.assertRaisesRegex(ValueError, "params: overlap: .*0.9"):
            coverbench.plan(WALL, "zigzag", {"overlap": 2})
        with self.assertRaisesRegex(ValueError, "unknown planner"):
            coverbench.plan(WALL, "nope")

    def test_an_experiments_runs_as_dicts(self):
        with tempfile.TemporaryDirectory() as d:
            with open(os.path.join(d, "c.yaml"), "w", encoding="utf-8") as f:
                f.write("name: py\noutput: out\ndatasets:\n  - suite: seed-cases\nplanners: [zigzag, spiral]\n")
            subprocess.run([BINARY, "run", os.path.join(d, "c.yaml"), "--no-report"], capture_output=True, check=True)
            rows = coverbench.runs(os.path.join(d, "out", "results.sqlite"))
            self.assertEqual({r["planner"] for r in rows}, {"zigzag", "spiral"})
            for r in rows:
                self.assertIn(r["status"], ("ok", "partial", "no_reachable_area"))
                self.assertIn("coverage_reachable", r)
            try:
                import pandas  # noqa: F401
            except ImportError:
                return
            self.assertEqual(len(coverbench.runs_dataframe(os.path.join(d, "out", "results.sqlite"))), len(rows))


if __name__ == "__main__":
    unittest.main()
