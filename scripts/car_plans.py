#!/usr/bin/env python3
"""The sweep planners' plans for a car itself (car_plan: headland) against their smoothed
baselines (car_plan: smoothed), per family and planner (docs/vehicles.md, "Planning for a car"): the first walls of every family
(seed 3), a forward-only (Dubins) and a reversing (Reeds-Shepp) car, each path scored by
`coverbench plan` as its vehicle drives it. Prints one row per family, planner, car and car_plan: valid
paths, the median coverage_reachable (lowest in brackets), the median overlap and length_ratio,
and the statuses. Configurations are never pooled. For the forward-only car, the table also gives
the median of what such a car could paint at best on the same walls (`coverbench car-ceiling`:
from viable poses, and with what a head and a tail add in dead ends; docs/metrics.md).

  /usr/bin/python3 scripts/car_plans.py [--walls 5] [--turn-radius 0.3] [--families open,facade]
                                        [--planners zigzag,boustrophedon,trapezoidal,spiral]
                                        [--car-plans headland,smoothed] [--coverbench build/coverbench]
"""
import argparse
import concurrent.futures
import json
import os
import statistics
import subprocess
import tempfile

FAMILIES = ["open", "facade", "residential", "gable", "stairwell", "industrial", "random", "stress", "narrow"]
CARS = {"dubins": [], "rs": ["--reverse"]}
CAR_PLANS = ["headland", "smoothed"]
PLANNERS = ["zigzag", "boustrophedon", "trapezoidal", "spiral"]
# Far above the slowest plan here (stress walls, about 50 s alone): two plans at a time on a
# loaded machine must not be cut by `coverbench plan`'s default 60 s, or the table would measure
# the load.
TIME_LIMIT_S = 600


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--walls", type=int, default=5)
    ap.add_argument("--turn-radius", type=float, default=0.3)
    ap.add_argument("--families", default=",".join(FAMILIES))
    ap.add_argument("--planners", default=",".join(PLANNERS))
    ap.add_argument("--car-plans", default=",".join(CAR_PLANS))
    ap.add_argument("--coverbench", default="build/coverbench")
    args = ap.parse_args()
    families = args.families.split(",")
    planners = args.planners.split(",")
    car_plans = args.car_plans.split(",")
    with tempfile.TemporaryDirectory() as tmp:
        jobs = []
        for family in families:
            folder = os.path.join(tmp, family)
            subprocess.run([args.coverbench, "dataset", "generate", "--family", family, "--count", str(args.walls),
                            "--seed", "3", "--out", folder], check=True, capture_output=True)
            for wall in sorted(f for f in os.listdir(folder) if f.endswith(".json") and f != "manifest.json"):
                for planner in planners:
                    for car, flags in CARS.items():
                        for car_plan in car_plans:
                            jobs.append((family, planner, car, car_plan, os.path.join(folder, wall), flags))

        def run(job):
            family, planner, car, car_plan, wall, flags = job
            fd, out = tempfile.mkstemp(suffix=".json", dir=tmp)
            os.close(fd)
            # Exit 3 for partial plans: read the file.
            subprocess.run([args.coverbench, "plan", "--wall", wall, "--planner", planner, "--vehicle", "car",
                            "--turn-radius", str(args.turn_radius), "--param", "car_plan=" + car_plan, "--out", out,
                            "--time-limit", str(TIME_LIMIT_S)]
                           + flags, capture_output=True)
            with open(out, encoding="utf-8") as f:
                plan = json.load(f)
            m = plan.get("metrics") or {}
            return (family, planner, car, car_plan, bool(m.get("valid")), m.get("coverage_reachable", 0.0),
                    m.get("overlap", 0.0), m.get("length_ratio", 0.0), plan.get("status"))

        def ceiling(wall):
            out = subprocess.run([args.coverbench, "car-ceiling", "--wall", wall, "--turn-radius", str(args.turn_radius)],
                                 check=True, capture_output=True, text=True).stdout
            c = json.loads(out)
            return c["interior"], c["with_ends"]

        walls = sorted({(job[0], job[4]) for job in jobs})
        with concurrent.futures.ThreadPoolExecutor(2) as pool:
            results = list(pool.map(run, jobs))
            ceilings = dict(zip(walls, pool.map(lambda fw: ceiling(fw[1]), walls)))
    print(f"turn radius {args.turn_radius} m, s = 0.1 m, c = 0.02 m; the first {args.walls} walls of each family, seed 3\n")
    print("| family | planner | vehicle | car_plan | valid | median coverage_reachable (min) | median overlap | median length_ratio | statuses "
          "| ceiling: interior, with ends (median) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    def ceiling_text(family):
        values = [c for (f, _), c in ceilings.items() if f == family]
        return f"{statistics.median(v[0] for v in values):.3f}, {statistics.median(v[1] for v in values):.3f}"

    for family in families:
        for planner in planners:
            for car in CARS:
                for car_plan in car_plans:
                    rows = [r[4:] for r in results if r[:4] == (family, planner, car, car_plan)]
                    statuses = {}
                    for r in rows:
                        statuses[r[4]] = statuses.get(r[4], 0) + 1
                    print(f"| {family} | {planner} | {car} | {car_plan} | {sum(r[0] for r in rows)}/{len(rows)} | "
                          f"{statistics.median(r[1] for r in rows):.4f} ({min(r[1] for r in rows):.4f}) | "
                          f"{statistics.median(r[2] for r in rows):.4f} | {statistics.median(r[3] for r in rows):.3f} | "
                          f"{statuses} | {ceiling_text(family) if car == 'dubins' else ''} |")


if __name__ == "__main__":
    main()
