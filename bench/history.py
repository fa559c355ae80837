"""The gates' history: each CI run appends what the cost gate counted and what the quality gate
measured to a JSON Lines file keyed by revision (a rerun of a revision replaces its line), and
`plot` draws it per planner and per wall, marking the first revision where each series moved.

  python3 bench/history.py append --history FILE --revision REV [--cost counts.csv] [--quality quality.csv]
  python3 bench/history.py plot   --history FILE --out DIR

counts.csv: `cost_gate.py check --save`; quality.csv: `quality_gate.py check --save`. Lines are in
the order revisions were appended (CI order), which is commit order on one branch.
`plot` writes DIR/cost_PLANNER.svg (instructions per wall, as % change from the first revision),
DIR/quality_PLANNER.svg (coverage, overlap, and length as % change, per wall) and DIR/first_changes.md (every
series' first move: the revision that moved it, before and after). A count moves when it changes
by more than 1 % (the cost gate's threshold); a quality metric at any change."""
import argparse
import csv
import json
import os
import sys

QUALITY_METRICS = ["coverage_reachable", "overlap", "length_total"]
# A cost series moves when its count changes by more than the cost gate's threshold (1 %): counts
# of the same code differ by a few dozen instructions between checkouts at different paths.
COST_TOLERANCE = 0.01


def read_history(path):
    if not os.path.exists(path):
        return []
    with open(path, encoding="utf-8") as f:
        return [json.loads(line) for line in f if line.strip()]


def read_counts(path):
    with open(path, newline="", encoding="utf-8") as f:
        lines = [line for line in f if not line.startswith("#")]
    return {r["case"]: int(r["instructions"]) for r in csv.DictReader(lines)}


def read_quality(path):
    """{"wall/planner": {metric: value}} (the dataset is part of the wall's name)."""
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    out = {}
    for r in rows:
        values = {m: float(r[m]) for m in QUALITY_METRICS if r.get(m) not in (None, "")}
        values["status"] = r["status"]
        out[f"{r['dataset']}:{r['wall']}/{r['planner']}"] = values
    return out


def append(history, revision, cost=None, quality=None):
    entries = [e for e in read_history(history) if e["revision"] != revision]
    entry = {"revision": revision}
    if cost:
        entry["cost"] = read_counts(cost)
    if quality:
        entry["quality"] = read_quality(quality)
    entries.append(entry)
    os.makedirs(os.path.dirname(os.path.abspath(history)), exist_ok=True)
    with open(history, "w", encoding="utf-8") as f:
        for e in entries:
            f.write(json.dumps(e, sort_keys=True, separators=(",", ":")) + "\n")
    return len(entries)


def series(entries, section, metric=None):
    """{key: [value or None per entry]} for the cost counts or one quality metric."""
    keys = sorted({k for e in entries for k in e.get(section, {})})
    out = {}
    for k in keys:
        values = []
        for e in entries:
            v = e.get(section, {}).get(k)
            values.append(v if metric is None or v is None else v.get(metric))
        out[k] = values
    return out


def first_change(revisions, values, tolerance=0.0):
    """(revision, before, after) of the first move of a series, or None. A move is a change from
    the previous value by more than `tolerance` (relative; 0: any change)."""
    previous = None
    for rev, v in zip(revisions, values):
        if v is None:
            continue
        if previous is not None and abs(v - previous) > tolerance * abs(previous):
            return rev, previous, v
        previous = v
    return None


def relative(values):
    """Percent change of each value from the series' first value."""
    first = next((v for v in values if v is not None), None)
    return [None if v is None or not first else 100.0 * (v - first) / first for v in values]


def split_key(key):
    """"planner/wall" for cost cases, "dataset:wall/planner" for quality rows -> (planner, wall)."""
    head, _, tail = key.partition("/")
    return (tail, head) if ":" in head else (head, tail)


