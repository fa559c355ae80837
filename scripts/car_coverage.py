#!/usr/bin/env python3
"""What smoothing for a car costs in coverage (docs/vehicles.md): every planner on the first walls of
every family (seed 3) and on the seed cases, planned for a holonomic tool, a Dubins car and a
Reeds-Shepp car of the given turn radius, each path scored by `coverbench plan` itself (as the
vehicle drives it). Prints, per family and vehicle, how many paths are valid and the range of the
planners' median coverage_reachable (one median per planner: planners are never pooled).

  /usr/bin/python3 scripts/car_coverage.py [--walls 3] [--turn-radius 0.3] [--coverbench build/coverbench]
"""
import argparse
import json
import os
import statistics
import subprocess
import tempfile

FAMILIES = ["residential", "facade", "gable", "stairwell", "industrial", "random", "narrow", "open", "stress"]
PLANNERS = ["zigzag", "spiral", "spanning-tree", "adaptive-resolution", "trapezoidal", "boustrophedon"]
VEHICLES = {"holonomic": [], "dubins": ["--vehicle", "car"], "reeds-shepp": ["--vehicle", "car", "--reverse"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--walls", type=int, default=3)
    ap.add_argument("--turn-radius", type=float, default=0.3)
    ap.add_argument("--coverbench", default="build/coverbench")
    args = ap.parse_args()
    results = {}  # (family, vehicle, planner) -> [(valid, coverage)]
    with tempfile.TemporaryDirectory() as tmp:
        for family in FAMILIES + ["seed-cases"]:
            folder = os.path.join(tmp, family)
            gen = [args.coverbench, "dataset", "generate", "--family", family, "--out", folder]
            if family != "seed-cases":
                gen += ["--count", str(args.walls), "--seed", "3"]
            subprocess.run(gen, check=True, capture_output=True)
            walls = sorted(f for f in os.listdir(folder) if f.endswith(".json") and f != "manifest.json")
            for wall in walls:
                for planner in PLANNERS:
                    for vehicle, flags in VEHICLES.items():
                        out = os.path.join(tmp, "plan.json")
                        cmd = [args.coverbench, "plan", "--wall", os.path.join(folder, wall), "--planner", planner,
                               "--out", out] + flags
                        if vehicle != "holonomic":
                            cmd += ["--turn-radius", str(args.turn_radius)]
                        subprocess.run(cmd, capture_output=True)  # exit 3 for partial plans: read the file
                        with open(out, encoding="utf-8") as f:
                            plan = json.load(f)
                        m = plan.get("metrics") or {}
                        results.setdefault((family, vehicle, planner), []).append(
                            (bool(m.get("valid")), m.get("coverage_reachable", 0.0)))
    print(f"turn radius {args.turn_radius} m; per cell: valid paths / paths, and the lowest and highest of the six "
          "planners' median coverage_reachable\n")
    print("| family | " + " | ".join(VEHICLES) + " |")
    print("|---|" + "---|" * len(VEHICLES))
    for family in FAMILIES + ["seed-cases"]:
        cells = []
        for vehicle in VEHICLES:
            runs = [r for p in PLANNERS for r in results[(family, vehicle, p)]]
            medians = [statistics.median(c for _, c in results[(family, vehicle, p)]) for p in PLANNERS]
            cells.append(f"{sum(v for v, _ in runs)}/{len(runs)} valid, {100 * min(medians):.1f} to {100 * max(medians):.1f} %")
        print(f"| {family} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
