"""The analysis of one experiment's report data: outcomes, summaries, rankings, paired
comparisons, Friedman tests. Pure functions of report_data.json (no plotting, no formatting)."""
import json
import math
from collections import OrderedDict

import numpy as np

from . import stats

COMPARED_KINDS = ("quality",)  # measured figures (one noisy sample per run) are never tested
# The coat's metrics (docs/deposition.md) head the report of an experiment whose runs carry them:
# how even the coat is, is what a tool with a flux profile is measured for. EVEN_COAT ranks "the
# most even coat".
COAT_HEADLINE = ("even_share", "thickness_cv")
EVEN_COAT = "even_share"
COAT_SPREAD = "thickness_cv"


def load(path):
    with open(path, encoding="utf-8") as f:
        data = json.load(f)
    if data.get("format") != "coverbench-report-data" or data.get("version") != 1:
        raise ValueError(f"{path}: format: not CoverBench report data of version 1")
    return data


# The JSON types of each run field type the report data's run_fields name (kRunFields in C++).
FIELD_TYPES = {"text": (str,), "status": (str,), "bool": (bool,), "integer": (int,), "real": (int, float)}


def read_runs(data):
    """The runs of report data, each checked against the run fields the data declares (its
    run_fields: names and types; its run_statuses), with real fields that were not measured (null)
    as NaN. Raises ValueError naming the run and the field."""
    fields, statuses = data.get("run_fields"), data.get("run_statuses")
    if not isinstance(fields, list) or not isinstance(statuses, list):
        raise ValueError("run_fields, run_statuses: missing (report data from another CoverBench?)")
    runs = []
    for i, run in enumerate(data["runs"]):
        out = dict(run)
        for f in fields:
            name, kind = f["name"], f["type"]
            if kind not in FIELD_TYPES:
                raise ValueError(f"run_fields: {name}: unknown type '{kind}'")
            if name not in run:
                raise ValueError(f"runs[{i}].{name}: missing")
            v = run[name]
            if kind == "real" and v is None:
                out[name] = math.nan
            elif isinstance(v, bool) != (kind == "bool") or not isinstance(v, FIELD_TYPES[kind]):
                raise ValueError(f"runs[{i}].{name}: must be {kind}, not {v!r}")
            elif kind == "status" and v not in statuses:
                raise ValueError(f"runs[{i}].{name}: unknown status '{v}'")
            elif kind == "real":
                out[name] = float(v)
        runs.append(out)
    return runs


def usable(run):
    """A run whose metrics are summarised: a valid path that leaves no reachable part out (ok) or
    knowingly leaves parts out (partial)."""
    return run["status"] in ("ok", "partial") and run["valid"]


# A run without a valid path where another planner has a value (analysis.Analysis.outcome).
FAILED = "failed"


def value(run, metric):
    v = run["metrics"].get(metric)
    return math.nan if v is None else float(v)


