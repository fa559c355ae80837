"""An experiment's report: index.html with its figures, and the same tables as Markdown, CSV and
LaTeX for papers."""
import json
import multiprocessing
import os
import re
import shlex

from . import plots
from . import published as P
from . import tables as T
from .analysis import Analysis
from .page import esc, gallery_html, page
from .page import figure as page_figure

# Plays the gallery's paths back in place (copied into the report folder, so it works from disk).
PLAYER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "player.js")


def params_line(params):
    """A configuration's parameters (a JSON object) as "key=value, ..." (numbers as JSON writes
    them: the fewest digits that read back)."""
    return ", ".join(f"{k}={v if isinstance(v, str) else json.dumps(v)}" for k, v in params.items())


def tool_suffix(a, i):
    return "" if len(a.tools) == 1 else f"-t{i + 1}"


def write(path, text):
    try:
        with open(path, "w", encoding="utf-8", newline="\n") as f:
            f.write(text)
    except OSError as e:  # a failed write names no file: name it
        raise OSError(e.errno, e.strerror, path) from e


def vehicle_text(a):
    """' Vehicle: gantry (lift 1 s, lower 1 s).' when the runs name a vehicle (holonomic runs name none)."""
    named = []
    for r in a.runs:
        v = r.get("vehicle")
        if v:
            text = (f"car (turn radius {v['turn_radius']:g} m, {'Reeds-Shepp: reverses' if v['reverse'] else 'Dubins: forward only'})"
                    if v["model"] == "car" else f"{v['model']} (lift {v['lift_s']:g} s, lower {v['lower_s']:g} s)")
            if text not in named:
                named.append(text)
    if not named:
        return ""
    if any("vehicle" not in r for r in a.runs):
        named.append("holonomic")
    return " Vehicle: " + ", ".join(named) + "."


def transit_text(a):
    """' Transit planner: rrtstar (2000 iterations a query).' when the runs name one (visibility runs name none)."""
    named = []
    for r in sorted(a.runs, key=lambda r: (r.get("transit") or {}).get("planner", "")):
        t = r.get("transit")
        text = f"{t['planner']} ({t['iterations']} iterations a query)" if t else "visibility"
        if text not in named:
            named.append(text)
    if named in ([], ["visibility"]):
        return ""
    return (" Transit planner: " if len(named) == 1 else " Transit planners (one column each): ") + ", ".join(named) + "."


def replanning_text(a):
    """' Replanning: obstacles appear at 0.3, 0.7 of each path (section Replanning).' when runs were repaired."""
    fractions = sorted({p["fraction"] for r in a.runs for p in r.get("replans", [])})
    if not fractions:
        return ""
    return (" Replanning: obstacles appear at " + ", ".join(T.exact_number(f) for f in fractions) +
            " of each path's length (docs/replanning.md).")


def motion_text(a):
    """' Time model of duration_s: v 0.3 m/s, a 0.5 m/s2, stops at turns over 30 degrees.'"""
    m = a.experiment.get("motion")
    return f" Time model of duration_s: {m}." if m else ""


def profile_text(a):
    """' Flux profile of the tool (the coat): beta 2.5.' when the runs' tool has one, and how many
    runs have no coat because its raster would pass the cap (docs/deposition.md)."""
    if not a.profiles:
        return ""
    unscored = sum(1 for r in a.runs if "the coat's metrics are not scored" in r.get("reason", ""))
    missing = (f" The coat is not scored on {unscored} of {len(a.runs)} runs (a raster past its cap; each run's "
               "reason says why): the coat's metrics leave them out.") if unscored else ""
    return f" Flux profile of the tool (the coat): {'; '.join(a.profiles)}.{missing}"


def coat_html(table):
    return T.to_html(table) if table is not None else ""


def preamble(a, fmt):
    e = a.experiment
    runs = len(a.runs)
    line = (f"Experiment {e['name']}: {runs} runs, {len(a.datasets)} datasets, {len(a.columns)} planner "
            f"configurations, baseline {e['baseline']}, config sha256 {e['config_hash'][:12]}.{motion_text(a)}{profile_text(a)}{vehicle_text(a)}"
            f"{transit_text(a)}{replanning_text(a)}")
    if fmt == "md":
        return f"# {T._md('Experiment ' + e['name'])}\n\n{T._md(line)}\n\n"
    if fmt == "latex":
        return f"% {T.latex_escape(line)} Needs \\usepackage{{booktabs,graphicx}}.\n\n"
    return ""


