"""Published results: each planner configuration beside each published method on the same walls
(report data key `published`, from a config's `published:` or `coverbench report --published`;
docs/report.md). The values are the user's; the statistics are stats.py's."""
import math
import sys

from . import stats
from . import tables as T
from .analysis import usable, value

TIME_UNIT = "s"  # metrics in seconds are the clock's (duration_s, turn_cost_s)
NOT_SOLVED = "not solved"
INSTANCE_TITLE = "Published results per instance"


class Published:
    """The published table of report data, matched to the experiment's walls by name."""

    def __init__(self, a, pub):
        self.a = a
        self.file, self.sha256 = pub["file"], pub["sha256"]
        self.clock, self.clock_matches = pub["clock"], bool(pub["clock_matches"])
        names = {}  # wall name -> the experiment's walls (content hashes) of that name
        for r in a.runs:
            names.setdefault(r["wall_name"], set()).add(r["wall"])
        self.run_of = {(r["column"], r["wall"]): r for r in a.runs}
        self.methods, metrics, instances = [], set(), []
        for instance, method, metric, _, _ in pub["rows"]:
            if method not in self.methods:
                self.methods.append(method)
            metrics.add(metric)
            if instance not in instances:
                instances.append(instance)
        self.metrics = [m for m in a.specs if m in metrics]  # the registry's order
        self.skipped = []  # rows of "Published values not compared": what, method, why
        for instance in sorted(instances):
            walls = names.get(instance, set())
            if not walls:
                self.skipped.append([instance, "all", "no wall of the experiment has this name"])
            elif len(walls) > 1:
                self.skipped.append([instance, "all", f"{len(walls)} walls of the experiment have this name"])
        gantry = any(isinstance(r.get("vehicle"), dict) and r["vehicle"].get("model") == "gantry" for r in a.runs)
        self.compared = []
        for m in self.metrics:
            if a.specs[m]["unit"] != TIME_UNIT:
                self.compared.append(m)
            elif gantry:
                self.skipped.append([m, "all", "a time: the gantry's lift and lower times are part of this experiment's "
                                               "durations and not of the published clock"])
            elif not self.clock_matches:
                theirs = self.clock if self.clock else "unknown"
                self.skipped.append([m, "all", f"a time measured with another clock (published: {theirs}; "
                                               f"this experiment: {a.experiment.get('motion') or 'the default'})"])
            else:
                self.compared.append(m)
        # (method, metric) -> [(instance, wall, value or None)], instances sorted by name
        self.values = {}
        for instance, method, metric, v, _ in sorted(pub["rows"], key=lambda row: (row[1], row[2], row[0])):
            walls = names.get(instance, set())
            if len(walls) == 1:
                self.values.setdefault((method, metric), []).append((instance, next(iter(walls)), v))
        self._cache = {}

    def pairs(self, column, method, metric):
        """(instance, ours, theirs) on every matched instance where `column` ran: a value, or None
        where that side did not solve it (ours: a run without a valid path; theirs: an empty
        value). A usable run without the metric (not measured) is left out."""
        out = []
        for instance, wall, theirs in self.values.get((method, metric), []):
            r = self.run_of.get((column, wall))
            if r is None:
                continue
            ours = None
            if usable(r):
                ours = value(r, metric)
                if not math.isfinite(ours):
                    continue
            out.append((instance, ours, None if theirs is None else float(theirs)))
        return out

    def comparison(self, column, method, metric):
        """Over the instances both solved: wins/ties/losses of ours in the metric's direction (a tie
        within its band), the geometric mean of ours / theirs with a 95 % t-interval on the log
        ratios, and the Wilcoxon signed-rank p of the untied log ratios; the ratios are over the
        pairs where both values are positive (`ratios`). Instances only one side solved and those
        neither solved are counted apart."""
        key = (column, method, metric)
        if key in self._cache:
            return self._cache[key]
        spec = self.a.specs[metric]
        pairs = self.pairs(column, method, metric)
        both = [(x, y) for _, x, y in pairs if x is not None and y is not None]
        out = {"instances": len(pairs), "both": len(both), "wins": 0, "ties": 0, "losses": 0,
               "only_ours": sum(1 for _, x, y in pairs if x is not None and y is None),
               "only_theirs": sum(1 for _, x, y in pairs if x is None and y is not None),
               "neither": sum(1 for _, x, y in pairs if x is None and y is None)}
        untied_logs, logs = [], []
        for x, y in both:
            tie = stats.tied(spec, x, y)
            if tie:
                out["ties"] += 1
            elif (x - y) * spec["better"] > 0:
                out["wins"] += 1
            else:
                out["losses"] += 1
            if x > 0 and y > 0:
                logs.append(log_ratio(x, y))
                if not tie:
                    untied_logs.append(log_ratio(x, y))
        out["ratios"] = len(logs)
        out["gmean"], out["low"], out["high"] = stats.geometric_mean_ci(logs)
        out["p"] = stats.signed_rank(untied_logs) if logs else math.nan
        self._cache[key] = out
        return out

    def rows(self):
        """Every (column, method, metric) compared, in config, file and registry order, with
        Holm-adjusted p-values across them."""
        keys = [(c, m, metric) for c in self.a.columns for m in self.methods for metric in self.compared
                if self.values.get((m, metric))]
        out = [dict(self.comparison(*k), column=k[0], method=k[1], metric=k[2]) for k in keys]
        for r, p in zip(out, stats.holm([r["p"] for r in out])):
            r["p_holm"] = p
        return out


