#!/usr/bin/env bash
# Measures what docs/scaling.md quotes, on this machine: the default experiment's runs per second
# in one process and as a 4-task Slurm job array (on a single-node cluster brought up here by
# tests/slurm/cluster.sh), and the merge time of the default experiment split in 8 shards.
#
#   bash scripts/measure_scaling.sh [build/coverbench] [WORK_DIR]
#
# Needs root and about 10 minutes on 2 cores. Prints a Markdown table.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
coverbench=$(realpath "${1:-$root/build/coverbench}")
work=${2:-$(mktemp -d /tmp/coverbench-scaling.XXXXXX)}
mkdir -p "$work" && work=$(cd "$work" && pwd)
rm -rf "$work"/{cluster,single,array4,array8}
cluster="$work/cluster"
trap 'bash "$root/tests/slurm/cluster.sh" stop "$cluster"' EXIT
eval "$(bash "$root/tests/slurm/cluster.sh" start "$cluster")"

config() {  # the default experiment, its output in folder $1
  mkdir -p "$work/$1"
  sed 's|^output: .*|output: out|' "$root/experiments/default.yaml" > "$work/$1/default.yaml"
}
ms() { echo $(( $(date +%s%N) / 1000000 )); }
wait_jobs() {
  while [ -n "$(squeue -h -j "$1" 2>/dev/null)" ]; do sleep 0.5; done
}

config single
t0=$(ms)
"$coverbench" run "$work/single/default.yaml" --no-report > "$work/single.log" 2>/dev/null
single_ms=$(( $(ms) - t0 ))
runs=$(grep -oE '[0-9]+ runs \(' "$work/single.log" | head -n1 | grep -oE '^[0-9]+')

array() {  # $1: folder, $2: shards; prints the wall-clock from submission to the merge's end
  config "$1"
  cd "$work/$1"
  local t0 jobs
  t0=$(ms)
  "$coverbench" slurm default.yaml --shards "$2" --cpus-per-task 1 --time 60 --no-report --submit > submit.log
  jobs=$(awk '$1 == "array" || $1 == "merge" {print $2}' submit.log | paste -sd,)
  wait_jobs "$jobs"
  echo $(( $(ms) - t0 ))
}
array4_ms=$(array array4 4)
array8_ms=$(array array8 8)
merge4=$(grep -oE 'in [0-9.]+ s' "$work"/array4/out/slurm/logs/merge-*.out | head -n1)
merge8=$(grep -oE 'in [0-9.]+ s' "$work"/array8/out/slurm/logs/merge-*.out | head -n1)
for d in array4 array8; do
  /usr/bin/python3 "$root/tests/slurm/compare_results.py" "$work/single/out/results.sqlite" "$work/$d/out/results.sqlite"
done
size=$(du -h "$work/array8/out/results.sqlite" | cut -f1)
shards8=$(/usr/bin/python3 - "$work/array8/out/shards" <<'PY'
import glob, sqlite3, sys
rows = []
for f in sorted(glob.glob(sys.argv[1] + "/shard-*-of-8.sqlite")):
    db = sqlite3.connect(f)
    runs = db.execute("SELECT COUNT(*) FROM runs").fetchone()[0]
    seconds = db.execute("SELECT (julianday(MAX(finished_at)) - julianday(MIN(started_at))) * 86400 FROM experiments").fetchone()[0]
    rows.append(f"{runs} runs in {seconds:.0f} s")
print("; ".join(rows))
PY
)

rate() { /usr/bin/python3 -c "print(f'{$1 / ($2 / 1000):.1f}')"; }
cat <<TABLE
| how (default experiment, $runs runs, $(nproc) cores) | wall-clock | runs/s |
|---|---:|---:|
| one process, $(nproc) workers (\`coverbench run\`) | $(( single_ms / 1000 )) s | $(rate "$runs" "$single_ms") |
| 4-task array, 1 CPU each, submission to merged database | $(( array4_ms / 1000 )) s | $(rate "$runs" "$array4_ms") |
| 8-task array, 1 CPU each, submission to merged database | $(( array8_ms / 1000 )) s | $(rate "$runs" "$array8_ms") |

merge of 4 shards: $merge4; merge of 8 shards: $merge8 (merged database $size)
the 8 shards (1 CPU each, 2 at a time): $shards8
TABLE
