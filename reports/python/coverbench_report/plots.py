"""The report's figures, drawn with matplotlib (SVG, deterministic: fixed hash salt, no date)."""
import math
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.ticker import FuncFormatter, LogLocator, NullLocator  # noqa: E402

from . import analysis as A  # noqa: E402
from . import stats  # noqa: E402
from .tables import is_percent, number, unit_label  # noqa: E402

# Text stays text in the SVGs (svg.fonttype "none": the viewer draws it in DejaVu Sans or its own
# sans-serif): drawing every glyph as a path cost a third of a figure's time and size.
# Titles sit at the top of their axes (axes.titley 1: no axes here has ticks on top, which is what
# matplotlib measures every panel's ticks for, a sixth of the figures' time).
plt.rcParams.update({"svg.hashsalt": "coverbench", "svg.fonttype": "none", "font.family": "DejaVu Sans", "font.size": 9,
                     "axes.titley": 1.0,
                     "axes.titlesize": 9, "axes.spines.top": False, "axes.spines.right": False,
                     "figure.dpi": 100,
                     # Labels come from configs: "$...$" in one is text, never mathtext.
                     "text.parse_math": False})
PROFILE_METRICS = ["length_total", "overlap", "duration_s", "plan_time_ms"]
PARAMETER_METRICS = ["coverage_reachable", "overlap", "length_ratio", "plan_time_ms"]


# A cloud of every run's point is drawn as an image inside the SVG (rasterized=True) at this
# resolution: as vectors the thousands of points cost hundreds of KB (666 KB for the default
# experiment's scaling plot) and show nothing more.
RASTER_DPI = 150


def save(fig, path):
    try:
        fig.savefig(path, format="svg", dpi=RASTER_DPI, metadata={"Date": None, "Creator": None})
    except OSError as e:  # a failed flush names no file: name it
        raise OSError(e.errno, e.strerror, path) from e
    finally:
        plt.close(fig)


def fixed_layout(fig, left=0.65, right=0.15, bottom=0.55, top=0.5, wgap=0.65, hgap=0.6):
    """Margins and gaps between panels in inches, set at once (tight_layout drew every figure
    once more to measure it: a third to half of the report's figure time)."""
    width, height = fig.get_size_inches()
    nrow, ncol = fig.axes[0].get_subplotspec().get_gridspec().get_geometry()
    axes_w = (width - left - right - (ncol - 1) * wgap) / ncol
    axes_h = (height - top - bottom - (nrow - 1) * hgap) / nrow
    fig.subplots_adjust(left=left / width, right=1 - right / width, bottom=bottom / height, top=1 - top / height,
                        wspace=wgap / axes_w, hspace=hgap / axes_h)


def log_axis(axis, values, base=10):
    """A log scale on `axis` (ax.xaxis or ax.yaxis) with ticks labelled as plain numbers: 1, 2, 5
    times the powers of `base` when the values span under 3 of its powers, the powers alone
    otherwise, and no minor ticks. (matplotlib's default labels powers in mathtext, whose parser
    and the minor ticks were a fifth of the figures' time.)"""
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v) & (v > 0)]
    span = math.log(float(v.max()) / float(v.min()), base) if v.size else 0.0
    subs = (1.0,) if span >= 3 else ((1.0, 2.0, 5.0) if base == 10 else (1.0, 1.5))
    (axis.axes.set_xscale if axis is axis.axes.xaxis else axis.axes.set_yscale)("log", base=base)
    axis.set_major_locator(LogLocator(base=base, subs=subs))
    axis.set_minor_locator(NullLocator())
    axis.set_major_formatter(FuncFormatter(lambda x, _: f"{x:g}"))


def legend(ax, **options):
    """A legend only where something is labelled (matplotlib warns otherwise)."""
    if ax.get_legend_handles_labels()[0]:
        ax.legend(**options)


def scaled(spec, values):
    v = np.asarray(values, dtype=float)
    if is_percent(spec):
        return 100 * v
    if spec["unit"] == "B":
        return v / 1048576
    return v


def axis_label(spec):
    u = unit_label(spec)
    return spec["name"] + (f" ({u})" if u else "")


def short(label, width=22):
    return label if len(label) <= width else label[: width - 1] + "…"


