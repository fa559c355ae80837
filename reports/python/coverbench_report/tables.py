"""The report's tables, independent of format, and their renderings: HTML, Markdown, CSV and
LaTeX (booktabs) share one layout, so a paper's table and the page say the same thing."""
import csv
import html
import statistics
import io
import math

from . import analysis as A

PERCENT_METRICS = ("coverage", "overlap", "passes")


def is_percent(spec):
    return spec["unit"] == "1" and spec["name"].startswith(PERCENT_METRICS)


def exact_number(v):
    """A number in as few digits as read back as it (0.5 and 0.5000000000000001 stay apart)."""
    short = f"{v:g}"
    return short if float(short) == v else repr(float(v))


def number(v, digits=3):
    """`digits` significant digits without exponent for everyday magnitudes."""
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "-"
    if math.isinf(v):
        return "inf" if v > 0 else "-inf"
    if v == 0:
        return "0"
    mag = math.floor(math.log10(abs(v)))
    if mag >= digits - 1:
        return f"{v:.0f}"
    if mag < -4:
        return f"{v:.{digits - 1}e}"
    return f"{v:.{digits - 1 - mag}f}"


def value(spec, v, with_unit=True):
    """A metric value with its unit: percentages with two decimals, bytes in MiB."""
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "-"
    unit = spec["unit"]
    if is_percent(spec):
        return f"{100 * v:.2f} %" if with_unit else f"{100 * v:.2f}"
    if unit == "B":
        return number(v / 1048576) + (" MiB" if with_unit else "")
    if unit in ("1", "segments") and spec["tie_absolute"] == 0.5:  # counts
        return f"{v:.0f}" if float(v).is_integer() else number(v)
    return number(v) + (f" {unit.replace('m2', 'm²')}" if with_unit and unit != "1" else "")


def difference(spec, v):
    """A paired difference: percentage points for percentages, else the metric's unit."""
    if v is None or math.isnan(v):
        return "-"
    if is_percent(spec):
        return f"{100 * v:+.2f} pp"
    s = value(spec, abs(v))
    return ("+" if v > 0 else "-" if v < 0 else "") + s if s != "0" else "0"


def unit_label(spec):
    if is_percent(spec):
        return "%"
    return {"B": "MiB", "1": "", "m2": "m²", "um": "µm"}.get(spec["unit"], spec["unit"])


def stars(p):
    if p is None or math.isnan(p):
        return ""
    return "***" if p < 0.001 else "**" if p < 0.01 else "*" if p < 0.05 else ""


def pvalue(p):
    if p is None or math.isnan(p):
        return "-"
    return "<1e-4" if p < 1e-4 else f"{p:.2g}" if p < 0.01 else f"{p:.2f}"


class Table:
    def __init__(self, title, header, note="", anchor=""):
        self.title, self.header, self.note, self.anchor = title, header, note, anchor
        self.rows = []   # lists of cells; a cell is text or (text, "best") for emphasis

    def add(self, row):
        self.rows.append(row)


def _text(cell):
    return cell[0] if isinstance(cell, tuple) else cell


def _best(cell):
    return isinstance(cell, tuple) and "best" in cell[1:]


def to_html(t):
    out = [f'<div class="table-wrap"><table{" id=" + chr(34) + html.escape(t.anchor) + chr(34) if t.anchor else ""}>',
           f"<caption>{html.escape(t.title)}</caption>", "<thead><tr>"]
    out += [f"<th>{html.escape(h)}</th>" for h in t.header]
    out.append("</tr></thead><tbody>")
    for row in t.rows:
        cells = []
        for i, c in enumerate(row):
            text = html.escape(_text(c))
            if _best(c):
                text = f"<strong>{text}</strong>"
            if i == 0:
                cells.append(f"<th scope=row>{text}</th>")
            else:  # words read from the left, numbers line up on the right
                cells.append(f'<td class="text">{text}</td>' if _text(c)[:1].isalpha() else f"<td>{text}</td>")
        out.append("<tr>" + "".join(cells) + "</tr>")
    out.append("</tbody></table></div>")
    if t.note:
        out.append(f'<p class="note">{html.escape(t.note)}</p>')
    return "\n".join(out)


def _md(text):
    text = " ".join(str(text).split())
    for ch in "\\`*_[]<>|&~$":
        text = text.replace(ch, "\\" + ch)
    return text


