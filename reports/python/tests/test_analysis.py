"""The analysis and the report on hand-made report data: paired counts and medians by hand, tool
groups never pooled, escaping, and the same data giving the same bytes."""
import filecmp
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(__file__), ".."))

from coverbench_report import report  # noqa: E402
from coverbench_report import stats  # noqa: E402
from coverbench_report import tables as T  # noqa: E402
from coverbench_report.analysis import Analysis  # noqa: E402

SPECS = [
    {"name": "coverage_reachable", "unit": "1", "better": 1, "kind": "quality", "headline": True,
     "tie_absolute": 0.001, "tie_relative": 0, "description": "c"},
    {"name": "length_total", "unit": "m", "better": -1, "kind": "quality", "headline": True,
     "tie_absolute": 0, "tie_relative": 0.001, "description": "l"},
    {"name": "overlap", "unit": "1", "better": -1, "kind": "quality", "headline": True,
     "tie_absolute": 0.005, "tie_relative": 0, "description": "o"},
    {"name": "length_ratio", "unit": "1", "better": -1, "kind": "quality", "headline": True,
     "tie_absolute": 0, "tie_relative": 0.001, "description": "r"},
    {"name": "duration_s", "unit": "s", "better": -1, "kind": "quality", "headline": True,
     "tie_absolute": 0, "tie_relative": 0.001, "description": "d"},
    {"name": "plan_time_ms", "unit": "ms", "better": -1, "kind": "measured", "headline": True,
     "tie_absolute": 0.05, "tie_relative": 0.25, "description": "t"},
]


# As the C++ report data declares them (kRunFields' exported fields, kRunStatuses).
RUN_FIELDS = [{"name": "status", "type": "status", "unit": "", "description": "s"},
              {"name": "valid", "type": "bool", "unit": "", "description": "v"},
              {"name": "uncovered_reachable_m2", "type": "real", "unit": "m2", "description": "u"}]
RUN_STATUSES = ["ok", "partial", "invalid_output", "metrics_error", "no_reachable_area", "invalid_input",
                "timeout", "memory_limit", "crash", "error"]


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def run(column, wall, cov, length, status="ok", tool=0.1, dataset="d", time=1.0):
    return {"key": f"{column}-{wall}-{tool}", "column": column, "config": column.split(" @")[0], "dataset": dataset,
            "wall": wall, "wall_name": wall, "tool_width": tool, "clearance": 0.02,
            "pairing": f"{wall}/{tool}/0.02/1", "status": status, "valid": status == "ok",
            "uncovered_reachable_m2": None,
            "metrics": {"coverage_reachable": cov, "length_total": length, "overlap": 0.1, "length_ratio": length / 10,
                        "duration_s": length * 3, "plan_time_ms": time}}


def data(runs, columns, name="hand", dataset_label="d"):
    return {"format": "coverbench-report-data", "version": 1,
            "experiment": {"id": 1, "name": name, "config_path": "c.yaml", "config_hash": "0123456789abcdef",
                           "config_text": "name: hand\n", "baseline": "a", "facts": [["host", "h"]],
                           "datasets": [{"label": dataset_label, "source": "s", "walls": 4, "sha256": "x"}],
                           "planners": [{"label": c, "planner": c, "params": {}} for c in ("a", "b", "c")],
                           "columns": columns},
            "metrics": SPECS, "walls": {}, "runs": runs, "gallery": [],
            "run_fields": RUN_FIELDS, "run_statuses": RUN_STATUSES}


# b against a: w1 better coverage, shorter (win, win); w2 equal coverage, longer (tie, loss);
# w3 worse coverage, equal length (loss, tie); w4 b timed out (a loss in both: a failure loses to
# every value on its wall).
HAND = [run("a", "w1", 0.90, 10), run("b", "w1", 0.95, 9), run("a", "w2", 0.99, 10), run("b", "w2", 0.99, 11),
        run("a", "w3", 0.99, 12), run("b", "w3", 0.98, 12), run("a", "w4", 0.99, 12),
        run("b", "w4", math.nan, math.nan, "timeout")]


