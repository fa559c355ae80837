"""Wall-time report, tracked but never gating: the base revision and this one built side by side,
their Google Benchmark programs timed interleaved in one job (A B, B A, ...), each benchmark in a
process of its own so its peak memory is its own. A change is reported as a change only when a
two-sided Mann-Whitney U test says so (p < ALPHA) and the medians differ by at least
MIN_EFFECT_PERCENT; everything else is "no change". p-values are Holm-adjusted across the
benchmarks of the report.

  python3 bench/walltime_report.py [--base REV] [--rounds 10] [--filter REGEX] [--out build-abab]

Writes OUT/walltime.md (for people) and OUT/walltime.json in github-action-benchmark's
`customSmallerIsBetter` format (a list of {name, unit, value, range, extra}; also read by
Bencher's JSON adapter), one entry per benchmark for time (ms) and one for peak memory (KiB).
The base is built in OUT/base (a git worktree; ccache makes it quick when most files are
unchanged). Without a base revision (a first commit) it says so and writes nothing."""
import argparse
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

from scipy import stats

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "reports", "python"))
from coverbench_report.stats import holm  # noqa: E402  (the report's Holm step-down)
ALPHA = 0.05
# Three runs of unchanged planners here (19 benchmarks each) moved medians by up to 8.2 % on an
# idle machine, once with a Holm-adjusted p of 0.025 (docs/ci.md): a change must be larger.
MIN_EFFECT_PERCENT = 10.0
# The default subset: every planner on two seed walls, the grid variants and the decomposition
# planners on the 200-opening wall: 19 benchmarks, about a minute for 10 rounds.
DEFAULT_FILTER = r"(seed_5x5_3obs|seed_10x10_5obs|bench_50x20_200rect)$"


def git(*args, cwd=ROOT):
    return subprocess.run(["git", *args], cwd=cwd, check=True, capture_output=True, text=True).stdout.strip()