def to_markdown(t):
    out = [f"## {_md(t.title)}", ""]
    if t.note:
        out += [_md(t.note), ""]
    out.append("| " + " | ".join(_md(h) for h in t.header) + " |")
    out.append("|" + "|".join(["---"] + ["---:"] * (len(t.header) - 1)) + "|")
    for row in t.rows:
        out.append("| " + " | ".join(("**" + _md(_text(c)) + "**") if _best(c) else _md(_text(c)) for c in row) + " |")
    return "\n".join(out) + "\n\n"


_LATEX = {"\\": r"\textbackslash{}", "&": r"\&", "%": r"\%", "$": r"\$", "#": r"\#", "_": r"\_", "{": r"\{",
          "}": r"\}", "~": r"\textasciitilde{}", "^": r"\textasciicircum{}", "<": r"\textless{}",
          ">": r"\textgreater{}", "²": r"\textsuperscript{2}", "±": r"$\pm$", "★": r"$\star$"}


def latex_escape(text):
    return "".join(_LATEX.get(ch, ch) for ch in " ".join(str(text).split()))


def to_latex(t):
    wide = len(t.header) > 5
    env = "table*" if wide else "table"
    out = [f"% {latex_escape(t.title)}", f"\\begin{{{env}}}[htbp]", "\\centering", "\\footnotesize" if wide else "\\small",
           "\\setlength{\\tabcolsep}{3pt}",
           # shrunk to the column (or page, for table*) only when wider than it (graphicx)
           "\\resizebox{\\ifdim\\width>\\linewidth\\linewidth\\else\\width\\fi}{!}{%",
           "\\begin{tabular}{l" + "r" * (len(t.header) - 1) + "}", "\\toprule",
           " & ".join(latex_escape(h) for h in t.header) + " \\\\", "\\midrule"]
    for row in t.rows:
        out.append(" & ".join(("\\textbf{" + latex_escape(_text(c)) + "}") if _best(c) else latex_escape(_text(c))
                              for c in row) + " \\\\")
    out += ["\\bottomrule", "\\end{tabular}}", f"\\caption{{{latex_escape(t.title)}." +
            (f" {latex_escape(t.note)}" if t.note else "") + "}", f"\\end{{{env}}}", ""]
    return "\n".join(out) + "\n"


def to_csv_rows(t, writer):
    for row in t.rows:
        writer.writerow([t.title] + [_text(c) for c in row])


def render(tables, fmt, preamble=""):
    if fmt == "md":
        return preamble + "".join(to_markdown(t) for t in tables)
    if fmt == "latex":
        return preamble + "".join(to_latex(t) for t in tables)
    if fmt == "csv":
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        for t in tables:
            w.writerow(["table"] + list(t.header))
            to_csv_rows(t, w)
        return buf.getvalue()
    raise ValueError(fmt)


# --- the curated tables ---------------------------------------------------------------------------

def tool_label(a, tool):
    shape = "" if tool[2] == "disk" else f"{tool[2]} "
    depth = f", d={number(tool[3])} m" if tool[2] == "rectangle" else ""
    return "" if len(a.tools) == 1 else f" at {shape}s={number(tool[0])} m{depth}, c={number(tool[1])} m"


MEASURED_TITLE = "Measured on this machine"