def plot(history, out):
    import matplotlib
    matplotlib.use("Agg")
    matplotlib.rcParams["svg.hashsalt"] = "coverbench-history"
    import matplotlib.pyplot as plt

    entries = read_history(history)
    if not entries:
        raise SystemExit(f"history: {history}: no entries")
    os.makedirs(out, exist_ok=True)
    full = [e["revision"] for e in entries]
    revisions = [r[:10] for r in full]
    x = list(range(len(entries)))
    changes = ["| series | first moved at | before | after |", "|---|---|---|---|"]

    def draw(name, panels):
        """panels: [(title, {key: values}, tolerance, transform)]: one figure per planner, one line
        per wall (a colour and line style of its own, kept across panels); the plot shows
        transform(values), the table of first moves the values themselves."""
        planners = sorted({split_key(k)[0] for _, s, _, _ in panels for k in s})
        palette = plt.get_cmap("tab20").colors
        for planner in planners:
            walls = sorted({split_key(k)[1] for _, s, _, _ in panels for k in s if split_key(k)[0] == planner})
            style = {w: (palette[i % 20], ["-", "--", ":"][i // 20 % 3]) for i, w in enumerate(walls)}
            fig, axes = plt.subplots(len(panels), 1, figsize=(11, 2.6 * len(panels) + 0.8), squeeze=False)
            for ax, (title, s, tolerance, transform) in zip(axes[:, 0], panels):
                for key in sorted(k for k in s if split_key(k)[0] == planner):
                    values = s[key]
                    shown = transform(values)
                    wall = split_key(key)[1]
                    color, dash = style[wall]
                    ax.plot(x, [float("nan") if v is None else v for v in shown], marker="o", ms=3, lw=1, color=color,
                            linestyle=dash, label=wall.split(":")[-1])
                    moved = first_change(full, values, tolerance)
                    if moved:
                        i = full.index(moved[0])
                        ax.plot([i], [shown[i]], marker="o", ms=9, mfc="none", mec="red", color="red", linestyle="")
                        changes.append(f"| {title.split(',')[0]}: {planner} / {wall} | {moved[0][:12]} | {moved[1]} | {moved[2]} |")
                ax.set_title(f"{planner}: {title}", fontsize=9, loc="left")
                ax.set_xticks(x, revisions, rotation=60, fontsize=7)
                ax.tick_params(axis="y", labelsize=7)
                ax.grid(alpha=0.3)
            axes[0, 0].legend(fontsize=6, loc="upper left", bbox_to_anchor=(1.01, 1.0), title="wall", title_fontsize=7)
            fig.text(0.99, 0.01, "red ring: the first revision where the series moved", ha="right", fontsize=7)
            fig.tight_layout()
            fig.savefig(os.path.join(out, f"{name}_{planner}.svg"), metadata={"Date": None})
            plt.close(fig)

    cost = series(entries, "cost")
    if cost:
        draw("cost", [("instructions (callgrind), % change from the first revision", cost, COST_TOLERANCE, relative)])
    if any("quality" in e for e in entries):
        same = lambda values: values  # noqa: E731
        draw("quality", [("coverage_reachable", series(entries, "quality", "coverage_reachable"), 0.0, same),
                         ("overlap", series(entries, "quality", "overlap"), 0.0, same),
                         ("length_total, % change from the first revision", series(entries, "quality", "length_total"),
                          0.0, relative)])
    with open(os.path.join(out, "first_changes.md"), "w", encoding="utf-8") as f:
        f.write("\n".join(changes) + "\n")
    return len(changes) - 2


def main(argv=None):
    ap = argparse.ArgumentParser()
    sub = ap.add_subparsers(dest="mode", required=True)
    a = sub.add_parser("append")
    a.add_argument("--history", required=True)
    a.add_argument("--revision", required=True)
    a.add_argument("--cost")
    a.add_argument("--quality")
    p = sub.add_parser("plot")
    p.add_argument("--history", required=True)
    p.add_argument("--out", required=True)
    args = ap.parse_args(argv)
    if args.mode == "append":
        n = append(args.history, args.revision, args.cost, args.quality)
        print(f"history: {args.history}: {n} revisions")
    else:
        moved = plot(args.history, args.out)
        print(f"history: plots in {args.out}; {moved} series moved (first_changes.md)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