def build_base(rev, out):
    """Builds `rev`'s benchmark program in OUT/base and returns its path (None if it has none)."""
    src = os.path.join(out, "base")
    if os.path.exists(src):
        subprocess.run(["git", "worktree", "remove", "--force", src], cwd=ROOT, capture_output=True)
        shutil.rmtree(src, ignore_errors=True)
    git("worktree", "add", "--detach", src, rev)
    if not os.path.exists(os.path.join(src, "bench", "planners_bench.cpp")):
        return None
    env = dict(os.environ, CCACHE_BASEDIR=os.path.dirname(ROOT))
    subprocess.run(["cmake", "-S", src, "-B", os.path.join(src, "build"), "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                    "-DCOVERBENCH_BUILD_TESTS=OFF"], check=True, stdout=subprocess.DEVNULL, env=env)
    subprocess.run(["cmake", "--build", os.path.join(src, "build"), "-j", "2", "--target", "coverbench_bench"],
                   check=True, stdout=subprocess.DEVNULL, env=env)
    return os.path.join(src, "build", "bench", "coverbench_bench")


def listed(bench):
    return subprocess.run([bench, "--benchmark_list_tests"], check=True, capture_output=True, text=True).stdout.split()


def exact_filter(name):
    """A Google Benchmark filter (a POSIX extended regular expression; its backslash escapes are
    refused) matching `name` alone: special characters go in bracket expressions."""
    def one(c):
        if c == "]":
            return "[]]"
        if c in "^\\":
            return "."  # not in bracket expressions' portable set; no benchmark name has them
        return f"[{c}]" if c in ".[()*+?$|{}" else c
    return "^" + "".join(one(c) for c in name) + "$"


def time_one(bench, name, min_time):
    """(real time in ms, peak resident memory in KiB) of one benchmark in its own process. The
    memory comes from GNU time, whose small process starts the benchmark: a child forked from this
    Python process would report Python's resident set as its own peak."""
    with tempfile.NamedTemporaryFile("r", prefix="coverbench-walltime-", suffix=".txt") as peak:
        run = subprocess.run(["/usr/bin/time", "-f", "%M", "-o", peak.name, bench, f"--benchmark_filter={exact_filter(name)}",
                              "--benchmark_format=json", f"--benchmark_min_time={min_time}"],
                             stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        if run.returncode != 0:
            raise SystemExit(f"walltime report: {bench} {name}: exit code {run.returncode}")
        peak_kib = int(peak.read().split()[-1])
    runs = json.loads(run.stdout)["benchmarks"] if run.stdout.strip() else []
    if len(runs) != 1:
        raise SystemExit(f"walltime report: {bench}: the filter {exact_filter(name)} ran {len(runs)} benchmarks, not 1")
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[runs[0]["time_unit"]]
    return runs[0]["real_time"] * scale, peak_kib


def interleave(base, head, names, rounds, min_time):
    """{name: {"base": [(ms, KiB)...], "head": [...]}}: every round times each benchmark on both
    sides, base first in even rounds and head first in odd ones (A B, B A, ...), so neither the
    machine's drift nor going first or second favours one side."""
    samples = {n: {"base": [], "head": []} for n in names}
    for r in range(rounds):
        for n in names:
            for side in (("base", "head") if r % 2 == 0 else ("head", "base")):
                samples[n][side].append(time_one(base if side == "base" else head, n, min_time))
    return samples


def verdict(base_ms, head_ms, p=None):
    """(change % of medians, p, verdict): a change needs both significance and size. `p` is the
    Holm-adjusted p-value when given (summarize adjusts across the report), else the test's own."""
    mb, mh = statistics.median(base_ms), statistics.median(head_ms)
    change = 100.0 * (mh - mb) / mb
    if p is None:
        p = mann_whitney(base_ms, head_ms)
    if p < ALPHA and abs(change) >= MIN_EFFECT_PERCENT:
        return change, p, "slower" if change > 0 else "faster"
    return change, p, "no change"


def mann_whitney(base_ms, head_ms):
    return float(stats.mannwhitneyu(base_ms, head_ms, alternative="two-sided").pvalue)


def summarize(samples):
    """One row per benchmark; p-values Holm-adjusted across all of them, so that with twenty
    benchmarks and no change, one of them is not called changed by chance."""
    times = {name: ([t for t, _ in s["base"]], [t for t, _ in s["head"]]) for name, s in samples.items()}
    names = list(samples)
    adjusted = dict(zip(names, holm([mann_whitney(*times[n]) for n in names])))
    rows = []
    for name, s in samples.items():
        base_ms, head_ms = times[name]
        change, p, v = verdict(base_ms, head_ms, adjusted[name])
        rows.append({"name": name, "base_ms": statistics.median(base_ms), "head_ms": statistics.median(head_ms),
                     "head_iqr_ms": iqr(head_ms), "change_percent": change, "p": p, "verdict": v,
                     "base_peak_kib": max(m for _, m in s["base"]), "head_peak_kib": max(m for _, m in s["head"]),
                     "n": len(head_ms)})
    return rows


def iqr(xs):
    q = statistics.quantiles(xs, n=4, method="inclusive")
    return q[2] - q[0]


def markdown(rows, base_rev, head_rev, rounds):
    lines = [f"# Wall time: {head_rev} against {base_rev}", "",
             f"{rounds} interleaved rounds of each benchmark (base first in even rounds, head first in odd ones), "
             "each run in its own process. A change "
             f"needs a two-sided Mann-Whitney U test's p, Holm-adjusted across the benchmarks below, under {ALPHA} "
             f"and a median change of at least {MIN_EFFECT_PERCENT:g} %; this report never fails a build. "
             "Peak memory: the largest resident set of the benchmark's processes.", "",
             "| benchmark | base median (ms) | head median (ms) | change | p (Holm) | verdict | base peak (MiB) | head peak (MiB) |",
             "|---|---:|---:|---:|---:|---|---:|---:|"]
    for r in rows:
        lines.append(f"| {r['name']} | {r['base_ms']:.3f} | {r['head_ms']:.3f} | {r['change_percent']:+.1f} % | "
                     f"{r['p']:.3f} | {r['verdict']} | {r['base_peak_kib'] / 1024:.1f} | {r['head_peak_kib'] / 1024:.1f} |")
    changed = [r for r in rows if r["verdict"] != "no change"]
    lines += ["", f"{len(changed)} of {len(rows)} benchmarks changed." if changed else f"No change in {len(rows)} benchmarks."]
    return "\n".join(lines) + "\n"


def dashboard_json(rows, base_rev):
    out = []
    for r in rows:
        out.append({"name": f"{r['name']} (time)", "unit": "ms", "value": round(r["head_ms"], 6),
                    "range": f"IQR {r['head_iqr_ms']:.4f}",
                    "extra": f"base {base_rev}: {r['base_ms']:.4f} ms; change {r['change_percent']:+.2f} %; "
                             f"Mann-Whitney p (Holm) {r['p']:.4f}; {r['verdict']}; n {r['n']}"})
        out.append({"name": f"{r['name']} (peak memory)", "unit": "KiB", "value": r["head_peak_kib"],
                    "extra": f"base {base_rev}: {r['base_peak_kib']} KiB"})
    return json.dumps(out, indent=1) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--base", default="HEAD~1", help="the revision to compare with (default: HEAD~1)")
    ap.add_argument("--base-bench", default=None, help="a built base benchmark program (skips building the base)")
    ap.add_argument("--head-bench", default=os.path.join(ROOT, "build", "bench", "coverbench_bench"))
    ap.add_argument("--rounds", type=int, default=10)
    ap.add_argument("--filter", default=DEFAULT_FILTER)
    ap.add_argument("--min-time", default="0.05", help="Google Benchmark's --benchmark_min_time per process")
    ap.add_argument("--out", default=os.path.join(ROOT, "build-abab"))
    args = ap.parse_args(argv)
    if args.rounds < 4:  # with 3 or fewer samples a side, no two-sided Mann-Whitney p reaches 0.05
        ap.error("--rounds must be at least 4")
    os.makedirs(args.out, exist_ok=True)
    head_rev = git("rev-parse", "--short=12", "HEAD")
    try:
        base_rev = git("rev-parse", "--short=12", args.base)
    except subprocess.CalledProcessError:
        print(f"walltime report: no revision {args.base} to compare with; nothing written")
        return 0
    base = args.base_bench or build_base(base_rev, args.out)
    if base is None:
        print(f"walltime report: {base_rev} has no benchmark program; nothing written")
        return 0
    names = sorted(set(listed(base)) & set(listed(args.head_bench)))
    names = [n for n in names if re.search(args.filter, n)]
    rows = summarize(interleave(base, args.head_bench, names, args.rounds, args.min_time))
    md = markdown(rows, base_rev, head_rev, args.rounds)
    with open(os.path.join(args.out, "walltime.md"), "w", encoding="utf-8") as f:
        f.write(md)
    with open(os.path.join(args.out, "walltime.json"), "w", encoding="utf-8") as f:
        f.write(dashboard_json(rows, base_rev))
    print(md)
    print(f"wrote {os.path.join(args.out, 'walltime.md')} and walltime.json")
    return 0


if __name__ == "__main__":
    sys.exit(main())