def headline_table(a, dataset, tool, measured=False):
    """Rows: planner configurations; columns: headline metrics, each 'median (rank)'. The
    measured ones (plan time, memory) get their own table: a rerun measures them anew."""
    cols = a.tool_columns(tool)
    metrics = a.headline_measured if measured else a.headline_quality
    if measured:
        title = f"{MEASURED_TITLE}: {dataset}{tool_label(a, tool)}, median and rank"
        note = ("One sample per run (the median of its repetitions), measured anew by every rerun and on every "
                "machine: ranked, never tested, never marked best. Everything else is reproduced byte for byte.")
    else:
        title = f"{dataset}{tool_label(a, tool)}: headline metrics, median and rank"
        note = ("Median over the walls where any planner here has a valid run (ok or partial), a run without a "
                "valid path (timeout, crash, error, invalid output, ...) counted as worse than every value on its "
                "wall; 'failed' when half or more of a planner's walls failed, ranked last. valid/walls: the "
                "planner's valid runs and the walls it is ranked over. Rank 1 = best in the metric's direction, "
                "medians within its tie band share a rank. ★ and bold: the leader is better than every other "
                "planner by a Holm-adjusted Wilcoxon signed-rank test over the same walls, a failure losing to "
                "every value (p < 0.05); without ★ the leader is not separable from the rest.")
    t = Table(title, ["planner", "valid/walls"] + [f"{m} ({unit_label(a.specs[m])})" if unit_label(a.specs[m]) else m
                                          for m in metrics], note=note)
    ranks = {m: {e["column"]: e for e in a.ranking(dataset, tool, m)} for m in metrics}
    for c in cols:
        first = ranks[metrics[0]][c] if metrics else {"valid": 0, "walls": 0}
        row = [c, f"{first['valid']}/{first['walls']}"]
        for m in metrics:
            e = ranks[m][c]
            text = "failed" if e["failed"] else value(a.specs[m], e["median"], with_unit=False)
            if e["rank"] is not None:
                text += f" ({e['rank']})"
            row.append((text + " ★", "best") if e["best"] else text)
        t.add(row)
    return t


def even_coat_table(a, dataset, tool):
    """Which configuration leaves the most even coat (analysis.most_even): the verdict in the
    title, the leader against every other configuration below it, in the share of R within 10 %
    and in the coefficient of variation. None without a coat."""
    found = a.most_even(dataset, tool) if a.has_coat else None
    if found is None:
        return None
    ranking, tests, spread = found["ranking"], found["tests"], found["spread_tests"]
    spec, leader = a.specs[A.EVEN_COAT], ranking[0]
    reference = "the target" if a.coat_target else "the mean"
    name = leader["column"]
    if not tests:
        verdict = f"one configuration, {name}: nothing to compare"
    elif leader["best"] and not found["less_varied"]:
        verdict = f"the most even coat: {name}"
    elif leader["best"]:
        verdict = (f"most of R within 10 % of {reference}: {name}, but {', '.join(found['less_varied'])} "
                   f"{'varies' if len(found['less_varied']) == 1 else 'vary'} less ({A.COAT_SPREAD}): no one most even coat")
    elif found["least_varied"]:
        others = [c for c in found["top"] if c != found["least_varied"]]
        verdict = (f"the most even coat: {found['least_varied']} (tied with {', '.join(others)} in {A.EVEN_COAT}, "
                   f"its coat varies less than every other's in {A.COAT_SPREAD})")
    elif len(found["top"]) > 1:
        verdict = f"no configuration leaves a more even coat than every other ({', '.join(found['top'])} tie at the top)"
    else:
        verdict = f"no configuration leaves a more even coat than every other ({name} leads, not separably)"
    profile = f" The tool's flux profile: {'; '.join(a.profiles)}." if a.profiles else ""
    cv = a.specs.get(A.COAT_SPREAD)
    t = Table(f"{dataset}{tool_label(a, tool)}: {verdict}",
              ["planner", "vs", "pairs", "failed", f"{A.EVEN_COAT}, median", "vs, median", "median difference",
               "win/tie/loss", "p (Holm)", f"{A.COAT_SPREAD}, median", "vs, median", "vs less varied: p (Holm)"],
              note=f"{A.EVEN_COAT}: the share of the reachable area R whose coat is within 10 % of {reference}; "
                   f"{A.COAT_SPREAD}: the coat's standard deviation over its mean (docs/deposition.md). The "
                   f"configuration with the highest median {A.EVEN_COAT} leads; it leaves the most even coat (bold) only "
                   "when it is better than every other configuration of this tool on the same walls by a two-sided "
                   "Wilcoxon signed-rank test, Holm-adjusted over these rows, p < 0.05, with more wins than losses, and no "
                   f"other configuration's coat varies less than its by the same test in {A.COAT_SPREAD} (the last "
                   "column: the other against the leader; a share of R near a target, or near a mean that stops raise, "
                   "can favour a patchier coat). When several tie at the top (medians within the tie band), the one "
                   f"whose coat varies less than every other's ({A.COAT_SPREAD}, by the same tests) leaves the most even "
                   "coat. A run without a valid path loses to every value on its wall; a win is better beyond the "
                   "metric's tie band." + profile)
    medians = {e["column"]: e for e in ranking}
    spread_of = {r["column"]: r for r in spread}
    spread_median = {e["column"]: e for e in a.ranking(dataset, tool, A.COAT_SPREAD)} if cv else {}
    for r in tests:
        other = medians[r["other"]]
        s = spread_of.get(r["other"])
        lead_cv, other_cv = spread_median.get(name), spread_median.get(r["other"])
        t.add([(r["column"], "best") if leader["best"] and not found["less_varied"] else r["column"], r["other"],
               str(r["pairs"]), f"{r['failed']}/{r['baseline_failed']}", value(spec, leader["median"], False),
               "failed" if other["failed"] else value(spec, other["median"], False), difference(spec, r["median"]),
               f"{r['wins']}/{r['ties']}/{r['losses']}", (pvalue(r["p_holm"]) + " " + stars(r["p_holm"])).strip(),
               "-" if lead_cv is None else ("failed" if lead_cv["failed"] else value(cv, lead_cv["median"], False)),
               "-" if other_cv is None else ("failed" if other_cv["failed"] else value(cv, other_cv["median"], False)),
               "-" if s is None else ((pvalue(s["p_holm"]) + " " + stars(s["p_holm"])).strip()
                                      + (" (yes)" if r["other"] in found["less_varied"] else ""))])
    return t