class PairedByHand(unittest.TestCase):
    def test_counts_medians_and_outcomes(self):
        a = Analysis(data(HAND, ["a", "b"]))
        rows = {r["metric"]: r for r in a.paired_table("d", ["coverage_reachable", "length_total"])}
        cov, length = rows["coverage_reachable"], rows["length_total"]
        self.assertEqual((cov["pairs"], cov["wins"], cov["ties"], cov["losses"]), (4, 1, 1, 2))
        self.assertEqual((cov["failed"], cov["baseline_failed"], cov["both"]), (1, 0, 3))
        self.assertEqual((length["wins"], length["ties"], length["losses"]), (1, 1, 2))
        self.assertAlmostEqual(length["median"], 0.0)  # over the 3 pairs both valid: differences -1, +1, 0
        # Medians over valid runs: a's lengths 10, 10, 12, 12 -> 11; b's 9, 11, 12 -> 11, q1 10, q3 11.5.
        self.assertEqual(a.summary("a", "d", "length_total")["median"], 11)
        self.assertEqual(a.summary("b", "d", "length_total"), {"n": 3, "median": 11, "q1": 10, "q3": 11.5})
        o = a.outcomes("b")
        self.assertEqual((o["runs"], o["ok"], o["counts"]["timeout"]), (4, 3, 1))
        # What ok still leaves, as a number a reader can check: b's ok runs cover 0.95, 0.99, 0.98.
        self.assertEqual(o["ok_coverage_min"], 0.95)
        self.assertEqual(a.outcomes("a")["ok_coverage_min"], 0.90)
        table = T.outcome_table(a)
        self.assertIn("ok: least coverage of R", table.header)
        self.assertEqual(table.rows[1][table.header.index("ok: least coverage of R")], "95.00 %")
        # Measured figures are ranked but never tested.
        self.assertNotIn("plan_time_ms", a.compared)
        ranking = a.ranking("d", a.tools[0], "plan_time_ms")
        self.assertFalse(any(e["best"] for e in ranking))

    def test_best_is_marked_only_when_the_test_says_so(self):
        # b shorter than a on 12 walls out of 12: Wilcoxon exact p = 2 / 4096, significant.
        runs = []
        for i in range(12):
            runs += [run("a", f"w{i}", 1.0, 10 + i), run("b", f"w{i}", 1.0, 9 + i)]
        a = Analysis(data(runs, ["a", "b"]))
        top = a.ranking("d", a.tools[0], "length_total")[0]
        self.assertEqual((top["column"], top["best"]), ("b", True))
        # On 3 walls the same difference is not significant (exact p = 0.25): no mark.
        a3 = Analysis(data(runs[:6], ["a", "b"]))
        self.assertFalse(a3.ranking("d", a3.tools[0], "length_total")[0]["best"])


