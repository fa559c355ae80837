"""The gates' history: each CI run appends what the cost gate counted and what the quality gate
measured to a JSON Lines file keyed by revision (a rerun of a revision replaces its line), and
`plot` draws it per planner and per wall, marking the first revision where each series moved.

  python3 bench/history.py append --history FILE --revision REV [--cost counts.csv] [--quality quality.csv]
  python3 bench/history.py plot   --history FILE --out DIR

counts.csv: `cost_gate.py check --save`; quality.csv: `quality_gate.py check --save`. Lines are in
the order revisions were appended (CI order), which is commit order on one branch.
`plot` writes DIR/cost_PLANNER.svg (instructions per wall), DIR/quality_PLANNER.svg (coverage,
overlap, length per wall) and DIR/first_changes.md (every series' first move, the revision that
moved it and by how much)."""
import argparse
import csv
import json
import os
import sys

QUALITY_METRICS = ["coverage_reachable", "overlap", "length_total"]


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


def first_change(revisions, values):
    """(revision, before, after) of the first move of a series, or None."""
    previous = None
    for rev, v in zip(revisions, values):
        if v is None:
            continue
        if previous is not None and v != previous:
            return rev, previous, v
        previous = v
    return None


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
        """panels: [(title, {key: values})], one figure per planner, one line per wall."""
        planners = sorted({split_key(k)[0] for _, s in panels for k in s})
        for planner in planners:
            fig, axes = plt.subplots(len(panels), 1, figsize=(9, 2.6 * len(panels) + 0.8), squeeze=False)
            for ax, (title, s) in zip(axes[:, 0], panels):
                for key in sorted(k for k in s if split_key(k)[0] == planner):
                    values = s[key]
                    wall = split_key(key)[1]
                    ax.plot(x, [float("nan") if v is None else v for v in values], marker="o", ms=3, lw=1, label=wall)
                    moved = first_change(full, values)
                    if moved:
                        i = full.index(moved[0])
                        ax.plot([i], [values[i]], marker="o", ms=9, mfc="none", mec="red")
                        changes.append(f"| {title}: {planner} / {wall} | {moved[0][:12]} | {moved[1]} | {moved[2]} |")
                ax.set_title(f"{planner}: {title}", fontsize=9, loc="left")
                ax.set_xticks(x, revisions, rotation=60, fontsize=7)
                ax.tick_params(axis="y", labelsize=7)
                ax.grid(alpha=0.3)
            axes[0, 0].legend(fontsize=6, ncol=3, loc="best")
            fig.text(0.99, 0.01, "red ring: the first revision where the series moved", ha="right", fontsize=7)
            fig.tight_layout()
            fig.savefig(os.path.join(out, f"{name}_{planner}.svg"), metadata={"Date": None})
            plt.close(fig)

    cost = series(entries, "cost")
    if cost:
        draw("cost", [("instructions (callgrind)", cost)])
    if any("quality" in e for e in entries):
        draw("quality", [(m, series(entries, "quality", m)) for m in QUALITY_METRICS])
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