class Analysis:
    """Everything the report shows, computed once."""

    def __init__(self, data):
        self.data = data
        self.experiment = data["experiment"]
        self.specs = OrderedDict((m["name"], m) for m in data["metrics"])
        self.runs = read_runs(data)
        # The statuses in the order tables list them (with a path first), as the data declares.
        self.status_order = list(data["run_statuses"])
        self.columns = list(self.experiment["columns"])
        seen = []
        for d in self.experiment["datasets"]:
            if d["label"] not in seen:
                seen.append(d["label"])
        for r in self.runs:
            if r["dataset"] not in seen:
                seen.append(r["dataset"])
        self.datasets = [d for d in seen if any(r["dataset"] == d for r in self.runs)]
        self.baseline = self.experiment["baseline"]
        self.by_column = {c: [r for r in self.runs if r["column"] == c] for c in self.columns}
        # Columns grouped by tool: only runs at the same tool are ever compared or ranked together.
        self.tools = []
        self.tool_of = {}
        for c in self.columns:
            rs = self.by_column[c]
            # A line or a rectangle is another tool than the disk of its width
            # (docs/metrics.md#tool-shapes); a rectangle of another depth is another tool.
            t = ((rs[0]["tool_width"], rs[0]["clearance"], rs[0].get("tool_shape", "disk"), rs[0].get("tool_depth", 0.0))
                 if rs else (math.nan, math.nan, "disk", 0.0))
            self.tool_of[c] = t
            if t not in self.tools:
                self.tools.append(t)
        self.config_of = {c: (self.by_column[c][0]["config"] if self.by_column[c] else c) for c in self.columns}
        self.has_coat = any(math.isfinite(value(r, EVEN_COAT)) for r in self.runs)
        # The tools' flux profiles (docs/deposition.md; one per experiment config): their labels,
        # and whether the coat's shares are of a target rather than of the mean.
        self.profiles = sorted({r["profile"]["label"] for r in self.runs if r.get("profile")})
        self.coat_target = any(r.get("profile") and r["profile"].get("target_um") for r in self.runs)
        self.headline = [m for m, s in self.specs.items() if s["headline"] or (self.has_coat and m in COAT_HEADLINE)]
        self.headline_quality = [m for m in self.headline if self.specs[m]["kind"] != "measured"]
        self.headline_measured = [m for m in self.headline if self.specs[m]["kind"] == "measured"]
        self.compared = [m for m, s in self.specs.items() if s["better"] != 0 and s["kind"] in COMPARED_KINDS]
        self.appendix = [m for m in self.specs if m not in self.headline and m != "valid"]
        self._index = {}
        self._by_column_dataset = {}
        for r in self.runs:
            self._index[(r["column"], r["pairing"])] = r
            self._by_column_dataset.setdefault((r["column"], r["dataset"]), []).append(r)
        # Computed once, asked for again by the paper's tables, the page's tables and the figures:
        self._friedman = {}  # (dataset, tool, metric) -> Friedman test
        self._paired = {}  # (column, other, dataset, metric) -> paired comparison
        self._ranking = {}  # (dataset, tool, metric) -> ranking

    # --- groups -------------------------------------------------------------------------------
    def tool_columns(self, tool):
        return [c for c in self.columns if self.tool_of[c] == tool]

    def baseline_column(self, tool):
        for c in self.tool_columns(tool):
            if self.config_of[c] == self.baseline:
                return c
        return None

    def runs_of(self, column, dataset):
        return self._by_column_dataset.get((column, dataset), [])

    def values(self, column, dataset, metric):
        return [v for v in (value(r, metric) for r in self.runs_of(column, dataset) if usable(r)) if math.isfinite(v)]

    # --- outcomes -----------------------------------------------------------------------------
    def statuses(self):
        present = {r["status"] for r in self.runs}
        return [s for s in self.status_order if s == "ok" or s in present]

    def outcomes(self, column, dataset=None):
        rs = [r for r in self.by_column[column] if dataset is None or r["dataset"] == dataset]
        counts = OrderedDict((s, 0) for s in self.statuses())
        for r in rs:
            counts[r["status"]] += 1
        ok = sum(1 for r in rs if r["status"] == "ok" and r["valid"])
        low, high = stats.wilson(ok, len(rs))
        uncovered = [r["uncovered_reachable_m2"] for r in rs
                     if r["status"] == "partial" and math.isfinite(r["uncovered_reachable_m2"])]
        # What an ok run still leaves of R (slivers a round tool's finite path cannot reach): the
        # least coverage_reachable among the valid ok runs.
        ok_coverage = [value(r, "coverage_reachable") for r in rs if r["status"] == "ok" and r["valid"]]
        ok_coverage = [v for v in ok_coverage if math.isfinite(v)]
        return {"runs": len(rs), "counts": counts, "ok": ok, "rate": ok / len(rs) if rs else math.nan,
                "low": low, "high": high,
                "partial_uncovered_median": float(np.median(uncovered)) if uncovered else math.nan,
                "ok_coverage_min": min(ok_coverage) if ok_coverage else math.nan}

    # --- summaries ----------------------------------------------------------------------------
    def summary(self, column, dataset, metric):
        v = self.values(column, dataset, metric)
        if not v:
            return {"n": 0, "median": math.nan, "q1": math.nan, "q3": math.nan}
        q1, med, q3 = np.percentile(v, [25, 50, 75])
        return {"n": len(v), "median": float(med), "q1": float(q1), "q3": float(q3)}

    # --- failures --------------------------------------------------------------------------
    def outcome(self, column, pairing, metric):
        """A column's outcome on one wall for ranking and testing: its value (a usable run with a
        value), FAILED (a run there without a valid path: timeout, crash, error, memory_limit,
        invalid_output, metrics_error, no_reachable_area or invalid_input, or a path that fails the
        check), or None (no run there, or a usable run without that metric: missing, not failed)."""
        r = self._index.get((column, pairing))
        if r is None:
            return None
        if not usable(r):
            return FAILED
        v = value(r, metric)
        return v if math.isfinite(v) else None

    def contested(self, columns, dataset, metric):
        """The walls (pairing keys, sorted) of `dataset` where at least one of `columns` has a
        value: the walls a ranking or test of those columns is over. A wall where none has one
        tells nothing about them (every planner may rightly say no_reachable_area there)."""
        pairings = sorted({r["pairing"] for c in columns for r in self.runs_of(c, dataset)})
        return [p for p in pairings
                if any(isinstance(self.outcome(c, p, metric), float) for c in columns)]

    def worst(self, metric):
        """The value a failure stands for: worse than any value in the metric's direction."""
        return -self.specs[metric]["better"] * math.inf

    # --- paired comparisons -------------------------------------------------------------------
    def pairs(self, column, other, dataset, metric):
        """Values of `column` and `other` on the walls where both ran and at least one has a value;
        a run without a valid path there is the metric's worst value (``worst``: -inf for
        coverage, +inf for length), so it loses to every value on that wall."""
        a, b = [], []
        worst = self.worst(metric)
        for p in self.contested([column, other], dataset, metric):
            x, y = self.outcome(column, p, metric), self.outcome(other, p, metric)
            if x is None or y is None:
                continue
            a.append(worst if x is FAILED else x)
            b.append(worst if y is FAILED else y)
        return a, b

    def compare(self, column, other, dataset, metric):
        """stats.paired of `column` against `other` over their pairs (``pairs``); shared, not to be changed."""
        key = (column, other, dataset, metric)
        if key not in self._paired:
            self._paired[key] = stats.paired(self.specs[metric], *self.pairs(column, other, dataset, metric))
        return self._paired[key]

    def paired_table(self, dataset, metrics):
        """Every column against its tool's baseline, per metric; Holm across the whole table."""
        rows = []
        for tool in self.tools:
            base = self.baseline_column(tool)
            if base is None:
                continue
            for c in self.tool_columns(tool):
                if c == base:
                    continue
                for m in metrics:
                    res = dict(self.compare(c, base, dataset, m), column=c, baseline=base, metric=m)
                    rows.append(res)
        for row, adj in zip(rows, stats.holm([r["p"] if r["pairs"] else math.nan for r in rows])):
            row["p_holm"] = adj
        return rows

    # --- rankings -----------------------------------------------------------------------------
    def ranking(self, dataset, tool, metric):
        """``_ranking``, computed once; shared, not to be changed."""
        key = (dataset, tool, metric)
        if key not in self._ranking:
            self._ranking[key] = self._ranking_uncached(dataset, tool, metric)
        return self._ranking[key]

    def _ranking_uncached(self, dataset, tool, metric):
        """Columns of one tool ordered by their median over the walls where any of them has a
        value, a run without a valid path counted as worse than every value (docs/report.md,
        "Failures"): `median` is NaN and `failed` True when half or more of a column's walls
        failed, and such columns share the last rank. `valid` and `walls` count the column's
        values and its walls there. The leader is marked best only if Holm-adjusted Wilcoxon tests
        against every other column, failures counted as losses, say so (never for measured
        figures)."""
        spec = self.specs[metric]
        cols = self.tool_columns(tool)
        walls = self.contested(cols, dataset, metric)
        entries = []
        for c in cols:
            outs = [o for o in (self.outcome(c, p, metric) for p in walls) if o is not None]
            vals = [o for o in outs if o is not FAILED]
            e = {"column": c, "valid": len(vals), "walls": len(outs), "median": math.nan, "failed": False}
            if outs and spec["better"] != 0:
                # Oriented so that smaller is better and a failure is +inf; the median of an even
                # count is the mean of the middle two, a failure when either is one.
                oriented = sorted([-spec["better"] * v for v in vals] + [math.inf] * (len(outs) - len(vals)))
                k = len(oriented)
                mid = oriented[k // 2] if k % 2 else (oriented[k // 2 - 1] + oriented[k // 2]) / 2
                if math.isinf(mid):
                    e["failed"] = True
                else:
                    e["median"] = -spec["better"] * mid
            elif vals:
                e["median"] = float(np.median(vals))
            entries.append(e)

        def key(e):
            if not math.isnan(e["median"]):
                return (0, -spec["better"] * e["median"])
            return (1 if e["failed"] else 2, 0)
        ordered = sorted(entries, key=key)
        ranked = [e for e in ordered if not math.isnan(e["median"])]
        # Competition ranking: medians within the metric's tie band share a rank; columns whose
        # median is a failure share the rank after every column with a median.
        for e in ordered:
            e["best"] = False
            if math.isnan(e["median"]):
                e["rank"] = 1 + len(ranked) if e["failed"] else None
                continue
            e["rank"] = 1 + sum(1 for o in ranked if (o["median"] - e["median"]) * spec["better"] > 0
                                and not stats.tied(spec, o["median"], e["median"]))
        tests = self._leader_tests(ordered, dataset, metric)
        if tests:
            ordered[0]["best"] = all(t["pairs"] > 0 and t["p_holm"] < stats.ALPHA and t["wins"] > t["losses"]
                                     for t in tests)
        return ordered

    def _leader_tests(self, ordered, dataset, metric):
        """The ranking's leader against every other column (stats.paired, with `column`, `other`
        and `p_holm`: Holm-adjusted over these tests); none without a leader with a median."""
        if len(ordered) < 2 or math.isnan(ordered[0]["median"]) or metric not in self.compared:
            return []
        leader = ordered[0]["column"]
        tests = [dict(self.compare(leader, e["column"], dataset, metric), column=leader, other=e["column"])
                 for e in ordered[1:]]
        for t, p in zip(tests, stats.holm([t["p"] if t["pairs"] else math.nan for t in tests])):
            t["p_holm"] = p
        return tests

    def most_even(self, dataset, tool):
        """Which configuration of `tool` leaves the most even coat on `dataset`: the ranking of
        EVEN_COAT (the share of R within 10 % of the target or the mean), its leader (`best` when
        the paired tests say it is better than every other) and those tests (`tests`); each other
        configuration against the leader in COAT_SPREAD (`spread_tests`, Holm-adjusted over
        them, in the same order) and those whose coat varies less than the leader's by them
        (`less_varied`: a share of R within 10 % of a target, or of a mean that stops raise, can
        favour a patchier coat); the configurations that share the leader's rank (`top`), and the
        one of them whose coat varies less than every other configuration's, when one does
        (`least_varied`). None when no run there has a coat."""
        ranking = self.ranking(dataset, tool, EVEN_COAT)
        if not any(not math.isnan(e["median"]) for e in ranking):
            return None
        tests = self._leader_tests(ranking, dataset, EVEN_COAT)
        spread = []
        if tests and COAT_SPREAD in self.compared:
            leader = ranking[0]["column"]
            spread = [dict(self.compare(e["column"], leader, dataset, COAT_SPREAD), column=e["column"], other=leader)
                      for e in ranking[1:]]
            for t, p in zip(spread, stats.holm([t["p"] if t["pairs"] else math.nan for t in spread])):
                t["p_holm"] = p
        less = [t["column"] for t in spread if t["pairs"] > 0 and t["p_holm"] < stats.ALPHA and t["wins"] > t["losses"]]
        top = [e["column"] for e in ranking if e["rank"] == 1]
        # Among configurations that tie at the top of EVEN_COAT, one whose coat varies less than
        # every other's (COAT_SPREAD's leader, marked best by its own paired tests) breaks the tie.
        least_varied = None
        if len(top) > 1 and COAT_SPREAD in self.compared:
            first = self.ranking(dataset, tool, COAT_SPREAD)[0]
            if first["best"] and first["column"] in top:
                least_varied = first["column"]
        return {"ranking": ranking, "tests": tests, "spread_tests": spread, "less_varied": less, "top": top,
                "least_varied": least_varied}

    # --- Friedman -----------------------------------------------------------------------------
    def _value_table(self, dataset, tool, metric):
        """The tool's columns and one row per wall (pairing) of their values, NaN where a column
        has no usable run there."""
        cols = self.tool_columns(tool)
        pairings = sorted({r["pairing"] for c in cols for r in self.runs_of(c, dataset)})
        rows = []
        for p in pairings:
            rs = [self._index.get((c, p)) for c in cols]
            rows.append([value(r, metric) if r is not None and usable(r) else math.nan for r in rs])
        return cols, rows

    def friedman(self, dataset, tool, metric):
        """Friedman test over the walls where every column of the tool has a usable value."""
        key = (dataset, tool, metric)
        if key not in self._friedman:
            self._friedman[key] = self._friedman_uncached(dataset, tool, metric)
        return self._friedman[key]

    def _friedman_uncached(self, dataset, tool, metric):
        """Over the walls where every column ran and at least one has a value; a run without a
        valid path there is the metric's worst value, so failures share the worst rank."""
        cols = self.tool_columns(tool)
        if len(cols) < 3 or metric not in self.compared:
            return None
        worst = self.worst(metric)
        table = []
        for p in self.contested(cols, dataset, metric):
            row = [self.outcome(c, p, metric) for c in cols]
            if all(o is not None for o in row):
                table.append([worst if o is FAILED else o for o in row])
        if len(table) < 2:
            return None
        res = stats.friedman(self.specs[metric], table)
        res["columns"] = cols
        return res

    # --- costs for performance profiles -------------------------------------------------------
    def costs(self, dataset, tool, metric):
        """Problems x columns; inf where a column has no usable run. Zero costs (overlap) are
        shifted by the metric's absolute tie band so that ratios exist."""
        shift = self.specs[metric]["tie_absolute"] if metric == "overlap" else 0.0
        cols, rows = self._value_table(dataset, tool, metric)
        table = [[v + shift if math.isfinite(v) else math.inf for v in row] for row in rows]
        return cols, np.array(table, dtype=float).reshape(len(table), len(cols)), shift