def summary_table(a, dataset, tool, metrics, title):
    cols = a.tool_columns(tool)
    t = Table(f"{dataset}{tool_label(a, tool)}: {title}", ["metric"] + cols,
              note="Median [q1, q3] over valid runs (linear-interpolation quartiles). Definitions: docs/metrics.md.")
    for m in metrics:
        row = [m + (f" ({unit_label(a.specs[m])})" if unit_label(a.specs[m]) else "")]
        for c in cols:
            s = a.summary(c, dataset, m)
            spec = a.specs[m]
            row.append("-" if s["n"] == 0 else
                       f"{value(spec, s['median'], False)} [{value(spec, s['q1'], False)}, {value(spec, s['q3'], False)}]")
        t.add(row)
    return t


def outcome_table(a):
    statuses = a.statuses()
    t = Table("Run outcomes per planner configuration (all datasets)",
              ["planner", "runs"] + statuses + ["success (ok)", "95 % interval", "ok: least coverage of R",
                                                "partial: uncovered (m²)"],
              note="ok: a valid path that leaves no reachable part out (no piece of F skipped, no part its planner "
                   "could not reach). It is not 100 % of R: a round tool's finite path leaves slivers at the ends of "
                   "rows and in F's corners, and 'ok: least coverage of R' is the lowest coverage_reachable of the "
                   "column's ok runs (each planner declares the least it promises, min_coverage_reachable, and the "
                   "conformance card checks it on every wall). partial: a valid path that knowingly leaves reachable "
                   "parts out (median uncovered reachable area given); invalid_output: the path fails the exact "
                   "check; the rest have no path. Success rate = ok / runs with a Wilson 95 % interval.",
              anchor="outcomes-table")
    for c in a.columns:
        o = a.outcomes(c)
        t.add([c, str(o["runs"])] + [str(o["counts"][s]) for s in statuses] +
              [f"{100 * o['rate']:.1f} %" if o["runs"] else "-",
               f"[{100 * o['low']:.1f}, {100 * o['high']:.1f}] %" if o["runs"] else "-",
               f"{100 * o['ok_coverage_min']:.2f} %" if math.isfinite(o["ok_coverage_min"]) else "-",
               number(o["partial_uncovered_median"])])
    return t