class Failures(unittest.TestCase):
    """A run without a valid path ranks below every valid run on its wall (docs/report.md, Failures)."""

    def test_a_planner_that_times_out_where_another_succeeds_is_not_ranked_first(self):
        # x times out on w1, w2 (y: 0.90 there) and beats y on w3, w4 (0.99 against 0.95).
        # Over its finished walls x's median is 0.99 and it ranked first. Counted as worst, x's
        # four outcomes are 0.99, 0.99, fail, fail: the middle two are 0.99 and a failure, so its
        # median is a failure and x ranks last; y's median (0.90, 0.90, 0.95, 0.95) is 0.925.
        runs = [run("x", "w1", math.nan, math.nan, "timeout"), run("y", "w1", 0.90, 10),
                run("x", "w2", math.nan, math.nan, "timeout"), run("y", "w2", 0.90, 10),
                run("x", "w3", 0.99, 10), run("y", "w3", 0.95, 10),
                run("x", "w4", 0.99, 10), run("y", "w4", 0.95, 10)]
        a = Analysis(data(runs, ["x", "y"]))
        ranking = a.ranking("d", a.tools[0], "coverage_reachable")
        self.assertEqual([(e["column"], e["rank"]) for e in ranking], [("y", 1), ("x", 2)])
        self.assertEqual([(e["valid"], e["walls"]) for e in ranking], [(4, 4), (2, 4)])
        self.assertAlmostEqual(ranking[0]["median"], 0.925)
        self.assertTrue(ranking[1]["failed"])
        table = T.to_markdown(T.headline_table(a, "d", a.tools[0]))
        self.assertIn("| x | 2/4 | failed (2) |", table)
        self.assertIn("| y | 4/4 | 92.50 (1) |", table)
        # The paired test counts the two timeouts as x's losses: 2 wins, 2 losses.
        x, y = a.pairs("x", "y", "d", "coverage_reachable")
        self.assertEqual(x, [-math.inf, -math.inf, 0.99, 0.99])
        r = stats.paired(a.specs["coverage_reachable"], *a.pairs("y", "x", "d", "coverage_reachable"))
        self.assertEqual((r["pairs"], r["wins"], r["losses"], r["failed"], r["baseline_failed"], r["both"]),
                         (4, 2, 2, 0, 2, 2))
        self.assertAlmostEqual(r["median"], -0.04)  # over w3, w4, where both have a path

    def test_failures_below_half_count_as_the_worst_values(self):
        # x fails on w1 only; its outcomes 1.0, 0.99, 0.98, fail (sorted best first): median
        # (0.98 + 0.99) / 2 = 0.985, not the 0.99 of its three finished walls; y: 0.97 everywhere.
        runs = [run("x", "w1", math.nan, math.nan, "crash"), run("x", "w2", 1.0, 10), run("x", "w3", 0.99, 10),
                run("x", "w4", 0.98, 10)] + [run("y", w, 0.97, 10) for w in ("w1", "w2", "w3", "w4")]
        a = Analysis(data(runs, ["x", "y"]))
        first = a.ranking("d", a.tools[0], "coverage_reachable")[0]
        self.assertEqual((first["column"], first["rank"], first["failed"]), ("x", 1, False))
        self.assertAlmostEqual(first["median"], 0.985)
        # Length (lower is better): x's failure counts as the longest path: 10, 10, 10, inf -> 10.
        self.assertEqual([(e["column"], e["rank"]) for e in a.ranking("d", a.tools[0], "length_total")],
                         [("x", 1), ("y", 1)])

    def test_walls_where_nobody_has_a_path_do_not_count_and_failures_share_the_worst_friedman_rank(self):
        # w0: every planner says no_reachable_area (not a failure of any of them: left out).
        # w1..w3: x 0.99, y 0.98, z times out -> z ranks 3 on each; w4: x and z time out, y 0.98 ->
        # x and z share ranks 2 and 3 (2.5 each). Average ranks: x (1+1+1+2.5)/4 = 1.375,
        # y (2+2+2+1)/4 = 1.75, z (3+3+3+2.5)/4 = 2.875.
        runs = [run(c, "w0", math.nan, math.nan, "no_reachable_area") for c in ("x", "y", "z")]
        for w in ("w1", "w2", "w3"):
            runs += [run("x", w, 0.99, 10), run("y", w, 0.98, 10), run("z", w, math.nan, math.nan, "timeout")]
        runs += [run("x", "w4", math.nan, math.nan, "timeout"), run("y", "w4", 0.98, 10),
                 run("z", "w4", math.nan, math.nan, "timeout")]
        a = Analysis(data(runs, ["x", "y", "z"]))
        f = a.friedman("d", a.tools[0], "coverage_reachable")
        self.assertEqual(f["blocks"], 4)
        self.assertEqual(f["ranks"], [1.375, 1.75, 2.875])
        ranking = a.ranking("d", a.tools[0], "coverage_reachable")
        self.assertEqual([(e["column"], e["rank"], e["walls"]) for e in ranking], [("x", 1, 4), ("y", 2, 4), ("z", 3, 4)])