def boxes(a, dataset, tool, path):
    """Box plots of every headline metric, one panel each, one box per planner configuration."""
    cols = a.tool_columns(tool)
    n = len(a.headline)
    ncol = 4
    nrow = math.ceil(n / ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(12, 2.9 * nrow), squeeze=False)
    for ax, m in zip(axes.flat, a.headline):
        spec = a.specs[m]
        data = [scaled(spec, a.values(c, dataset, m)) for c in cols]
        shown = [d if len(d) else np.array([np.nan]) for d in data]
        ax.boxplot(shown, vert=True, showfliers=True, flierprops={"markersize": 2})
        ax.set_xticks(range(1, len(cols) + 1), [short(c, 14) for c in cols], rotation=35, ha="right")
        ax.set_title(axis_label(spec) + (" ↑" if spec["better"] > 0 else " ↓"))
        if m in ("plan_time_ms", "peak_memory_bytes") and all(len(d) and np.all(d > 0) for d in data):
            log_axis(ax.yaxis, np.concatenate(data))
    for ax in list(axes.flat)[n:]:
        ax.axis("off")
    fig.suptitle(f"{dataset}: headline metrics over valid runs (↑ higher is better, ↓ lower is better)")
    fixed_layout(fig, bottom=0.95, top=0.55, wgap=0.6, hgap=1.35)
    save(fig, path)


def profiles(a, dataset, tool, path):
    """Dolan-More performance profiles; a failure (no valid path) counts as infinitely worse."""
    metrics = [m for m in PROFILE_METRICS if m in a.specs]
    fig, axes = plt.subplots(1, len(metrics), figsize=(12, 3.1), squeeze=False)
    for ax, m in zip(axes.flat, metrics):
        cols, costs, shift = a.costs(dataset, tool, m)
        if costs.size == 0:
            ax.axis("off")
            continue
        _, ratio = stats.performance_profile(costs, [1.0])
        finite = ratio[np.isfinite(ratio)]
        top = max(2.0, float(finite.max()) * 1.05) if finite.size else 2.0
        taus = np.unique(np.concatenate([[1.0], np.sort(finite), [top]]))
        rho, _ = stats.performance_profile(costs, taus)
        for j, c in enumerate(cols):
            ax.step(taus, rho[j], where="post", label=short(c))
        log_axis(ax.xaxis, taus, base=2)
        ax.set_ylim(0, 1.02)
        ax.set_xlabel("τ (within τ × best)")
        ax.set_title(m + (f" (+{number(shift)} to all)" if shift else ""))
    axes[0, 0].set_ylabel("share of walls")
    legend(axes[0, 0], fontsize=7, loc="lower right")
    fig.suptitle(f"{dataset}: performance profiles (Dolan-Moré); a failure never reaches any τ")
    fixed_layout(fig, left=0.6, bottom=0.5, top=0.55, wgap=0.45)
    save(fig, path)


def pareto(a, dataset, tool, path):
    """Coverage of the reachable area against length ratio: every valid run faint, each planner
    configuration's median bold, and the Pareto front of the medians (and of each planner's
    configurations when it has several)."""
    cols = a.tool_columns(tool)
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    medians = []
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for j, c in enumerate(cols):
        pts = [(A.value(r, "length_ratio"), A.value(r, "coverage_reachable")) for r in a.runs_of(c, dataset) if A.usable(r)]
        pts = [(x, 100 * y) for x, y in pts if math.isfinite(x) and math.isfinite(y)]
        color = colors[j % len(colors)]
        if pts:
            xs, ys = zip(*pts)
            ax.scatter(xs, ys, s=6, alpha=0.25, color=color, rasterized=True)  # as an image (RASTER_DPI)
            mx, my = float(np.median(xs)), float(np.median(ys))
            ax.scatter([mx], [my], s=50, color=color, edgecolor="black", label=short(c), zorder=3)
            medians.append((mx, my, a.config_of[c]))

    def front(points):
        best, out = -math.inf, []
        for x, y, _ in sorted(points, key=lambda p: (p[0], -p[1])):
            if y > best:
                out.append((x, y))
                best = y
        return out

    f = front(medians)
    if len(f) >= 1:
        ax.step([p[0] for p in f], [p[1] for p in f], where="post", color="black", lw=1, ls="--", label="Pareto front")
    planners = {}
    for x, y, cfg in medians:
        planners.setdefault(re.sub(r"\(.*", "", cfg), []).append((x, y, cfg))
    for name, pts in planners.items():
        if len(pts) > 1:
            pf = front(pts)
            ax.plot([p[0] for p in pf], [p[1] for p in pf], lw=0.8, color="grey")
    ax.set_xlabel("length_ratio (lower is better)")
    ax.set_ylabel("coverage_reachable (%), higher is better")
    ax.set_title(f"{dataset}: coverage against length")
    legend(ax, fontsize=7, loc="lower right")
    fixed_layout(fig, left=0.6, bottom=0.5, top=0.35)
    save(fig, path)


