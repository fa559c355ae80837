#!/usr/bin/env python3
"""Compares the runs of two result databases of one experiment run by two builds, run by run.

    python3 scripts/compare_results.py BEFORE.sqlite AFTER.sqlite [--metric NAME ...]

Runs are paired by their base key (wall, planner configuration, tool, seed and options: what a
run asks, not the code that answered). For each planner it prints the runs paired, how many
changed status, the median of each chosen metric before and after, and the largest change of
every metric over the paired runs, so a change meant to move some metrics (waypoints, turns) can
be read against the ones it must leave alone (coverage, overlap, length).
"""
import argparse
import sqlite3
import statistics
import sys


def load(path):
    db = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
    runs = {}
    for base, planner, status in db.execute(
        "SELECT r.base_key, c.planner, r.status FROM runs r JOIN planner_configs c ON c.id = r.config_id"
    ):
        runs[base] = {"planner": planner, "status": status, "metrics": {}}
    keys = dict(db.execute("SELECT key, base_key FROM runs"))
    for key, name, value in db.execute("SELECT run_key, name, value FROM metrics"):
        runs[keys[key]]["metrics"][name] = value
    return runs


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("before")
    parser.add_argument("after")
    parser.add_argument("--metric", action="append", default=None,
                        help="metrics whose medians are printed (default: waypoints, turns, duration_s)")
    args = parser.parse_args()
    medians = args.metric or ["waypoints", "turns", "duration_s"]
    before, after = load(args.before), load(args.after)
    paired = sorted(set(before) & set(after))
    if not paired:
        sys.exit(f"{args.after}: runs: none pairs with a run of {args.before} (not the same experiment?)")
    print(f"{len(paired)} runs paired ({len(before)} before, {len(after)} after)")
    planners = sorted({before[k]["planner"] for k in paired})
    for planner in planners:
        keys = [k for k in paired if before[k]["planner"] == planner]
        moved = sum(before[k]["status"] != after[k]["status"] for k in keys)
        line = [f"{planner}: {len(keys)} runs, {moved} changed status"]
        for name in medians:
            b = [before[k]["metrics"][name] for k in keys if before[k]["metrics"].get(name) is not None]
            a = [after[k]["metrics"][name] for k in keys if after[k]["metrics"].get(name) is not None]
            if b and a:
                line.append(f"median {name} {statistics.median(b):.6g} -> {statistics.median(a):.6g}")
        print("; ".join(line))
    print("largest change of each metric over the paired runs (absolute; relative to the value before):")
    names = sorted({n for k in paired for n in before[k]["metrics"]})
    for name in names:
        worst, worst_rel, where = 0.0, 0.0, None
        for k in paired:
            b, a = before[k]["metrics"].get(name), after[k]["metrics"].get(name)
            if b is None or a is None:
                continue
            d = abs(a - b)
            if d > worst:
                worst, where = d, k
            if b != 0:
                worst_rel = max(worst_rel, d / abs(b))
        planner = before[where]["planner"] if where else "-"
        print(f"  {name:22s} {worst:.3g} ({worst_rel:.3g} relative; largest in a {planner} run)")


if __name__ == "__main__":
    main()