class Ranks(unittest.TestCase):
    def test_medians_within_the_tie_band_share_a_rank(self):
        # coverage medians 0.9999, 0.9995 (within 0.001: tied), 0.99 -> ranks 1, 1, 3
        runs = [run("a", "w", 0.9999, 10), run("b", "w", 0.9995, 10), run("c", "w", 0.99, 10)]
        a = Analysis(data(runs, ["a", "b", "c"]))
        ranks = {e["column"]: e["rank"] for e in a.ranking("d", a.tools[0], "coverage_reachable")}
        self.assertEqual(ranks, {"a": 1, "b": 1, "c": 3})


class ToolsNeverPooled(unittest.TestCase):
    def test_comparisons_and_rankings_stay_within_a_tool(self):
        cols = ["a @ s=0.05 m, c=0.02 m", "a @ s=0.1 m, c=0.02 m", "b @ s=0.05 m, c=0.02 m", "b @ s=0.1 m, c=0.02 m"]
        runs = []
        for w in ("w1", "w2", "w3"):
            for tool, suffix in ((0.05, " @ s=0.05 m, c=0.02 m"), (0.1, " @ s=0.1 m, c=0.02 m")):
                runs.append(run("a" + suffix, w, 1.0, 20 / tool, tool=tool))
                runs.append(run("b" + suffix, w, 1.0, 21 / tool, tool=tool))
        a = Analysis(data(runs, cols))
        self.assertEqual(len(a.tools), 2)
        for r in a.paired_table("d", ["length_total"]):
            self.assertEqual(a.tool_of[r["column"]], a.tool_of[r["baseline"]])
            self.assertEqual(r["pairs"], 3)
            self.assertEqual(r["wins"] + r["ties"] + r["losses"], 3)
        for tool in a.tools:
            self.assertEqual({e["column"] for e in a.ranking("d", tool, "length_total")}, set(a.tool_columns(tool)))


    def test_a_line_tool_and_a_disk_of_its_width_are_two_tools(self):
        # docs/metrics.md#tool-shapes: same width and clearance, other shape: never ranked together.
        cols = ["a @ s=0.1 m, c=0.02 m", "a @ line s=0.1 m, c=0.02 m", "b @ s=0.1 m, c=0.02 m", "b @ line s=0.1 m, c=0.02 m"]
        runs = []
        for w in ("w1", "w2", "w3"):
            for shape, suffix in (("disk", " @ s=0.1 m, c=0.02 m"), ("line", " @ line s=0.1 m, c=0.02 m")):
                for planner, length in (("a", 20), ("b", 21)):
                    r = run(planner + suffix, w, 1.0, length if shape == "disk" else length - 5)
                    if shape == "line":
                        r["tool_shape"] = "line"
                        r["key"] += "-line"
                        r["pairing"] += "/line"
                    runs.append(r)
        a = Analysis(data(runs, cols))
        self.assertEqual(sorted(a.tools), [(0.1, 0.02, "disk", 0.0), (0.1, 0.02, "line", 0.0)])
        for r in a.paired_table("d", ["length_total"]):
            self.assertEqual(a.tool_of[r["column"]], a.tool_of[r["baseline"]])
            self.assertEqual(r["pairs"], 3)
        self.assertEqual(T.tool_label(a, (0.1, 0.02, "line", 0.0)), " at line s=0.100 m, c=0.0200 m")
        self.assertEqual(T.tool_label(a, (0.1, 0.02, "disk", 0.0)), " at s=0.100 m, c=0.0200 m")
        self.assertEqual(T.tool_label(a, (0.1, 0.02, "rectangle", 0.05)), " at rectangle s=0.100 m, d=0.0500 m, c=0.0200 m")


COAT_SPECS = SPECS + [
    {"name": "thickness_cv", "unit": "1", "better": -1, "kind": "quality", "headline": False,
     "tie_absolute": 0.001, "tie_relative": 0, "description": "cv"},
    {"name": "even_share", "unit": "1", "better": 1, "kind": "quality", "headline": False,
     "tie_absolute": 0.005, "tie_relative": 0, "description": "e"}]


def coated(r, even, cv, target=None):
    """A run of a tool with a flux profile (as report data carries it) and its coat's metrics."""
    out = json.loads(json.dumps(r))
    out["metrics"].update(even_share=even, thickness_cv=cv)
    out["profile"] = {"label": "beta 2.5" + (f", target {target} um" if target else ""), "target_um": target}
    return out