def write_tables(a, folder, formats):
    tables = T.paper_tables(a)
    names = {"md": "report.md", "csv": "report.csv", "latex": "report.tex"}
    for fmt in formats:
        write(os.path.join(folder, names[fmt]), T.render(tables, fmt, preamble(a, fmt)))


_ANALYSIS = None  # shared with the figure workers (forked after it is set)
# CPU seconds of each figure kind on the default experiment, roughly (the order they are drawn in).
FIGURE_COST = {"boxes": 0.9, "cd_diagram": 0.3, "profiles": 0.3, "parameter_plot": 0.3, "tool_plot": 0.3,
               "scaling": 0.6, "pareto": 0.13}


def svg_size(path):
    """A matplotlib SVG's (width, height) in CSS pixels (it gives them in points, 72 an inch)."""
    with open(path, encoding="utf-8") as f:
        head = f.read(2000)
    m = re.search(r'<svg[^>]* width="([0-9.]+)pt" height="([0-9.]+)pt"', head)
    return (round(float(m.group(1)) * 96 / 72), round(float(m.group(2)) * 96 / 72)) if m else None


def _draw(job):
    """Draws one figure (the job's last argument is its file); returns its file and size."""
    name, args = job
    getattr(plots, name)(_ANALYSIS, *args)
    return args[-1], svg_size(args[-1])


class Drawing:
    """Draws the figures on every core while the caller goes on (matplotlib is single-threaded;
    the workers are forked, so they share what the analysis has computed so far); with one core,
    when waited for."""

    def __init__(self, a, jobs):
        global _ANALYSIS
        _ANALYSIS = a
        # The costliest kinds first, so that no worker is left with a box plot at the end.
        self.jobs = sorted(jobs, key=lambda j: -FIGURE_COST.get(j[0], 0))
        workers = min(len(jobs), os.cpu_count() or 1)
        self.pool = multiprocessing.get_context("fork").Pool(workers) if workers > 1 else None
        self.result = self.pool.map_async(_draw, self.jobs, chunksize=1) if self.pool else None

    def wait(self):
        if self.pool is None:
            return [_draw(j) for j in self.jobs]
        try:
            return self.result.get()
        finally:
            self.pool.close()
            self.pool.join()

    def stop(self):
        if self.pool is not None:
            self.pool.terminate()
            self.pool.join()


class Later:
    """A part of the page made after the figures have started drawing: tables while they draw,
    a figure's tag once it is drawn (its size known)."""

    def __init__(self, make, after_figures=False):
        self.make = make
        self.after_figures = after_figures

    def __str__(self):
        return self.make()


def made(parts, figures_drawn):
    """`parts` with what can be made by now made."""
    return [str(p) if isinstance(p, Later) and (figures_drawn or not p.after_figures) else p for p in parts]



