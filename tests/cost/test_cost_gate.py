"""The cost gate's comparison at its threshold, and the gate itself on a deliberately slowed
planner (COVERBENCH_COST_SELFTEST_SLOW makes the probe plan twice inside the counted region).
COVERBENCH_COST_PROBE names the probe (ctest sets it)."""
import os
import subprocess
import sys
import unittest

sys.path.insert(0, os.path.dirname(__file__))

import cost_gate as gate  # noqa: E402

PROBE = os.environ.get("COVERBENCH_COST_PROBE", gate.DEFAULT_PROBE)


class Compare(unittest.TestCase):
    def test_equal_counts_pass(self):
        self.assertEqual(gate.compare({"a": 1000}, {"a": 1000}), ([], []))

    def test_a_rise_at_the_threshold_passes_and_just_above_fails(self):
        self.assertEqual(gate.compare({"a": 100000}, {"a": 101000}), ([], []))  # +1.000 %
        fails, _ = gate.compare({"a": 100000}, {"a": 101001})                     # +1.001 %
        self.assertEqual(fails, ["| a | 100,000 | 101,001 | +1,001 | +1.001 % |"])

    def test_a_fall_is_reported_and_passes(self):
        fails, falls = gate.compare({"a": 100000}, {"a": 90000})
        self.assertEqual(fails, [])
        self.assertEqual(falls, ["| a | 100,000 | 90,000 | -10,000 | -10.000 % |"])

    def test_a_new_case_fails_and_a_case_outside_the_subset_is_not_judged(self):
        fails, falls = gate.compare({"a": 5, "b": 7}, {"a": 5, "c": 9})
        self.assertEqual(fails, ["| c | new | 9 | | |"])
        self.assertEqual(falls, [])


def check(case, **env):
    return subprocess.run([sys.executable, os.path.join(os.path.dirname(__file__), "cost_gate.py"), "check",
                           "--probe", PROBE, "--cases", f"^{case}$"],
                          capture_output=True, text=True, env=dict(os.environ, **env))


class Gate(unittest.TestCase):
    """The gate on the pinned build; on another one (tests/pinned_build.py) these are skipped with
    the reason, unless COVERBENCH_GATES_REQUIRED=1 (CI), where they run and would fail."""
    CASE = "zigzag/seed_5x5_3obs"

    def setUp(self):
        build = subprocess.run([PROBE, "--identity"], check=True, capture_output=True, text=True).stdout.strip()
        pinned = gate.pinned_build.pinned_build()
        if build != pinned and os.environ.get("COVERBENCH_GATES_REQUIRED") != "1":
            self.skipTest(f"the cost gate is pinned to {pinned}; this build is {build}")

    def test_the_committed_baseline_holds(self):
        run = check(self.CASE)
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)
        self.assertIn("1 cases within +1.0 %", run.stdout)

    def test_a_slowed_planner_trips_the_gate(self):
        run = check(self.CASE, COVERBENCH_COST_SELFTEST_SLOW="zigzag")
        self.assertEqual(run.returncode, 1, run.stdout + run.stderr)
        self.assertIn(f"| {self.CASE} |", run.stdout)
        # Planning twice costs about twice: the second plan skips the first one's one-time costs
        # (allocations, first touches), a few per cent of a 5 million instruction case.
        self.assertRegex(run.stdout, r"\+(9[5-9]|100)\.\d+ % \|")

    def test_a_different_planner_slowed_leaves_this_case_alone(self):
        run = check(self.CASE, COVERBENCH_COST_SELFTEST_SLOW="spiral")
        self.assertEqual(run.returncode, 0, run.stdout + run.stderr)


if __name__ == "__main__":
    unittest.main()