class EvenCoat(unittest.TestCase):
    """docs/deposition.md, the report: which planner leaves the most even coat, by paired tests."""

    def coat_data(self, walls, target=None):
        # b's coat is more even than a's on every wall (0.05 more of R within 10 %), c's less.
        runs = []
        for i in range(walls):
            runs += [coated(run("a", f"w{i}", 1.0, 10), 0.70 + 0.001 * i, 0.3, target),
                     coated(run("b", f"w{i}", 1.0, 11), 0.75 + 0.002 * i, 0.2, target),
                     coated(run("c", f"w{i}", 1.0, 12), 0.60 + 0.001 * i, 0.4, target)]
        d = data(runs, ["a", "b", "c"])
        d["metrics"] = COAT_SPECS
        return d

    def test_the_coat_heads_the_report_only_when_runs_have_one(self):
        a = Analysis(self.coat_data(6))
        self.assertIn("even_share", a.headline)
        self.assertIn("thickness_cv", a.headline)
        plain = data(HAND, ["a", "b"])
        plain["metrics"] = COAT_SPECS
        b = Analysis(plain)
        self.assertNotIn("even_share", b.headline)
        self.assertIsNone(T.even_coat_table(b, "d", b.tools[0]))

    def test_the_most_even_coat_is_named_only_when_the_paired_tests_say_so(self):
        # 12 walls, b ahead of both on all: exact Wilcoxon p = 2/4096 each, Holm-adjusted 2 x that.
        a = Analysis(self.coat_data(12, target=87.9))
        t = T.even_coat_table(a, "d", a.tools[0])
        self.assertEqual(t.title, "d: the most even coat: b")
        self.assertEqual([(r[0], r[1], r[7]) for r in t.rows], [(("b", "best"), "a", "12/0/0"), (("b", "best"), "c", "12/0/0")])
        self.assertEqual([t["p_holm"] for t in a.most_even("d", a.tools[0])["tests"]], [4 / 4096, 4 / 4096])
        self.assertEqual(t.rows[0][8], "0.00098 ***")
        self.assertIn("within 10 % of the target", t.note)
        self.assertIn("beta 2.5, target 87.9 um", t.note)
        # On 3 walls the same lead is not significant (exact p = 0.25): the leader is not named best.
        a3 = Analysis(self.coat_data(3))
        t3 = T.even_coat_table(a3, "d", a3.tools[0])
        self.assertEqual(t3.title, "d: no configuration leaves a more even coat than every other (b leads, not separably)")
        self.assertFalse(any(isinstance(c, tuple) for row in t3.rows for c in row))
        self.assertIn("within 10 % of the mean", t3.note)

    def test_a_share_near_the_target_that_a_patchier_coat_wins_is_not_called_most_even(self):
        # b has more of R within 10 % of the target on all 12 walls, but c's coat varies less on
        # all 12 (its CV 0.1 against b's 0.2): the title says what b leads in, and that c varies less.
        runs = []
        for i in range(12):
            runs += [coated(run("a", f"w{i}", 1.0, 10), 0.70 + 0.001 * i, 0.3, 87.9),
                     coated(run("b", f"w{i}", 1.0, 11), 0.75 + 0.002 * i, 0.2, 87.9),
                     coated(run("c", f"w{i}", 1.0, 12), 0.60 + 0.001 * i, 0.1 - 0.001 * i, 87.9)]
        d = data(runs, ["a", "b", "c"])
        d["metrics"] = COAT_SPECS
        a = Analysis(d)
        self.assertEqual(a.most_even("d", a.tools[0])["less_varied"], ["c"])
        t = T.even_coat_table(a, "d", a.tools[0])
        self.assertEqual(t.title, "d: most of R within 10 % of the target: b, but c varies less (thickness_cv): no one most even coat")
        self.assertFalse(any(isinstance(c, tuple) for row in t.rows for c in row))
        # The last column: each other configuration's CV against b's, two-sided; "(yes)" where it is lower.
        self.assertEqual({row[1]: row[11] for row in t.rows}, {"a": "0.00098 ***", "c": "0.00098 *** (yes)"})

    def test_configurations_within_the_tie_band_tie_at_the_top(self):
        # a and b leave the same coat on every wall (as two settings that give one path do).
        runs = []
        for i in range(6):
            runs += [coated(run("a", f"w{i}", 1.0, 10), 0.75, 0.2), coated(run("b", f"w{i}", 1.0, 10), 0.75, 0.2),
                     coated(run("c", f"w{i}", 1.0, 12), 0.60, 0.4)]
        d = data(runs, ["a", "b", "c"])
        d["metrics"] = COAT_SPECS
        a = Analysis(d)
        self.assertEqual(T.even_coat_table(a, "d", a.tools[0]).title,
                         "d: no configuration leaves a more even coat than every other (a, b tie at the top)")
        # A tie at the top broken by a coat that varies less than every other's, on all 12 walls.
        runs = []
        for i in range(12):
            runs += [coated(run("a", f"w{i}", 1.0, 10), 0.75, 0.3), coated(run("b", f"w{i}", 1.0, 10), 0.75, 0.2 - 0.001 * i),
                     coated(run("c", f"w{i}", 1.0, 12), 0.60, 0.4)]
        d = data(runs, ["a", "b", "c"])
        d["metrics"] = COAT_SPECS
        a = Analysis(d)
        self.assertEqual(T.even_coat_table(a, "d", a.tools[0]).title,
                         "d: the most even coat: b (tied with a in even_share, its coat varies less than every other's in "
                         "thickness_cv)")

    def test_the_report_says_it(self):
        d = self.coat_data(12, target=87.9)
        # A wall whose coat's raster is past the cap: the run keeps its other metrics, not its coat.
        big = coated(run("a", "big", 1.0, 10), None, None, 87.9)
        big["reason"] = "the coat's metrics are not scored (the others are): deposition: tool.profile: needs ..."
        d["runs"].append(big)
        with tempfile.TemporaryDirectory() as out:
            report.build(d, out)
            page = read(os.path.join(out, "index.html"))
            self.assertIn("d: the most even coat: b", page)
            self.assertIn("Flux profile of the tool (the coat): beta 2.5, target 87.9 um. The coat is not scored on 1 "
                          "of 37 runs (a raster past its cap; each run&#x27;s reason says why)", page)
            self.assertIn("d: the most even coat: b", read(os.path.join(out, "report.md")))


