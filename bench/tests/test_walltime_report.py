"""The wall-time report's verdicts (a change needs significance and size), its two outputs, and
one real interleaved run of the same program against itself (COVERBENCH_BENCH names it; ctest
sets it)."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

import walltime_report as report  # noqa: E402

BENCH = os.environ.get("COVERBENCH_BENCH", os.path.join(report.ROOT, "build", "bench", "coverbench_bench"))


class Verdict(unittest.TestCase):
    def test_a_large_significant_rise_is_slower(self):
        change, p, v = report.verdict([10.0, 10.1, 9.9, 10.2, 10.0, 9.8], [12.0, 12.1, 11.9, 12.2, 12.0, 11.8])
        self.assertAlmostEqual(change, 20.0, places=6)
        self.assertLess(p, 0.05)
        self.assertEqual(v, "slower")

    def test_a_significant_but_small_shift_is_no_change(self):
        _, p, v = report.verdict([10.0, 10.01, 10.02, 10.03, 10.04, 10.05], [10.2, 10.21, 10.22, 10.23, 10.24, 10.25])
        self.assertLess(p, 0.05)
        self.assertEqual(v, "no change")

    def test_a_large_but_noisy_shift_is_no_change(self):
        _, p, v = report.verdict([10, 14, 8, 12, 9, 13], [11, 15, 9, 13, 10, 14])
        self.assertGreater(p, 0.05)
        self.assertEqual(v, "no change")

    def test_a_large_significant_fall_is_faster(self):
        self.assertEqual(report.verdict([10, 10.1, 10.2, 10.3, 10.4], [8, 8.1, 8.2, 8.3, 8.4])[2], "faster")


class Order(unittest.TestCase):
    def test_rounds_alternate_which_side_goes_first(self):
        calls = []
        real = report.time_one
        report.time_one = lambda bench, name, min_time: calls.append((bench, name)) or (1.0, 1)
        try:
            samples = report.interleave("A", "B", ["x", "y"], 3, "0.01")
        finally:
            report.time_one = real
        self.assertEqual(calls, [("A", "x"), ("B", "x"), ("A", "y"), ("B", "y"),
                                 ("B", "x"), ("A", "x"), ("B", "y"), ("A", "y"),
                                 ("A", "x"), ("B", "x"), ("A", "y"), ("B", "y")])
        self.assertEqual(len(samples["x"]["base"]), 3)


class Holm(unittest.TestCase):
    def samples(self, others):
        moved = {"base": [(1.0, 1), (1.01, 1), (1.02, 1), (1.03, 1)], "head": [(2.0, 1), (2.01, 1), (2.02, 1), (2.03, 1)]}
        still = {"base": [(1.0, 1), (1.2, 1), (0.9, 1), (1.1, 1)], "head": [(1.05, 1), (1.15, 1), (0.95, 1), (1.1, 1)]}
        return {"moved": moved, **{f"still{i}": still for i in range(others)}}

    def test_alone_a_clean_separation_is_a_change(self):
        row = report.summarize(self.samples(0))[0]
        self.assertAlmostEqual(row["p"], 2 / 70)  # the exact test's smallest p with 4 and 4
        self.assertEqual(row["verdict"], "slower")

    def test_among_twenty_benchmarks_the_same_p_is_adjusted_away(self):
        rows = {r["name"]: r for r in report.summarize(self.samples(19))}
        self.assertAlmostEqual(rows["moved"]["p"], 20 * 2 / 70)
        self.assertEqual(rows["moved"]["verdict"], "no change")


class Outputs(unittest.TestCase):
    def test_markdown_and_dashboard_json(self):
        samples = {"zigzag/w": {"base": [(1.0, 5000), (1.1, 5100), (1.0, 5000), (1.05, 5000)],
                                 "head": [(2.0, 6000), (2.1, 6100), (2.0, 6000), (2.05, 6000)]}}
        rows = report.summarize(samples)
        md = report.markdown(rows, "base1", "head1", 3)
        self.assertIn("| zigzag/w | 1.025 | 2.025 | +97.6 % |", md)
        self.assertIn("| 5.0 | 6.0 |", md)  # peak MiB of base and head (5100 KiB, 6100 KiB)
        entries = json.loads(report.dashboard_json(rows, "base1"))
        self.assertEqual([e["name"] for e in entries], ["zigzag/w (time)", "zigzag/w (peak memory)"])
        self.assertEqual((entries[0]["unit"], entries[0]["value"]), ("ms", 2.025))
        self.assertEqual((entries[1]["unit"], entries[1]["value"]), ("KiB", 6100))
        for e in entries:
            self.assertTrue({"name", "unit", "value"} <= set(e))


class RealRun(unittest.TestCase):
    def test_a_name_with_brackets_and_dashes_selects_exactly_that_benchmark(self):
        name = "spanning-tree[return]/seed_10x10_5obs"
        self.assertEqual(report.exact_filter(name), "^spanning-tree[[]return[]]/seed_10x10_5obs$")
        ms, kib = report.time_one(BENCH, name, "0.01")  # exits unless exactly one benchmark ran
        self.assertGreater(ms, 0.0)
        self.assertGreater(kib, 1000)
        self.assertLess(kib, 50000)  # its own peak, not this Python process's (about 70 MiB with scipy)

    def test_the_same_program_against_itself(self):
        out = tempfile.mkdtemp(prefix="coverbench-walltime-test-")
        run = subprocess.run([sys.executable, os.path.join(report.HERE, "walltime_report.py"), "--base", "HEAD",
                              "--base-bench", BENCH, "--head-bench", BENCH, "--rounds", "4",
                              "--filter", "^zigzag/seed_(1x1_empty|5x5_1obs)$", "--min-time", "0.01", "--out", out],
                             capture_output=True, text=True)
        self.assertEqual(run.returncode, 0, run.stderr)
        with open(os.path.join(out, "walltime.json"), encoding="utf-8") as f:
            entries = json.load(f)
        self.assertEqual(len(entries), 4)
        with open(os.path.join(out, "walltime.md"), encoding="utf-8") as f:
            md = f.read()
        self.assertIn("| zigzag/seed_1x1_empty |", md)
        self.assertIn("4 interleaved rounds", md)


if __name__ == "__main__":
    unittest.main()