def build(data, folder, formats=("html", "md", "csv", "latex")):
    a = Analysis(data)
    e = a.experiment
    if "html" not in formats:
        write_tables(a, folder, formats)
        return None
    figs = os.path.join(folder, "figures")
    os.makedirs(figs, exist_ok=True)

    def fig(name):
        return os.path.join(figs, name), "figures/" + name

    sizes = {}  # figure file -> its size, once drawn

    def figure(src, alt):
        return Later(lambda: page_figure(src, alt, sizes.get(os.path.join(folder, src))), after_figures=True)

    headline, paired, plots_html, appendix, jobs = [], [], [], [], []
    for i, d in enumerate(a.datasets):
        for ti, tool in enumerate(a.tools):
            stem = f"d{i + 1:02d}{tool_suffix(a, ti)}"
            label = d + T.tool_label(a, tool)
            headline.append(f"<h3>{esc(label)}</h3>")
            headline.append(Later(lambda d=d, tool=tool: T.to_html(T.headline_table(a, d, tool))))
            if a.has_coat:  # which planner leaves the most even coat, by paired tests
                headline.append(Later(lambda d=d, tool=tool: coat_html(T.even_coat_table(a, d, tool))))
            if a.headline_measured:
                headline.append(Later(lambda d=d, tool=tool: T.to_html(T.headline_table(a, d, tool, measured=True))))
            path, src = fig(stem + "-boxes.svg")
            jobs.append(("boxes", (d, tool, path)))
            headline.append(figure(src, f"{label}: box plots of the headline metrics"))
            plots_html.append(f"<h3>{esc(label)}</h3>")
            path, src = fig(stem + "-profiles.svg")
            jobs.append(("profiles", (d, tool, path)))
            plots_html.append(figure(src, f"{label}: performance profiles"))
            path, src = fig(stem + "-pareto.svg")
            jobs.append(("pareto", (d, tool, path)))
            plots_html.append(figure(src, f"{label}: coverage against length"))
            path, src = fig(stem + "-cd.svg")
            if plots.has_cd_diagram(a, d, tool):
                jobs.append(("cd_diagram", (d, tool, path)))
                paired.append(f"<h3>{esc(label)}: critical differences</h3>")
                paired.append(figure(src, f"{label}: critical-difference diagrams"))
            appendix.append(Later(lambda d=d, tool=tool: T.to_html(T.summary_table(a, d, tool, a.appendix, "the other metrics"))))
        if len(a.columns) > 1:
            paired.insert(len(paired), f"<h3>{esc(d)}</h3>")
            paired.append(Later(lambda d=d: T.to_html(T.paired_table(
                a, d, [m for m in a.headline if m in a.compared], "paired comparison with the baseline, headline metrics"))))
            rest = [m for m in a.compared if m not in a.headline]
            appendix.append(Later(lambda d=d, rest=rest: T.to_html(
                T.paired_table(a, d, rest, "paired comparison with the baseline, other metrics"))))
    if len(a.columns) > 1:
        ft = T.friedman_table(a)
        if ft.rows:
            paired.append("<h3>Friedman tests</h3>" + T.to_html(ft))
    else:
        paired.append("<p>One planner configuration: nothing to compare.</p>")

    plots_html.append("<h3>Scaling</h3>")
    for ti, tool in enumerate(a.tools):
        path, src = fig(f"scaling{tool_suffix(a, ti)}.svg")
        jobs.append(("scaling", (tool, path)))
        plots_html.append(figure(src, "plan time against obstacles and wall area"))
    plots_html.append("<h3>Swept parameters</h3>")
    sweeps = plots.swept_parameters(a)
    for k, (planner, param, points) in enumerate(sweeps):
        path, src = fig(f"param{k + 1:02d}.svg")
        jobs.append(("parameter_plot", (planner, param, points, path)))
        plots_html.append(figure(src, f"{planner}: metrics against {param}"))
    if len(a.tools) > 1 and len({t[0] for t in a.tools}) > 1:
        path, src = fig("tool-width.svg")
        jobs.append(("tool_plot", (path,)))
        plots_html.append(figure(src, "metrics against the tool width"))
    if not sweeps and len({t[0] for t in a.tools}) < 2:
        plots_html.append("<p>No planner parameter and no tool width was swept in this experiment.</p>")

    # The figures draw on every core while the tables are made here.
    drawing = Drawing(a, jobs)
    try:
        write_tables(a, folder, [f for f in formats if f != "html"])
        headline, paired, appendix = (made(parts, False) for parts in (headline, paired, appendix))
        sizes.update(drawing.wait())
    except BaseException:
        drawing.stop()
        raise
    headline, paired, plots_html, appendix = (made(parts, True) for parts in (headline, paired, plots_html, appendix))

    gallery = []
    for section in data["gallery"]:
        gallery.append(f"<h3>{esc(section['title'])}</h3>" + gallery_html(section))
    if not gallery:
        gallery.append("<p>No runs to picture.</p>")

    record = ['<div class="table-wrap"><table><tbody>']
    for k, v in e["facts"]:
        record.append(f'<tr><th scope="row">{esc(k)}</th><td style="text-align:left;white-space:normal">{esc(v)}</td></tr>')
    record.append(f'<tr><th scope="row">config sha256</th><td style="text-align:left">{esc(e["config_hash"])}</td></tr>')
    record.append("</tbody></table></div>")
    dt = T.Table("Datasets", ["label", "source", "walls", "content sha256"])
    for d in e["datasets"]:
        dt.add([d["label"], d["source"], str(d["walls"]), d["sha256"]])
    pt = T.Table("Planner configurations (resolved parameters, defaults included)", ["label", "planner", "parameters"])
    for p in e["planners"]:
        pt.add([p["label"], p["planner"], params_line(p["params"]) or "-"])
    record += [T.to_html(dt), T.to_html(pt), f"<h3>Config ({esc(e['config_path'])})</h3><pre>{esc(e['config_text'])}</pre>",
               "<h3>How to reproduce</h3><pre>" + esc(
                   "git checkout <the git revision above>\nbash scripts/setup.sh\n"
                   f"build/coverbench run {shlex.quote(e['config_path'] or 'CONFIG.yaml')}\n"
                   "build/coverbench report RESULTS.sqlite --format html --out REPORT\n") + "</pre>"
               "<p class=\"note\">The same config and build give the same metrics byte for byte; plan time and "
               "memory are measured anew. report_data.json in this folder holds every run this page was made "
               "from; report.md, report.csv and report.tex hold its tables.</p>"]

    outcomes = [T.to_html(T.outcome_table(a)), T.to_html(T.success_table(a))]
    transit = T.transit_table(a)
    if transit:
        outcomes.append(T.to_html(transit))
    subtitle = (f"<p>{len(a.runs)} runs: {len(a.datasets)} datasets, {len(a.columns)} planner configurations, "
                f"baseline <b>{esc(e['baseline'])}</b>.{esc(motion_text(a) + profile_text(a) + vehicle_text(a) + transit_text(a) + replanning_text(a))} Definitions of every metric: docs/metrics.md "
                f"(vehicle models: docs/vehicles.md). Tables for "
                f'papers: <a href="report.md">Markdown</a>, <a href="report.csv">CSV</a>, '
                f'<a href="report.tex">LaTeX</a>; every run: <a href="report_data.json">report_data.json</a>.</p>')
    replanning = [T.to_html(t) for t in T.replanning_tables(a) + T.replanning_tables(a, measured=True)]
    published = [f"<details><summary>{esc(t.title)} ({len(t.rows)} rows)</summary>{T.to_html(t)}</details>"
                 if t.title == P.INSTANCE_TITLE else T.to_html(t) for t in P.tables(a)]
    sections = [("headline", "Headline", "\n".join(headline)), ("outcomes", "Outcomes", "\n".join(outcomes)),
                *([("replanning", "Replanning", "\n".join(replanning))] if replanning else []),
                ("paired", "Paired statistics", "\n".join(paired)),
                *([("published", "Published results", "\n".join(published))] if published else []), ("plots", "Plots", "\n".join(plots_html)),
                ("galleries", "Galleries", "\n".join(gallery)), ("appendix", "Appendix", "\n".join(appendix)),
                ("record", "Reproducibility record", "\n".join(record))]
    scripts = []
    if any(p.get("playback") for section in data["gallery"] for w in section["walls"] for p in w["pictures"]):
        with open(PLAYER, encoding="utf-8") as f:
            write(os.path.join(folder, "player.js"), f.read())
        scripts.append("player.js")
    index = os.path.join(folder, "index.html")
    write(index, page(f"CoverBench: experiment {e['name']}", subtitle, sections, scripts))
    return index


def showcase(data, folder):
    """The showcase page: a summary table and every wall with every planner side by side."""
    t = T.Table(data["table"]["title"], data["table"]["header"])
    for row in data["table"]["rows"]:
        t.add(row)
    sections = [("summary", "Summary", T.to_html(t))]
    for section in data["gallery"]:
        sections.append(("walls", "Walls", gallery_html(section)))
    subtitle = f"<p>{esc(data['subtitle'])}</p>"
    index = os.path.join(folder, "index.html")
    write(index, page(data["title"], subtitle, sections))
    return index
