#!/usr/bin/env bash
# The Slurm test: brings up a real single-node Slurm cluster from Debian's packages on this
# machine (tests/slurm/cluster.sh), writes the job scripts of a small experiment with
# `coverbench slurm --shards 4 --submit` (a 4-task job array and a merge-and-report job after it),
# waits for both, checks that every task and the merge completed, that the merged results equal a
# single-process run of the same config run key by run key (tests/slurm/compare_results.py), and
# that the report was written; then stops every daemon it started, by pid, whatever happened.
#
#   bash tests/slurm/slurm_test.sh [build/coverbench] [WORK_DIR]
#
# Needs root (it starts munged, slurmctld and slurmd); installs slurm-wlm and munge if missing.
# Prints the wall-clock of the single-process run and of the array, for docs/scaling.md.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
coverbench=$(realpath "${1:-$root/build/coverbench}")
work=${2:-$(mktemp -d /tmp/coverbench-slurm.XXXXXX)}
mkdir -p "$work"
work=$(cd "$work" && pwd)
rm -rf "$work/cluster" "$work/single" "$work/array"  # a fresh cluster and experiment every time
[ "$(id -u)" -eq 0 ] || { echo "slurm_test: must run as root (it starts the Slurm and munge daemons)" >&2; exit 1; }
[ -x "$coverbench" ] || { echo "slurm_test: $coverbench is not an executable (build first)" >&2; exit 1; }

if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
  echo "== installing slurm-wlm and munge"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq -o DPkg::Lock::Timeout=300 slurm-wlm munge >/dev/null
fi

cluster="$work/cluster"
trap 'bash "$root/tests/slurm/cluster.sh" stop "$cluster"' EXIT
eval "$(bash "$root/tests/slurm/cluster.sh" start "$cluster")"
echo "== cluster up: $(sinfo -h -o '%P %a %D node(s) %c CPUs %t')"

mkdir -p "$work/single" "$work/array"
cp "$root/tests/slurm/experiment.yaml" "$work/single/experiment.yaml"
cp "$root/tests/slurm/experiment.yaml" "$work/array/experiment.yaml"

start=$(date +%s%N)
"$coverbench" run "$work/single/experiment.yaml" --no-report > "$work/single.log" 2> "$work/single.err"
single_ms=$(( ($(date +%s%N) - start) / 1000000 ))
runs=$(/usr/bin/python3 -c "import sqlite3,sys; print(sqlite3.connect(sys.argv[1]).execute('SELECT COUNT(*) FROM runs').fetchone()[0])" "$work/single/out/results.sqlite")
echo "== single process: $runs runs in ${single_ms} ms ($(tail -n 3 "$work/single.log" | head -n 1))"

cd "$work/array"
start=$(date +%s%N)
"$coverbench" slurm experiment.yaml --shards 4 --cpus-per-task 1 --time 10 --mem 1500M --submit | tee "$work/submit.log"
array=$(awk '$1 == "array" {print $2}' "$work/submit.log")
merge=$(awk '$1 == "merge" {print $2}' "$work/submit.log")
[ -n "$array" ] && [ -n "$merge" ] || { echo "slurm_test: no job ids in the submission's output" >&2; exit 1; }

# Wait for both jobs to leave the queue (at most 5 minutes).
for _ in $(seq 1 600); do
  [ -z "$(squeue -h -j "$array,$merge" 2>/dev/null)" ] && break
  sleep 0.5
done
array_ms=$(( ($(date +%s%N) - start) / 1000000 ))
if [ -n "$(squeue -h -j "$array,$merge" 2>/dev/null)" ]; then
  squeue
  echo "slurm_test: the jobs did not finish within 5 minutes" >&2
  exit 1
fi

# Every array task and the merge job completed with exit code 0.
states=$(scontrol show job "$array" | grep -oE 'JobState=[A-Z_]+|ExitCode=[0-9:]+' | paste -sd' ')
echo "== array $array: $states"
tasks_ok=$(scontrol show job "$array" | grep -c 'JobState=COMPLETED' || true)
[ "$tasks_ok" -eq 4 ] || { echo "slurm_test: $tasks_ok of 4 array tasks completed; logs in $work/array/out/slurm/logs" >&2; tail -n 5 out/slurm/logs/* >&2; exit 1; }
scontrol show job "$array" | grep -q 'ExitCode=[1-9]' && { echo "slurm_test: an array task failed" >&2; exit 1; }
merge_state=$(scontrol show job "$merge" | grep -oE 'JobState=[A-Z_]+ |ExitCode=[0-9:]+' | paste -sd' ')
echo "== merge $merge: $merge_state"
case "$merge_state" in *JobState=COMPLETED*ExitCode=0:0*) ;; *)
  echo "slurm_test: the merge job did not complete" >&2; cat out/slurm/logs/merge-*.out >&2; exit 1 ;;
esac
cat out/slurm/logs/merge-*.out
for i in 0 1 2 3; do
  [ -s "out/slurm/logs/run-${array}_$i.out" ] || { echo "slurm_test: no log of task $i" >&2; exit 1; }
done
[ -s out/report/index.html ] || { echo "slurm_test: the merge job wrote no report" >&2; exit 1; }

/usr/bin/python3 "$root/tests/slurm/compare_results.py" "$work/single/out/results.sqlite" "$work/array/out/results.sqlite"
echo "== $runs runs: one process ${single_ms} ms; 4-task array (submission to merged report) ${array_ms} ms"

# Stop the cluster now (the trap stays for failures) and check that no daemon it started is left.
pids=$(cat "$cluster"/*.pid 2>/dev/null | paste -sd' ')
bash "$root/tests/slurm/cluster.sh" stop "$cluster"
for pid in $pids; do
  if kill -0 "$pid" 2>/dev/null; then echo "slurm_test: daemon $pid still running" >&2; exit 1; fi
done
echo "== stopped munged, slurmctld and slurmd (pids $pids); none left"
echo "slurm_test: PASSED"
