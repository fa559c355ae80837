"""The gate's comparison: a moved metric, a lost run and an unbumped version are all reported."""
import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(__file__))

import quality_gate as gate  # noqa: E402
import pinned_build  # noqa: E402


def row(planner="zigzag", version="1", overlap="0.25", status="ok"):
    return {"dataset": "d", "wall": "w", "planner": planner, "planner_version": version, "status": status,
            "valid": "true", "coverage_reachable": "1.0", "coverage_wall": "0.98", "overlap": overlap,
            "length_total": "100.0", "turns": "40.0", "waypoints": "41.0"}


class Compare(unittest.TestCase):
    def test_nothing_moved(self):
        self.assertEqual(gate.compare([row()], [row()]), ([], []))

    def test_a_moved_metric_is_a_row_with_its_change_and_names_the_unbumped_planner(self):
        lines, unbumped = gate.compare([row()], [row(overlap="0.2")])
        self.assertEqual(lines, ["| d / w / zigzag | overlap | 0.25 | 0.2 | -0.05 (-20 %) |"])
        self.assertEqual(unbumped, ["zigzag"])

    def test_a_bumped_version_is_expected_alongside(self):
        lines, unbumped = gate.compare([row()], [row(version="2", overlap="0.2")])
        self.assertEqual(len(lines), 2)
        self.assertEqual(unbumped, [])

    def test_missing_and_new_runs(self):
        lines, _ = gate.compare([row("a")], [row("b")])
        self.assertEqual(lines, ["| d / w / a | (run) | in golden | missing | |", "| d / w / b | (run) | missing | new | |"])


class OffThePinnedBuild(unittest.TestCase):
    """Another compiler skips a gate with its reason; where the gates are required it fails."""

    def setUp(self):
        self.saved = os.environ.pop("COVERBENCH_GATES_REQUIRED", None)

    def tearDown(self):
        os.environ.pop("COVERBENCH_GATES_REQUIRED", None)
        if self.saved is not None:
            os.environ["COVERBENCH_GATES_REQUIRED"] = self.saved

    def test_the_pinned_build_is_the_cost_baselines(self):
        self.assertRegex(pinned_build.pinned_build(), r"^\S+ [\d.]+ \w+, flags '.*'$")

    def test_skipped_with_the_reason_or_failed_when_required(self):
        self.assertEqual(pinned_build.off_pinned_build("quality gate", "Clang 14.0.6 Release, flags '-O3'", "GNU 12.2.0"), 77)
        os.environ["COVERBENCH_GATES_REQUIRED"] = "1"
        self.assertEqual(pinned_build.off_pinned_build("quality gate", "Clang 14.0.6 Release, flags '-O3'", "GNU 12.2.0"), 1)


if __name__ == "__main__":
    unittest.main()
