#!/usr/bin/env python3
"""The fast metrics engine against the exact judge, on the default experiment's walls.

For every family of experiments/default.yaml (the first --per-family walls of each, generated
exactly as the experiment generates them), every registered planner and every --tool-widths
value: plan the wall, score the plan with `coverbench metrics --judge exact`, and record how far
the fast engine's figures lie outside the exact judge's certified intervals. Prints the largest
differences per family and overall (the fast engine's measured error, quoted in docs/metrics.md)
and writes every row to --out (CSV).

  /usr/bin/python3 scripts/judge_compare.py --coverbench build/coverbench --per-family 3 \\
      --tool-widths 0.05 0.1 0.2 --out build/judge_compare.csv

--per-family 0 takes every wall of the experiment (1962 runs at one tool width: hours).
Exit status 1 when any validity verdict differs between the two judges.
"""
import argparse
import concurrent.futures
import csv
import json
import os
import subprocess
import sys
import tempfile

# The default experiment's datasets (experiments/default.yaml): family, count, seed.
DEFAULT_DATASETS = [("seed-cases", None, 1), ("residential", 80, 1), ("facade", 16, 1), ("gable", 40, 1),
                    ("stairwell", 40, 1), ("industrial", 30, 1), ("random", 50, 1), ("narrow", 40, 1),
                    ("stress", 2, 1), ("open", 20, 1)]
AREA_KEYS = ["coverage_reachable", "coverage_wall", "reachable_area", "paintable_area", "swept_area"]


def run(cmd):
    return subprocess.run(cmd, capture_output=True, text=True)


def planners(coverbench):
    out = run([coverbench, "planners"]).stdout
    return [line.split(":")[0] for line in out.splitlines() if line and not line[0].isspace()]


def walls(coverbench, per_family, families, work):
    found = []
    for family, count, seed in DEFAULT_DATASETS:
        if families and family not in families:
            continue
        folder = os.path.join(work, family)
        cmd = [coverbench, "dataset", "generate", "--family", family, "--seed", str(seed), "--out", folder]
        if count is not None:
            cmd += ["--count", str(count)]
        r = run(cmd)
        if r.returncode != 0:
            sys.exit(f"judge_compare: dataset generate {family}: {r.stderr.strip()}")
        names = sorted(n for n in os.listdir(folder) if n.endswith(".json") and n != "manifest.json")
        if per_family > 0:
            names = names[:per_family]
        found += [(family, os.path.join(folder, n)) for n in names]
    return found


def judge_one(coverbench, family, wall, planner, width, arc_vertices, work):
    stem = f"{os.path.basename(wall)[:-5]}-{planner}-{width}"
    plan = os.path.join(work, stem + ".plan.json")
    r = run([coverbench, "plan", "--wall", wall, "--planner", planner, "--tool-width", str(width), "--out", plan])
    row = {"family": family, "wall": os.path.basename(wall), "planner": planner, "tool_width": width}
    if not os.path.exists(plan):
        return dict(row, status="no plan: " + r.stderr.strip()[:200])
    r = run([coverbench, "metrics", "--wall", wall, "--plan", plan, "--judge", "exact",
             "--arc-vertices", str(arc_vertices), "--time-limit", "3600"])
    if r.returncode not in (0, 3):
        return dict(row, status="not judged: " + r.stderr.strip()[:200])
    doc = json.loads(r.stdout)
    fast, exact, diff = doc["metrics"], doc["exact_judge"], doc["fast_outside_exact"]
    row.update(status="judged", waypoints=fast["waypoints"], fast_valid=fast["valid"], exact_valid=exact["valid"],
               fast_violations=fast["violations"], exact_violations=exact["violations"],
               seconds=r.stderr.strip().split()[2] if r.stderr.startswith("exact judge:") else "")
    for k in AREA_KEYS:
        row["fast_" + k] = fast[k]
        row["exact_" + k + "_lower"], row["exact_" + k + "_upper"] = exact[k]
        row["outside_" + k] = diff[k]
    # Areas also relative to the area itself, the form the bounds are quoted in.
    for k in ["reachable_area", "paintable_area", "swept_area"]:
        row["relative_outside_" + k] = diff[k] / exact[k][1] if exact[k][1] > 0 else 0.0
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--coverbench", default="build/coverbench")
    ap.add_argument("--per-family", type=int, default=3, help="walls per family (0: all of the experiment's)")
    ap.add_argument("--tool-widths", type=float, nargs="+", default=[0.1])
    ap.add_argument("--planners", nargs="*", help="default: every registered planner")
    ap.add_argument("--families", nargs="*", help="default: every family of the default experiment")
    ap.add_argument("--arc-vertices", type=int, default=128)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--out", required=True, help="CSV of every comparison")
    a = ap.parse_args()
    coverbench = os.path.abspath(a.coverbench)
    with tempfile.TemporaryDirectory() as work:
        cases = [(f, w, p, s) for f, w in walls(coverbench, a.per_family, a.families, work)
                 for p in (a.planners or planners(coverbench)) for s in a.tool_widths]
        rows = []
        with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
            for row in pool.map(lambda c: judge_one(coverbench, *c, a.arc_vertices, work), cases):
                rows.append(row)
                print(f"[{len(rows)}/{len(cases)}] {row['family']} {row['wall']} {row['planner']} "
                      f"s={row['tool_width']}: {row['status']}", file=sys.stderr, flush=True)
    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    with open(a.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
    judged = [r for r in rows if r["status"] == "judged"]
    print(f"{len(judged)} of {len(rows)} paths judged (arc_vertices {a.arc_vertices}); rows in {a.out}")
    for r in rows:
        if r["status"] != "judged":
            print(f"  {r['family']} {r['wall']} {r['planner']} s={r['tool_width']}: {r['status']}")
    disagree = [r for r in judged if r["fast_valid"] != r["exact_valid"] or r["fast_violations"] != r["exact_violations"]]
    print(f"validity: {len(disagree)} paths where the verdicts or violation counts differ")
    for r in disagree:
        print(f"  {r['wall']} {r['planner']} s={r['tool_width']}: fast {r['fast_violations']}, exact {r['exact_violations']}")
    cols = ["outside_coverage_reachable", "outside_coverage_wall", "relative_outside_reachable_area",
            "relative_outside_paintable_area", "relative_outside_swept_area"]
    width_cols = ["coverage_reachable", "coverage_wall"]
    print("largest |fast - exact interval| (0: inside); interval widths for comparison")
    print("| family | paths | " + " | ".join(c.replace("relative_outside_", "rel. ").replace("outside_", "") for c in cols)
          + " | " + " | ".join("width " + c for c in width_cols) + " |")
    print("|---" * (2 + len(cols) + len(width_cols)) + "|")
    for family in [f for f, _, _ in DEFAULT_DATASETS] + ["all"]:
        sel = [r for r in judged if family in ("all", r["family"])]
        if not sel:
            continue
        worst = [max(abs(r[c]) for r in sel) for c in cols]
        widths = [max(r[f"exact_{c}_upper"] - r[f"exact_{c}_lower"] for r in sel) for c in width_cols]
        print(f"| {family} | {len(sel)} | " + " | ".join(f"{v:.2e}" for v in worst) + " | "
              + " | ".join(f"{v:.2e}" for v in widths) + " |")
    return 1 if disagree else 0


if __name__ == "__main__":
    sys.exit(main())