def transit_table(a):
    """The sampling transit planners' routes per column: None when no run used one (docs/transits.md)."""
    columns = [c for c in a.columns if any(r.get("transit") for r in a.by_column[c])]
    if not columns:
        return None
    t = Table("Transit planners: routes against the visibility route (all datasets)",
              ["planner", "runs", "queries", "no route", "length / visibility, all routes", "median per run",
               "ms per query (measured)"],
              note="Every detour a planner asked for, answered by the column's sampling transit planner within its "
                   "iterations and compared with the visibility route for the same query (the shortest path through "
                   "nodes circumscribing F's round corners: a sampled route may be a little shorter). 'no route': "
                   "queries without an answer, whose parts the run left out (partial). Time: the sampling planner's "
                   "own, measured anew by every rerun. docs/transits.md.",
              anchor="transit-table")
    for c in columns:
        figs = [r["transit"]["figures"] for r in a.by_column[c] if r.get("transit")]
        queries = sum(f.get("transit_queries", 0) for f in figs)
        failures = sum(f.get("transit_failures", 0) for f in figs)
        length = sum(f.get("transit_length_m", 0) for f in figs)
        shortest = sum(f.get("transit_shortest_m", 0) for f in figs)
        ratios = sorted(f["transit_length_ratio"] for f in figs if f.get("transit_queries", 0) > f.get("transit_failures", 0))
        ms = sum(f.get("transit_ms", 0) for f in figs)
        t.add([c, str(len(figs)), f"{queries:.0f}", f"{failures:.0f}",
               f"{length / shortest:.4f}" if shortest > 0 else "-",
               f"{statistics.median(ratios):.4f}" if ratios else "-",
               f"{ms / queries:.2f}" if queries else "-"])
    return t


def replanning_tables(a, measured=False):
    """Per dataset, the repairs after surprise obstacles (docs/replanning.md): one row per planner
    column, fraction and repair. Empty when the experiment has no replanning. The repairs' times
    (`measured`) are a table of their own, placed with the other measured tables after everything
    a rerun reproduces byte for byte."""
    out = []
    for d in a.datasets:
        rows = []
        for c in a.columns:
            repairs = {}
            for r in a.by_column[c]:
                if r["dataset"] != d:
                    continue
                for p in r.get("replans", []):
                    repairs.setdefault((p["fraction"], p["repair"]), []).append(p)
            for (fraction, repair), ps in sorted(repairs.items()):
                rows.append((c, fraction, repair, ps))
        if not rows:
            continue
        if measured:
            t = Table(f"{d}: replanning, time per repair (measured)", ["planner", "at", "repair", "n", "ms median", "ms max"],
                      note="Measured anew by every rerun: the repair's wall-clock time (replan's includes its plan call).",
                      anchor="replanning-time-" + d)
            for c, fraction, repair, ps in rows:
                ms = [p["repair_ms"] for p in ps if p.get("repair_ms") is not None]
                t.add([c, exact_number(fraction), repair, str(len(ms)),
                       number(statistics.median(ms)) if ms else "-", number(max(ms)) if ms else "-"])
            out.append(t)
            continue
        t = Table(f"{d}: replanning after surprise obstacles",
                  ["planner", "at", "repair", "n", "ok/partial/failed/invalid", "obstacles",
                   "+length", "+unpainted", "coverage", "scratch"],
                  note="Medians over the walls (n repairs). At the fraction 'at' of each valid path's length, obstacles drawn from the run's seed appear "
                       "(placed / asked for); the rest of the path is repaired by planning again with the same planner "
                       "(replan: its moves that paint something new, linked from the robot) or by detours around them "
                       "(detour: the free stretches of blocked passes). 'invalid' counts repaired paths the metrics engine "
                       "rejects (the executed part on the old wall, the rest on the new). +length: "
                       "repaired path minus the original; +unpainted: reachable area left unpainted after the repair "
                       "minus what the original left (m², new wall); coverage: coverage_reachable of the repaired path "
                       "on the new wall; scratch: of the same planner's plan with the obstacles known. The repairs' times "
                       "are measured: their table is at the end. docs/replanning.md.",
                  anchor="replanning-" + d)
        for c, fraction, repair, ps in rows:
            def med(name):
                vals = [p["figures"][name] for p in ps if p["figures"].get(name) is not None]
                return statistics.median(vals) if vals else None
            counts = {s: sum(1 for p in ps if p["status"] == s) for s in ("ok", "partial", "failed", "invalid_output")}
            placed = sum(p["obstacles"] for p in ps)
            asked = sum(p["requested"] for p in ps)
            after, scratch = med("coverage_reachable"), med("scratch_coverage_reachable")
            t.add([c, exact_number(fraction), repair, str(len(ps)),
                   f"{counts['ok']} / {counts['partial']} / {counts['failed']} / {counts['invalid_output']}",
                   f"{placed}/{asked}",
                   number(med("added_length_m")) + " m" if med("added_length_m") is not None else "-",
                   number(med("uncovered_added_m2")) + " m²" if med("uncovered_added_m2") is not None else "-",
                   f"{100 * after:.2f} %" if after is not None else "-",
                   f"{100 * scratch:.2f} %" if scratch is not None else "-"])
        out.append(t)
    return out


