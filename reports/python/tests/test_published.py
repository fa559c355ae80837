"""Published results on hand-made report data: ratios, the geometric mean with its interval, wins
and losses with the signed-rank test, instances one side solved, names that match no wall or
several, times under another clock, and each planner configuration on its own row.

The published values here are made-up test data, chosen so that every figure can be worked out
by hand; they come from no paper."""
import math
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

from coverbench_report import published as P  # noqa: E402
from coverbench_report import report  # noqa: E402
from coverbench_report import tables as T  # noqa: E402
from coverbench_report.analysis import Analysis  # noqa: E402
from test_analysis import data, read, run  # noqa: E402

WALLS = [f"w{i:02d}" for i in range(24)]


def theirs(i):
    """The made-up published length of wall i: 5 + i on w00-w09, 7 on w10-w19, 9 on w22, none
    (not solved) on w20, w21 and w23."""
    return 5.0 + i if i < 10 else 7.0 if i < 20 else 9.0 if i == 22 else None


def runs():
    out = []
    for i, w in enumerate(WALLS):
        # a: twice the published length on w00-w09, the same on w10-w19 (ties), a length on w20 and
        # w21, which the paper did not solve, and a timeout on w22 and w23.
        if i < 20:
            out.append(run("a", w, 0.99, 2 * theirs(i) if i < 10 else theirs(i)))
            # b: half the published length everywhere it ran (w00-w19 only).
            out.append(run("b", w, 0.99, theirs(i) / 2))
        elif i < 22:
            out.append(run("a", w, 0.99, 12.0))
        else:
            out.append(run("a", w, math.nan, math.nan, "timeout"))
    for twin in ("twin-1", "twin-2"):  # two walls of one name
        r = run("a", twin, 0.99, 10.0)
        r["wall_name"] = "twin"
        out.append(r)
    return out


def rows():
    out = []
    line = 2
    for i, w in enumerate(WALLS):
        out.append([w, "M", "length_total", theirs(i), line])
        out.append([w, "M", "duration_s", None if theirs(i) is None else 3 * theirs(i), line + 1])
        line += 2
    out.append(["ghost", "M", "length_total", 4.0, line])
    out.append(["twin", "M", "length_total", 4.0, line + 1])
    return out


def published_data(clock_matches=False):
    d = data(runs(), ["a", "b"])
    d["published"] = {"file": "made-up.csv", "sha256": "ab" * 32, "clock": "v 1 m/s, a 1 m/s2, stops at turns over 30 degrees",
                      "clock_matches": clock_matches, "columns": ["instance", "method", "metric", "value", "line"],
                      "rows": rows()}
    return d