class Rendering(unittest.TestCase):
    def test_hostile_labels_are_text_in_every_format(self):
        hostile = '<script>alert("x")</script> | 50% & _x_'
        d = data([dict(r, dataset=hostile) for r in HAND], ["a", "b"], name=hostile, dataset_label=hostile)
        with tempfile.TemporaryDirectory() as out:
            report.build(d, out)
            page = read(os.path.join(out, "index.html"))
            self.assertNotIn("<script", page)
            self.assertIn("&lt;script&gt;alert(&quot;x&quot;)&lt;/script&gt;", page)
            md = read(os.path.join(out, "report.md"))
            self.assertNotIn("<script>", md)
            tex = read(os.path.join(out, "report.tex"))
            self.assertIn(r"50\% \& \_x\_", tex)

    def test_latex_tables_compile_and_fit_one_and_two_columns(self):
        if not shutil.which("pdflatex"):
            self.skipTest("pdflatex not installed (scripts/setup.sh installs texlive-latex-recommended)")
        hostile = 'a_b & 50% <x> {y} #z ~'
        d = data([dict(r, dataset=hostile) for r in HAND] + [run("c", "w1", 0.9, 10), run("c", "w2", 0.9, 10)],
                 ["a", "b", "c"], name=hostile, dataset_label=hostile)
        with tempfile.TemporaryDirectory() as out:
            report.build(d, out, formats=("latex",))
            for options in ("", "twocolumn"):
                with open(os.path.join(out, "main.tex"), "w", encoding="utf-8") as f:
                    f.write(f"\\documentclass[{options}]{{article}}\n\\usepackage[utf8]{{inputenc}}\n"
                            "\\usepackage{booktabs,graphicx}\n\\begin{document}\n\\input{report.tex}\n\\end{document}\n")
                r = subprocess.run(["pdflatex", "-interaction=nonstopmode", "-halt-on-error", "main.tex"], cwd=out,
                                   capture_output=True, text=True, timeout=120)
                self.assertEqual(r.returncode, 0, r.stdout[-2000:])
                self.assertNotIn("Overfull \\hbox", r.stdout)

    def test_same_data_same_bytes(self):
        runs = []
        for i in range(8):
            for c, k in (("a", 1.0), ("b", 1.1), ("c", 0.95)):
                runs.append(run(c, f"w{i}", 1.0 - 0.001 * i * k, (10 + i) * k, time=1 + i * k))
        d = data(runs, ["a", "b", "c"])
        with tempfile.TemporaryDirectory() as one, tempfile.TemporaryDirectory() as two:
            report.build(json.loads(json.dumps(d)), one)
            report.build(json.loads(json.dumps(d)), two)
            cmp = filecmp.dircmp(one, two)
            self.assertEqual(cmp.left_only + cmp.right_only, [])
            for sub in ("", "figures"):
                names = sorted(os.listdir(os.path.join(one, sub)))
                self.assertTrue(names)
                _, mismatch, errors = filecmp.cmpfiles(os.path.join(one, sub), os.path.join(two, sub),
                                                       [n for n in names if os.path.isfile(os.path.join(one, sub, n))],
                                                       shallow=False)
                self.assertEqual(mismatch + errors, [])
            self.assertTrue(os.path.exists(os.path.join(one, "figures", "d01-cd.svg")))  # 3 planners: a CD diagram


