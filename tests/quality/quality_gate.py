"""The quality gate: what every planner configuration plans on a pinned mini-dataset, against the
committed golden file. Any change fails with a table of what moved and by how much.

  python3 tests/quality/quality_gate.py check  [--coverbench build/coverbench] [--work DIR]
  python3 tests/quality/quality_gate.py update [--coverbench build/coverbench] [--work DIR]

`check --save FILE` also writes what it measured (the golden file's format), for the history.

`update` rewrites tests/quality/golden.csv deliberately (commit it with the planner change, and
bump the planner's `version`: `check` names every planner whose output changed at the same
version). Metrics are compared exactly: the same code and inputs give the same bytes."""
import argparse
import csv
import io
import os
import shutil
import sqlite3
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, ".."))
import pinned_build  # noqa: E402  (tests/pinned_build.py)

GOLDEN = os.path.join(HERE, "golden.csv")
KEY = ["dataset", "wall", "planner"]
FIELDS = ["planner_version", "status", "valid", "coverage_reachable", "coverage_wall", "overlap", "length_total",
          "turns", "waypoints"]
NUMERIC = {"coverage_reachable", "coverage_wall", "overlap", "length_total", "turns", "waypoints"}


def measure(coverbench, work):
    """Runs the gate's experiment in `work` and returns its rows (dicts of KEY + FIELDS)."""
    os.makedirs(work, exist_ok=True)
    shutil.copy(os.path.join(HERE, "gate.yaml"), os.path.join(work, "gate.yaml"))
    run = subprocess.run([coverbench, "run", os.path.join(work, "gate.yaml"), "--no-report"],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if run.returncode != 0:
        sys.stderr.write(run.stderr)
        raise SystemExit(f"quality gate: the gate's experiment failed (exit code {run.returncode})")
    out = subprocess.run([coverbench, "runs", os.path.join(work, "out", "results.sqlite"), "--format", "csv"],
                         check=True, capture_output=True, text=True).stdout
    rows = [{k: r[k] for k in KEY + FIELDS} for r in csv.DictReader(io.StringIO(out))]
    return sorted(rows, key=lambda r: tuple(r[k] for k in KEY))


def build_of(work):
    """The compiler, build type and flags of the binary that ran the gate's experiment, as the
    cost probe prints them ("GNU 12.2.0 Release, flags '-O3 -DNDEBUG'")."""
    with sqlite3.connect(os.path.join(work, "out", "results.sqlite")) as db:
        compiler, build_type, flags = db.execute(
            "SELECT compiler, build_type, build_flags FROM experiments ORDER BY id DESC LIMIT 1").fetchone()
    return f"{compiler} {build_type}, flags '{flags.strip()}'"


def write(rows, path):
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, KEY + FIELDS, lineterminator="\n")
        w.writeheader()
        w.writerows(rows)


def read(path):
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def delta(field, old, new):
    if field not in NUMERIC or not old or not new:
        return ""
    a, b = float(old), float(new)
    d = b - a
    return f"{d:+.6g}" + (f" ({100 * d / abs(a):+.3g} %)" if a else "")


def compare(golden, current):
    """(table lines, planners changed at the same version). Empty table: nothing moved."""
    g = {tuple(r[k] for k in KEY): r for r in golden}
    c = {tuple(r[k] for k in KEY): r for r in current}
    lines, unbumped = [], set()
    for key in sorted(set(g) | set(c)):
        name = " / ".join(key)
        if key not in c:
            lines.append(f"| {name} | (run) | in golden | missing | |")
            continue
        if key not in g:
            lines.append(f"| {name} | (run) | missing | new | |")
            continue
        for f in FIELDS:
            if g[key][f] != c[key][f]:
                lines.append(f"| {name} | {f} | {g[key][f]} | {c[key][f]} | {delta(f, g[key][f], c[key][f])} |")
                if f != "planner_version" and g[key]["planner_version"] == c[key]["planner_version"]:
                    unbumped.add(key[2])
    return lines, sorted(unbumped)


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("mode", choices=["check", "update"])
    ap.add_argument("--coverbench", default=os.path.join(HERE, "..", "..", "build", "coverbench"))
    ap.add_argument("--work", default=None, help="folder for the gate's experiment (default: a temporary one)")
    ap.add_argument("--golden", default=GOLDEN)
    ap.add_argument("--save", default=None, help="check: also write the measured rows here (CSV, for bench/history.py)")
    args = ap.parse_args(argv)
    work = args.work or tempfile.mkdtemp(prefix="coverbench-quality-")
    try:
        if os.path.exists(os.path.join(work, "out")):
            shutil.rmtree(os.path.join(work, "out"))
        current = measure(args.coverbench, work)
        this_build = build_of(work)
    finally:
        if not args.work:
            shutil.rmtree(work, ignore_errors=True)
    if args.mode == "update":
        write(current, args.golden)
        print(f"wrote {args.golden}: {len(current)} runs")
        return 0
    if args.save:
        write(current, args.save)
    if this_build != pinned_build.pinned_build():
        return pinned_build.off_pinned_build("quality gate", this_build, pinned_build.pinned_build())
    lines, unbumped = compare(read(args.golden), current)
    if not lines:
        print(f"quality gate: {len(current)} runs as in {os.path.relpath(args.golden)}")
        return 0
    print("quality gate: planned output changed\n\n| wall / planner | field | golden | now | change |\n|---|---|---|---|---|")
    print("\n".join(lines))
    if unbumped:
        print(f"\nchanged at the same planner version: {', '.join(unbumped)} (bump `version` in its PlannerInfo)")
    print("\nIf the change is deliberate: python3 tests/quality/quality_gate.py update, and commit golden.csv "
          "with the planner change.")
    return 1


if __name__ == "__main__":
    sys.exit(main())