def has_cd_diagram(a, dataset, tool):
    return any(a.friedman(dataset, tool, m) is not None for m in a.headline_quality)


def cd_diagram(a, dataset, tool, path):
    """Critical-difference diagrams (Demsar 2006) of the headline metrics, one band each, all
    drawn in one axes (an axes each cost a tenth of a second in ticks it never shows); returns
    False when no Friedman test applies (fewer than 3 planners or 2 walls)."""
    results = [(m, a.friedman(dataset, tool, m)) for m in a.headline_quality]
    results = [(m, f) for m, f in results if f is not None]
    if not results:
        return False
    n = len(results)
    fig = plt.figure(figsize=(9, 1.35 * n))
    ax = fig.add_axes([0.1 / 9, 0.05 / (1.35 * n), 1 - 0.2 / 9, 1 - 0.55 / (1.35 * n)])
    band = 2.2  # a band's height in data units: from -1.2 to 1.0 about its axis line at 0.6
    gap = band * 0.3 / max(1.05 - 0.25 / n, 0.1)  # 0.3 inch between bands, for the title
    k_max = max(f["k"] for _, f in results)
    for i, (m, f) in enumerate(results):
        top = -i * (band + gap)

        def y(v, top=top):  # a band's own coordinate (-1.2 to 1.0) in the axes
            return top - 1.0 + v

        k = f["k"]
        order = sorted(zip(f["ranks"], f["columns"]))
        ax.hlines(y(0.6), 1, k, color="black", lw=1)
        ax.vlines(range(1, k + 1), y(0.55), y(0.65), color="black", lw=1)
        for r in range(1, k + 1):
            ax.text(r, y(0.75), str(r), ha="center", fontsize=7)
        ax.plot([rank for rank, _ in order], [y(0.6)] * k, "o", ms=4, color="black")
        for j, (rank, c) in enumerate(order):
            label_y = -0.25 - 0.28 * (j % 3)
            ax.plot([rank, rank], [y(0.6), y(label_y + 0.08)], color="grey", lw=0.6)
            ax.text(rank, y(label_y), short(c, 18), ha="center", va="top", fontsize=7)
        # Cliques: maximal runs of planners within one CD of each other get a bar.
        cd = f["cd"]
        ranks = [r for r, _ in order]
        bars = []
        for s_ in range(k):
            e = s_
            while e + 1 < k and ranks[e + 1] - ranks[s_] <= cd:
                e += 1
            if e > s_ and not any(s0 <= s_ and e <= e0 for s0, e0 in bars):
                bars.append((s_, e))
        for b, (s_, e) in enumerate(bars):
            ax.hlines(y(0.38 - 0.1 * b), ranks[s_] - 0.05, ranks[e] + 0.05, color="tab:red", lw=2.5)
        ax.hlines(y(0.95), 1, 1 + cd, color="tab:blue", lw=2)
        ax.text(1 + cd / 2, y(1.0), f"CD = {cd:.2f}", ha="center", fontsize=7, color="tab:blue")
        ax.annotate(f"{m}: Friedman p = {f['p']:.2g} over {f['blocks']} walls", (0.5, top), xytext=(0, 6),
                    textcoords="offset points", ha="left", va="bottom", fontsize=8)
    ax.set_xlim(0.5, k_max + 0.5)
    ax.set_ylim(-(n - 1) * (band + gap) - band, 0.0)
    ax.axis("off")
    fig.suptitle(f"{dataset}: average ranks (1 = best); red bars join planners not separable by Nemenyi")
    save(fig, path)
    return True


def scaling(a, tool, path):
    """Plan time against obstacle count and wall area, log-log, with fitted exponents (all
    datasets' walls together: scaling is about size, whatever the family)."""
    cols = a.tool_columns(tool)
    walls = a.data["walls"]
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.2))
    fits = []
    for ax, feature, label in ((axes[0], "obstacles", "obstacles on the wall"), (axes[1], "area", "wall area (m²)")):
        for c in cols:
            xs, ys = [], []
            for r in a.by_column[c]:
                if not A.usable(r):
                    continue
                x = walls.get(r["wall"], {}).get(feature)
                y = A.value(r, "plan_time_ms")
                if x and x > 0 and math.isfinite(y) and y > 0:
                    xs.append(float(x))
                    ys.append(y)
            if not xs:
                continue
            fit = stats.power_law(xs, ys)
            lab = short(c)
            if fit:
                lab += f": t ∝ x^{fit['exponent']:.2f} ± {fit['stderr']:.2f}"
                fits.append((c, feature, fit))
            sc = ax.scatter(xs, ys, s=6, alpha=0.35, label=lab, rasterized=True)  # as an image (RASTER_DPI)
            if fit:
                gx = np.logspace(np.log10(min(xs)), np.log10(max(xs)), 20)
                ax.plot(gx, 10 ** (fit["intercept"] + fit["exponent"] * np.log10(gx)), color=sc.get_facecolor()[0][:3])
        shown = [(x, y) for c in ax.collections for x, y in c.get_offsets()]
        if shown:
            log_axis(ax.xaxis, [x for x, _ in shown])
            log_axis(ax.yaxis, [y for _, y in shown])
        ax.set_xlabel(label + ("; walls without obstacles left out" if feature == "obstacles" else ""))
        ax.set_ylabel("plan time (ms)")
        legend(ax, fontsize=7, loc="upper left")
    fig.suptitle("Plan time scaling (least-squares fit on log-log axes, ± standard error)")
    fixed_layout(fig, left=0.65, bottom=0.5, top=0.45, wgap=0.7)
    save(fig, path)
    return fits