def replan(fraction, repair, status, ms, added, after, scratch, obstacles=2):
    return {"fraction": fraction, "repair": repair, "obstacles": obstacles, "requested": 2, "status": status,
            "valid": status != "invalid_output", "repair_ms": ms,
            "figures": {"added_length_m": added, "uncovered_added_m2": 0.0, "coverage_reachable": after,
                        "scratch_coverage_reachable": scratch}}


class Replanning(unittest.TestCase):
    def test_one_row_per_planner_fraction_and_repair_with_medians_by_hand(self):
        runs = [run("a", w, 0.99, 10) for w in ("w1", "w2", "w3")] + [run("b", "w1", 0.99, 10)]
        runs[0]["replans"] = [replan(0.3, "replan", "ok", 10.0, 1.0, 0.99, 0.99), replan(0.3, "detour", "partial", 2.0, 5.0, 0.95, 0.99)]
        runs[1]["replans"] = [replan(0.3, "replan", "partial", 30.0, 3.0, 0.98, 0.98), replan(0.3, "detour", "partial", 4.0, 7.0, 0.96, 0.98)]
        runs[2]["replans"] = [replan(0.3, "replan", "failed", 20.0, None, None, None, 1),
                              replan(0.3, "detour", "invalid_output", 6.0, 9.0, 0.97, None, 1)]
        a = Analysis(data(runs, ["a", "b"]))
        [t] = T.replanning_tables(a)
        self.assertEqual(t.title, "d: replanning after surprise obstacles")
        self.assertEqual([r[:3] for r in t.rows], [["a", "0.3", "detour"], ["a", "0.3", "replan"]])
        detour, replan_row = t.rows
        # detour: ms 2, 4, 6 -> median 4, max 6; added 5, 7, 9 -> 7; coverage 0.95, 0.96, 0.97 -> 0.96
        self.assertEqual(detour[3:], ["3", "0 / 2 / 0 / 1", "5/6", "7.00 m", "0 m²", "96.00 %", "98.50 %"])
        # replan: the failed one has no figures: medians of the other two
        self.assertEqual(replan_row[3:], ["3", "1 / 1 / 1 / 0", "5/6", "2.00 m", "0 m²", "98.50 %", "98.50 %"])
        # The times, measured anew by every rerun, in a table of their own after every reproduced one;
        # the failed replan's time counts.
        [m] = T.replanning_tables(a, measured=True)
        self.assertEqual(m.rows, [["a", "0.3", "detour", "3", "4.00", "6.00"], ["a", "0.3", "replan", "3", "20.0", "30.0"]])
        titles = [x.title for x in T.paper_tables(a)]
        self.assertIn(t.title, titles)
        self.assertEqual(titles[-1], m.title, "the measured table is not last")
        measured_first = min(i for i, x in enumerate(T.paper_tables(a)) if "measured" in x.title)
        self.assertLess(titles.index(t.title), measured_first)
        self.assertIn("obstacles appear at 0.3 of each path", report.replanning_text(a))

    def test_fractions_that_differ_print_apart(self):
        runs = [run("a", "w1", 0.99, 10)]
        runs[0]["replans"] = [replan(0.5, "replan", "ok", 1.0, 1.0, 0.99, 0.99),
                              replan(0.5000000000000001, "replan", "ok", 1.0, 1.0, 0.99, 0.99)]
        [t] = T.replanning_tables(Analysis(data(runs, ["a"])))
        self.assertEqual([r[1] for r in t.rows], ["0.5", "0.5000000000000001"])
        self.assertEqual(T.exact_number(0.3), "0.3")

    def test_no_section_without_replanning(self):
        a = Analysis(data(HAND, ["a", "b"]))
        self.assertEqual(T.replanning_tables(a), [])
        self.assertEqual(report.replanning_text(a), "")


