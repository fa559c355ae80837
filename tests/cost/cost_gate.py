"""The cost gate: instructions each planner and the metrics engine execute on fixed walls, counted
by callgrind, against the committed baseline. Instruction counts of the same binary on the same
inputs repeat exactly (tests/cost/README.md quotes the spread), so the gate can be tight where a
wall-clock gate on this 2-core machine would swing by a third.

  python3 tests/cost/cost_gate.py check   [--probe build/bench/coverbench_cost_probe] [--cases REGEX]
  python3 tests/cost/cost_gate.py update  [--probe ...] [--cases REGEX]
  python3 tests/cost/cost_gate.py measure [--probe ...] [--cases REGEX] [--save counts.csv]

Every case of the probe (`--list`) is counted; about a minute on 2 cores (tests/cost/README.md).

`check` fails when a case's count rises more than THRESHOLD_PERCENT above the baseline, or when a
case is missing or new; falls are reported and pass (update the baseline to bank them). `update`
rewrites tests/cost/baseline.csv deliberately (commit it with the change that moved the counts)."""
import argparse
import concurrent.futures
import csv
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import pinned_build  # noqa: E402  (tests/pinned_build.py)

HERE = os.path.dirname(os.path.abspath(__file__))
BASELINE = os.path.join(HERE, "baseline.csv")
DEFAULT_PROBE = os.path.join(HERE, "..", "..", "build", "bench", "coverbench_cost_probe")
# The rise that fails the gate. Five repeated measurements of every case gave identical counts,
# and a checkout at another path differed by at most 0.0056 % (heap layout; README.md): 1 % is
# far above that noise and far below the wall-time noise (about 30 %) that makes timing gates
# useless here.
THRESHOLD_PERCENT = 1.0


def cases(probe):
    return subprocess.run([probe, "--list"], check=True, capture_output=True, text=True).stdout.split()


def identity(probe):
    """What the counts depend on besides the code: the build (compiler, type, flags) and valgrind."""
    build = subprocess.run([probe, "--identity"], check=True, capture_output=True, text=True).stdout.strip()
    valgrind = subprocess.run(["valgrind", "--version"], check=True, capture_output=True, text=True).stdout.strip()
    return f"{build}; {valgrind}"


def count(probe, case):
    """Instructions of the case's measured call, from callgrind's totals."""
    with tempfile.TemporaryDirectory(prefix="coverbench-cost-") as tmp:
        out = os.path.join(tmp, "callgrind.out")
        run = subprocess.run(["valgrind", "--tool=callgrind", "--collect-atstart=no", f"--callgrind-out-file={out}", probe, case],
                             capture_output=True, text=True, env=dict(os.environ, LD_BIND_NOW="1"))
        if run.returncode != 0:
            raise SystemExit(f"cost gate: {case}: the probe failed (exit code {run.returncode}):\n{run.stderr[-2000:]}")
        with open(out, encoding="utf-8") as f:
            totals = [line for line in f if line.startswith("totals:")]
        if not totals:
            raise SystemExit(f"cost gate: {case}: callgrind wrote no totals")
        return int(totals[-1].split()[1])


def measure(probe, names, jobs=2):
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        counts = list(pool.map(lambda n: count(probe, n), names))
    return dict(zip(names, counts))


def write(counts, ident, path):
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    with open(path, "w", newline="", encoding="utf-8") as f:
        f.write(f"# {ident}\n")
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["case", "instructions"])
        for name in sorted(counts):
            w.writerow([name, counts[name]])


def read(path):
    """(identity, {case: instructions})."""
    with open(path, newline="", encoding="utf-8") as f:
        first = f.readline()
        ident = first[2:].strip() if first.startswith("# ") else ""
        if not ident:
            f.seek(0)
        return ident, {r["case"]: int(r["instructions"]) for r in csv.DictReader(f)}


def compare(baseline, current, threshold=THRESHOLD_PERCENT):
    """(failing lines, improved lines) as Markdown table rows. Only cases in `current` are judged
    (a `--cases` run judges its own); main() adds the baseline's cases the probe no longer has."""
    fails, falls = [], []
    for name in sorted(current):
        if name not in baseline:
            fails.append(f"| {name} | new | {current[name]:,} | | |")
            continue
        old, new = baseline[name], current[name]
        change = 100.0 * (new - old) / old if old else (0.0 if new == old else float("inf"))
        row = f"| {name} | {old:,} | {new:,} | {new - old:+,} | {change:+.3f} % |"
        if change > threshold:
            fails.append(row)
        elif change < -threshold:
            falls.append(row)
    return fails, falls


HEADER = "| case | baseline | now | change | change % |\n|---|---|---|---|---|"


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("mode", choices=["check", "update", "measure"])
    ap.add_argument("--probe", default=DEFAULT_PROBE)
    ap.add_argument("--baseline", default=BASELINE)
    ap.add_argument("--cases", default=None, help="a regular expression: only the cases it matches")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--save", default=None, help="measure, check: write the counts here (the baseline's format)")
    args = ap.parse_args(argv)
    names = cases(args.probe)
    if args.cases:
        names = [n for n in names if re.search(args.cases, n)]
    ident = identity(args.probe)
    if args.mode == "check" and os.path.exists(args.baseline):
        base_build = read(args.baseline)[0].split("; ")[0]
        if base_build != ident.split("; ")[0]:  # another compiler or flags: nothing to measure against
            return pinned_build.off_pinned_build("cost gate", ident, read(args.baseline)[0])
    current = measure(args.probe, names, args.jobs)
    if args.save and args.mode != "update":
        write(current, ident, args.save)
    if args.mode == "measure":
        if not args.save:
            for n in names:
                print(f"{n},{current[n]}")
        return 0
    if args.mode == "update":
        _, old = read(args.baseline) if os.path.exists(args.baseline) else ("", {})
        if args.cases:
            old.update(current)  # a partial update keeps the other cases' counts
            current = old
        write(current, ident, args.baseline)
        print(f"wrote {args.baseline}: {len(current)} cases")
        return 0
    base_ident, baseline = read(args.baseline)
    if base_ident != ident:
        print(f"cost gate: the baseline was counted with\n  {base_ident}\nand this build is\n  {ident}\n"
              "Counts of different builds are not comparable: update the baseline on this build "
              "(python3 tests/cost/cost_gate.py update) and commit it.")
        return 1
    fails, falls = compare(baseline, current)
    if not args.cases:
        fails += [f"| {n} | {baseline[n]:,} | missing | | |" for n in sorted(set(baseline) - set(current))]
    if falls:
        print(f"cost gate: {len(falls)} case(s) fell by more than {THRESHOLD_PERCENT} % (bank them with `update`):\n\n{HEADER}")
        print("\n".join(falls) + "\n")
    if not fails:
        print(f"cost gate: {len(current)} cases within +{THRESHOLD_PERCENT} % of {os.path.relpath(args.baseline)}")
        return 0
    print(f"cost gate: {len(fails)} case(s) rose by more than {THRESHOLD_PERCENT} % or are new:\n\n{HEADER}")
    print("\n".join(fails))
    print("\nIf the rise is deliberate: python3 tests/cost/cost_gate.py update, and commit baseline.csv with the change.")
    return 1


if __name__ == "__main__":
    sys.exit(main())