def median_bars(ax, points, label, min_points=1):
    """The median and interquartile range of each (x, values) with values, as error bars in x
    order; nothing when fewer than `min_points` have values."""
    pts = sorted(((x, np.percentile(v, [25, 50, 75])) for x, v in points if len(v)), key=lambda p: p[0])
    if len(pts) < min_points:
        return
    q = np.array([q for _, q in pts])
    ax.errorbar([x for x, _ in pts], q[:, 1], yerr=[q[:, 1] - q[:, 0], q[:, 2] - q[:, 1]], marker="o", ms=3,
                capsize=2, label=label)


def swept_parameters(a):
    """(planner, parameter, [(value, config label)]) for every numeric parameter that takes
    several values among one planner's configurations, plus the tool width when it does."""
    sweeps = []
    by_planner = {}
    for p in a.experiment["planners"]:
        by_planner.setdefault(p["planner"], []).append((p["params"], p["label"]))
    for planner, configs in by_planner.items():
        if len(configs) < 2:
            continue
        keys = sorted({k for params, _ in configs for k in params})
        for k in keys:
            vals = {params.get(k) for params, _ in configs}
            if len(vals) < 2:
                continue
            if not all(isinstance(params[k], (int, float)) and not isinstance(params[k], bool)
                       for params, _ in configs if k in params):
                continue
            points = sorted((float(params[k]), label) for params, label in configs if k in params)
            sweeps.append((planner, k, points))
    return sweeps


def parameter_plot(a, planner, param, points, path):
    """Headline metrics against one swept parameter: median and interquartile range per dataset,
    every other parameter of the configurations as they are (their labels say which)."""
    metrics = [m for m in PARAMETER_METRICS if m in a.specs]
    fig, axes = plt.subplots(1, len(metrics), figsize=(12, 3.1), squeeze=False)
    for ax, m in zip(axes.flat, metrics):
        spec = a.specs[m]
        for d in a.datasets:
            median_bars(ax, [(x, scaled(spec, a.values(c, d, m))) for x, label in points for c in a.columns
                             if a.config_of[c] == label], short(d, 16))
        ax.set_xlabel(param)
        ax.set_title(axis_label(spec))
    legend(axes[0, 0], fontsize=7)
    fig.suptitle(f"{planner}: metrics against {param} (median and interquartile range per dataset)")
    fixed_layout(fig, left=0.6, bottom=0.5, top=0.55, wgap=0.55)
    save(fig, path)


def tool_plot(a, path):
    """Headline metrics against the tool width, one line per planner configuration and dataset."""
    widths = sorted({t[0] for t in a.tools})
    metrics = [m for m in PARAMETER_METRICS if m in a.specs]
    fig, axes = plt.subplots(1, len(metrics), figsize=(12, 3.1), squeeze=False)
    configs = []
    for c in a.columns:
        if a.config_of[c] not in configs:
            configs.append(a.config_of[c])
    for ax, m in zip(axes.flat, metrics):
        spec = a.specs[m]
        for cfg in configs:
            for d in a.datasets:
                median_bars(ax, [(a.tool_of[c][0], scaled(spec, a.values(c, d, m))) for c in a.columns
                                 if a.config_of[c] == cfg], short(f"{cfg} / {d}", 26), min_points=2)
        ax.set_xlabel("tool width s (m)")
        ax.set_xticks(widths)
        ax.set_title(axis_label(spec))
    legend(axes[0, 0], fontsize=6)
    fig.suptitle("Metrics against the tool width (median and interquartile range)")
    fixed_layout(fig, left=0.6, bottom=0.5, top=0.55, wgap=0.55)
    save(fig, path)