def success_table(a):
    t = Table("Success rate (ok runs) per dataset, with Wilson 95 % interval", ["dataset"] + a.columns)
    for d in a.datasets:
        row = [d]
        for c in a.columns:
            o = a.outcomes(c, d)
            row.append("-" if not o["runs"] else
                       f"{o['ok']}/{o['runs']} [{100 * o['low']:.0f}, {100 * o['high']:.0f}] %")
        t.add(row)
    return t


def paired_table(a, dataset, metrics, title):
    rows = a.paired_table(dataset, metrics)
    t = Table(f"{dataset}: {title}",
              ["planner", "vs", "metric", "pairs", "failed", "median difference", "95 % interval", "win/tie/loss",
               "p (Holm)"],
              note="Over the walls where both ran and at least one has a valid run; a run without a valid path loses "
                   "to every value on its wall (failed: such pairs, planner/baseline). Difference = planner - baseline "
                   "over the pairs where both are valid; a win is better in the metric's direction beyond its tie "
                   "band (docs/metrics.md). Interval: percentile bootstrap of the median, 95 %, from its exact "
                   "bootstrap distribution (no resampling). p: two-sided Wilcoxon signed-rank over the untied pairs, a failure's difference ranked "
                   "above every other, Holm-adjusted across every comparison in this table; * p < 0.05, "
                   "** p < 0.01, *** p < 0.001.")
    for r in rows:
        spec = a.specs[r["metric"]]
        t.add([r["column"], r["baseline"], r["metric"], str(r["pairs"]), f"{r['failed']}/{r['baseline_failed']}",
               difference(spec, r["median"]),
               f"[{difference(spec, r['low'])}, {difference(spec, r['high'])}]" if r["both"] else "-",
               f"{r['wins']}/{r['ties']}/{r['losses']}", (pvalue(r["p_holm"]) + " " + stars(r["p_holm"])).strip()])
    return t


def friedman_table(a):
    t = Table("Friedman tests over the walls every planner of a tool group ran",
              ["dataset", "metric", "walls", "planners", "chi²", "p", "Nemenyi CD", "average ranks (1 = best)"],
              note="Friedman's test of equal ranks (scipy.stats.friedmanchisquare); critical difference of average "
                   "ranks by Nemenyi at alpha = 0.05 (Demsar 2006): two planners whose average ranks differ by more "
                   "are different. Walls where every planner ran and one has a valid run count; "
                   "runs without a valid path share the worst rank on their wall.")
    for d in a.datasets:
        for tool in a.tools:
            for m in a.headline_quality:
                f = a.friedman(d, tool, m)
                if f is None:
                    continue
                ranks = ", ".join(f"{c} {r:.2f}" for c, r in sorted(zip(f["columns"], f["ranks"]), key=lambda x: x[1]))
                t.add([d + tool_label(a, tool), m, str(f["blocks"]), str(f["k"]), number(f["statistic"]),
                       pvalue(f["p"]), number(f["cd"]), ranks])
    return t


def paper_tables(a):
    """The tables a paper takes: outcomes, per dataset the headline ranking, paired comparisons of
    the headline metrics, the Friedman tests, and published results when given."""
    tables = [outcome_table(a), success_table(a)]
    for d in a.datasets:
        for tool in a.tools:
            tables.append(headline_table(a, d, tool))
            coat = even_coat_table(a, d, tool)
            if coat is not None:
                tables.append(coat)
    headline_compared = [m for m in a.headline if m in a.compared]
    if len(a.columns) > 1:
        for d in a.datasets:
            tables.append(paired_table(a, d, headline_compared, "paired comparison with the baseline, headline metrics"))
        ft = friedman_table(a)
        if ft.rows:
            tables.append(ft)
    from . import published  # published imports this module
    tables += published.tables(a)  # none without published values
    tables += replanning_tables(a)
    for d in a.datasets:  # last: what a rerun does not reproduce
        for tool in a.tools:
            if a.headline_measured:
                tables.append(headline_table(a, d, tool, measured=True))
    tables += replanning_tables(a, measured=True)
    return tables