def log_ratio(x, y):
    """ln(x / y) of two positive values, also where the quotient leaves the doubles' normal range
    (a published 1e308 or a subnormal 1e-320): then ln x - ln y."""
    r = x / y
    if sys.float_info.min <= r < math.inf:
        return math.log(r)
    return math.log(x) - math.log(y)


def of(a):
    """The analysis' Published, made once; None without published values."""
    if "published" not in a.data:
        return None
    if getattr(a, "_published", None) is None:
        a._published = Published(a, a.data["published"])
    return a._published


def ratio(v):
    return T.number(v, 4)


def source_note(p):
    return (f"Published values from {p.file} (sha256 {p.sha256[:12]}), measured with the clock "
            f"{p.clock or 'unknown'}; data given by the user.")


def summary_table(p):
    t = T.Table("Published results: each planner configuration against each published method",
                ["planner", "published", "metric", "instances", "both solved", "ours / theirs (geometric mean)",
                 "95 % interval", "win/tie/loss", "p (Holm)", "only ours solved", "only theirs solved", "neither"],
                note=source_note(p) + " Instances are the walls of the same name. Ratio = this experiment's value / "
                     "the published one, over the instances both solved with positive values; interval: t-interval "
                     "of the mean log ratio, exp taken. A win is better in the metric's direction beyond its tie band "
                     "(docs/metrics.md). p: two-sided Wilcoxon signed-rank of the untied log ratios, Holm-adjusted "
                     "across this table; * p < 0.05, ** p < 0.01, *** p < 0.001. Solved: ours, a valid path; "
                     "theirs, a value given.")
    for r in p.rows():
        t.add([r["column"], r["method"], r["metric"], str(r["instances"]), str(r["both"]), ratio(r["gmean"]),
               f"[{ratio(r['low'])}, {ratio(r['high'])}]" if not math.isnan(r["low"]) else "-",
               f"{r['wins']}/{r['ties']}/{r['losses']}", (T.pvalue(r["p_holm"]) + " " + T.stars(r["p_holm"])).strip(),
               str(r["only_ours"]), str(r["only_theirs"]), str(r["neither"])])
    return t


def instance_table(p):
    t = T.Table(INSTANCE_TITLE, ["planner", "published", "metric", "instance", "ours", "theirs",
                                                   "ours / theirs"],
                note="Every matched instance; ratio where both solved it with positive values.")
    for c in p.a.columns:
        for m in p.methods:
            for metric in p.compared:
                spec = p.a.specs[metric]
                for instance, x, y in p.pairs(c, m, metric):
                    r = x / y if x is not None and y is not None and x > 0 and y > 0 else math.nan
                    t.add([c, m, metric, instance, NOT_SOLVED if x is None else T.value(spec, x),
                           NOT_SOLVED if y is None else T.value(spec, y), ratio(r)])
    return t


def skipped_table(p):
    t = T.Table("Published values not compared", ["instance or metric", "published", "why"])
    for row in p.skipped:
        t.add(row)
    return t


def tables(a):
    """The published tables of the report (none without published values)."""
    p = of(a)
    if p is None:
        return []
    out = [summary_table(p), instance_table(p)]
    if p.skipped:
        out.append(skipped_table(p))
    return out