class Markdown(unittest.TestCase):
    def test_underscores_and_markup_are_escaped(self):
        self.assertEqual(T._md("_u_ *b* a|b"), "\\_u\\_ \\*b\\* a\\|b")
        # Strikethrough and math (GitHub) are text too.
        self.assertEqual(T._md("~~x~~ $a$"), "\\~\\~x\\~\\~ \\$a\\$")


class Numbers(unittest.TestCase):
    def test_units_and_significant_digits(self):
        cov = {"name": "coverage_reachable", "unit": "1", "tie_absolute": 0.001}
        self.assertEqual(T.value(cov, 0.99871), "99.87 %")
        self.assertEqual(T.difference(cov, -0.0007), "-0.07 pp")
        self.assertEqual(T.value({"name": "length_total", "unit": "m", "tie_absolute": 0}, 15912.3), "15912 m")
        self.assertEqual(T.value({"name": "x", "unit": "ms", "tie_absolute": 0}, 1.2149), "1.21 ms")
        self.assertEqual(T.value({"name": "peak_memory_bytes", "unit": "B", "tie_absolute": 0}, 3 * 1048576), "3.00 MiB")
        self.assertEqual(T.value({"name": "turns_30", "unit": "1", "tie_absolute": 0.5}, 198.0), "198")


if __name__ == "__main__":
    unittest.main()


class Playback(unittest.TestCase):
    """A gallery picture with playback data gets a figure the player attaches to; the page loads
    the player only then, as a file of its own (never inline, never from data)."""

    def section(self, playback):
        pic = {"column": "z", "key": "k", "status": "ok", "file": "gallery/a.svg", "note": "", "playback": playback}
        return {"title": "d", "walls": [{"wall": "h", "wall_name": "w", "why": "median", "pictures": [pic]}]}

    def test_figure_names_its_data_escaped(self):
        from coverbench_report.page import gallery_html
        self.assertIn('<figure data-playback="gallery/a&quot;b.js">', gallery_html(self.section('gallery/a"b.js')))
        self.assertIn("<figure><a", gallery_html(self.section("")))

    def test_page_loads_only_the_scripts_it_is_given(self):
        from coverbench_report.page import page
        self.assertNotIn("<script", page("t", "", [("a", "A", "x")]))
        self.assertIn('<script src="player.js"></script>\n</body>', page("t", "", [("a", "A", "x")], ["player.js"]))

    def test_the_player_ships_with_the_package(self):
        with open(report.PLAYER, encoding="utf-8") as f:
            self.assertIn("window.coverbenchPlayback", f.read())