class PublishedByHand(unittest.TestCase):
    def test_ratios_geometric_mean_interval_and_test(self):
        p = P.of(Analysis(published_data()))
        a = p.comparison("a", "M", "length_total")
        # 24 matched walls where a ran: 20 both solved, w20 and w21 only a, w22 only the paper,
        # w23 neither; "ghost" and "twin" are not compared.
        self.assertEqual((a["instances"], a["both"], a["only_ours"], a["only_theirs"], a["neither"]), (24, 20, 2, 1, 1))
        # Lower is better: ratio 2 on w00-w09 (losses), 1 on w10-w19 (ties).
        self.assertEqual((a["wins"], a["ties"], a["losses"]), (0, 10, 10))
        # Geometric mean: (2^10 * 1^10)^(1/20) = sqrt(2). Log ratios: ten ln 2, ten 0; mean ln2/2,
        # sample sd (ln2/2) sqrt(20/19); half width t(0.975, 19) sd / sqrt(20) = 2.093024 (ln2/2) / sqrt(19).
        half = 2.0930240544 * (math.log(2) / 2) / math.sqrt(19)
        self.assertAlmostEqual(a["gmean"], 1.4142135624, places=9)
        self.assertAlmostEqual(a["low"], math.exp(math.log(2) / 2 - half), places=7)
        self.assertAlmostEqual(a["high"], math.exp(math.log(2) / 2 + half), places=7)
        self.assertAlmostEqual(a["low"], 1.19740, places=4)
        self.assertAlmostEqual(a["high"], 1.67028, places=4)
        # Signed-rank over the ten untied log ratios, all positive: exact two-sided p = 2 / 2^10.
        self.assertAlmostEqual(a["p"], 2 / 1024, places=12)

    def test_per_instance_ratios(self):
        p = P.of(Analysis(published_data()))
        pairs = {i: (x, y) for i, x, y in p.pairs("a", "M", "length_total")}
        self.assertEqual(pairs["w03"], (16.0, 8.0))   # 2 * 8 and 5 + 3
        self.assertEqual(pairs["w12"], (7.0, 7.0))
        self.assertEqual(pairs["w20"], (12.0, None))  # the paper did not solve it
        self.assertEqual(pairs["w22"], (None, 9.0))   # a timed out
        self.assertEqual(pairs["w23"], (None, None))
        self.assertNotIn("ghost", pairs)
        self.assertNotIn("twin", pairs)
        md = T.to_markdown(P.instance_table(p))
        self.assertIn("| a | M | length\\_total | w03 | 16.0 m | 8.00 m | 2.000 |", md)
        self.assertIn("| a | M | length\\_total | w20 | 12.0 m | not solved | - |", md)

    def test_each_configuration_on_its_own_row_with_holm_across_them(self):
        p = P.of(Analysis(published_data()))
        got = {r["column"]: r for r in p.rows()}
        self.assertEqual(sorted(got), ["a", "b"])
        b = got["b"]
        # b ran w00-w19 only, half the published length on each: ratio 0.5 twenty times.
        self.assertEqual((b["instances"], b["both"], b["wins"], b["ties"], b["losses"]), (20, 20, 20, 0, 0))
        self.assertAlmostEqual(b["gmean"], 0.5, places=12)
        self.assertAlmostEqual(b["low"], 0.5, places=12)
        self.assertAlmostEqual(b["high"], 0.5, places=12)
        self.assertAlmostEqual(b["p"], 2 / 2 ** 20, places=15)
        # Holm over two tests: b's 2 * 2/2^20, a's max of that and 2/1024.
        self.assertAlmostEqual(b["p_holm"], 4 / 2 ** 20, places=15)
        self.assertAlmostEqual(got["a"]["p_holm"], 2 / 1024, places=12)

    def test_names_without_one_wall_and_times_of_another_clock_are_listed(self):
        p = P.of(Analysis(published_data()))
        skipped = {row[0]: row[2] for row in p.skipped}
        self.assertEqual(skipped["ghost"], "no wall of the experiment has this name")
        self.assertEqual(skipped["twin"], "2 walls of the experiment have this name")
        self.assertIn("another clock", skipped["duration_s"])
        self.assertEqual(p.compared, ["length_total"])
        self.assertNotIn("duration_s", [r["metric"] for r in p.rows()])
        # The same clock: the times are compared too (3 times the lengths, so the same ratios).
        same = P.of(Analysis(published_data(clock_matches=True)))
        self.assertEqual(same.compared, ["length_total", "duration_s"])
        self.assertAlmostEqual(same.comparison("a", "M", "duration_s")["gmean"], math.sqrt(2), places=9)

    def test_values_at_the_ends_of_the_doubles_give_ratios_not_an_error(self):
        # Made-up published values a table may hold (finite, >= 0): 1e308, whose quotient with a
        # small length underflows to 0, and a subnormal 1e-320, whose quotient overflows; and special
        # characters in the names, escaped in every format.
        runs_ = [run("a", f"w{i}", 0.99, ours) for i, ours in enumerate((1e-20, 1e-20, 10.0, 10.0))]
        d = data(runs_, ["a"])
        d["published"] = {"file": "t.csv", "sha256": "ab" * 32, "clock": None, "clock_matches": False,
                          "columns": ["instance", "method", "metric", "value", "line"],
                          "rows": [["w0", "big", "length_total", 1e308, 2], ["w1", "big", "length_total", 1e308, 3],
                                   ["w2", "sub", "length_total", 1e-320, 4], ["w3", "sub", "length_total", 1e-320, 5],
                                   ["<b>x</b> & 50% a_b | c\\d", "sub", "length_total", 1.0, 6]]}
        p = P.of(Analysis(d))
        big, sub = p.comparison("a", "big", "length_total"), p.comparison("a", "sub", "length_total")
        # ln(1e-20 / 1e308) = -328 ln 10 twice: the mean and its zero-width interval, exp'd, are 0.
        self.assertEqual((big["ratios"], big["gmean"], big["low"], big["high"]), (2, 0.0, 0.0, 0.0))
        # ln(10 / 1e-320) = 321 ln 10 is over ln of the largest double: infinity.
        self.assertEqual((sub["ratios"], sub["gmean"], sub["low"], sub["high"]), (2, math.inf, math.inf, math.inf))
        self.assertAlmostEqual(P.log_ratio(1e-20, 1e308), -328 * math.log(10), places=9)
        with tempfile.TemporaryDirectory() as folder:
            report.build(d, folder, ["md", "csv", "latex"])
            md = read(os.path.join(folder, "report.md"))
            self.assertIn("| a | sub | length\\_total | 2 | 2 | inf | \\[inf, inf\\] |", md)
            self.assertNotIn("<b>", md)
            self.assertNotIn("<b>", read(os.path.join(folder, "report.tex")))

    def test_tables_in_every_format_same_bytes_and_none_without(self):
        outs = []
        for _ in range(2):
            with tempfile.TemporaryDirectory() as folder:
                report.build(published_data(), folder, ["md", "csv", "latex"])
                outs.append([read(os.path.join(folder, f)) for f in ("report.md", "report.csv", "report.tex")])
        self.assertEqual(outs[0], outs[1])
        md, csv, tex = outs[0]
        self.assertIn("## Published results: each planner configuration against each published method", md)
        self.assertIn("| a | M | length\\_total | 24 | 20 | 1.414 | \\[1.197, 1.670\\] | 0/10/10 | 0.002 \\*\\* | 2 | 1 | 1 |", md)
        self.assertIn("Published results per instance,a,M,length_total,w03,16.0 m,8.00 m,2.000", csv)
        self.assertIn("Published values not compared,ghost,all,no wall of the experiment has this name", csv)
        self.assertIn("a & M & length\\_total & 24 & 20 & 1.414 & [1.197, 1.670]", tex)
        with tempfile.TemporaryDirectory() as folder:
            report.build(data(runs(), ["a", "b"]), folder, ["md"])
            self.assertNotIn("Published", read(os.path.join(folder, "report.md")))


if __name__ == "__main__":
    unittest.main()
