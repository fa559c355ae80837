#!/usr/bin/env bash
# The Slurm test: brings up a real single-node Slurm cluster from Debian's packages on this
# machine (tests/slurm/cluster.sh), writes the job scripts of a small experiment with
# `coverbench slurm --shards 4 --submit` (a 4-task job array and a merge-and-report job after it),
# waits for both, checks that every task and the merge completed, that the merged results equal a
# single-process run of the same config run key by run key (tests/slurm/compare_results.py), and
# that the report was written. Then it cancels one task of a second array mid-way (scancel),
# checks the merge refuses and names it, resubmits that task alone, and checks the merge is then
# complete and equal to a single-process run. It stops every daemon it started, by pid, whatever
# happened.
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
rm -rf "$work/cluster" "$work/single" "$work/array" "$work/resume" "$work/resume-single"  # fresh every time
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

# Phase 2: a task cancelled mid-way (scancel: SIGTERM, then SIGKILL) keeps what it stored; the merge
# refuses and names it; resubmitted alone, it resumes; the merge is then complete and equal to a
# single-process run. Task 0 owes about 400 runs, about 1.5 s of work here: the cancel is sent once
# its first run is stored. A cancel that lands too late (the task completed: a fast host, a slow
# scancel) or too early (nothing stored) is not a verdict: the shard is deleted and task 0 submitted
# again, five times at most.
wait_gone() {  # jobs leave the queue within 5 minutes
  for _ in $(seq 1 600); do [ -z "$(squeue -h -j "$1" 2>/dev/null)" ] && return 0; sleep 0.5; done
  squeue; echo "slurm_test: job $1 did not finish within 5 minutes" >&2; exit 1
}
count_runs() {  # the runs stored in a shard; -1 if it cannot be read (no table yet, locked for 5 s)
  /usr/bin/python3 -c "import sqlite3,sys; print(sqlite3.connect(sys.argv[1], timeout=5).execute('SELECT COUNT(*) FROM runs').fetchone()[0])" "$1" 2>/dev/null || echo -1
}
for d in resume resume-single; do
  mkdir -p "$work/$d"
  sed 's/^    count: 10$/    count: 240/' "$root/tests/slurm/experiment.yaml" > "$work/$d/experiment.yaml"
done
"$coverbench" run "$work/resume-single/experiment.yaml" --no-report > /dev/null 2>&1
cd "$work/resume"
"$coverbench" slurm experiment.yaml --shards 4 --cpus-per-task 1 --time 10 --mem 1500M > /dev/null
shard0=out/shards/shard-0-of-4.sqlite
caught=""
for attempt in 1 2 3 4 5; do
  if [ "$attempt" -eq 1 ]; then
    job=$(sbatch --parsable out/slurm/run.sbatch)  # the other three tasks complete
  else
    rm -f "$shard0" "$shard0-wal" "$shard0-shm" "$shard0-journal"
    job=$(sbatch --parsable --array=0 out/slurm/run.sbatch)
  fi
  for _ in $(seq 1 1200); do [ -s "$shard0" ] && [ "$(count_runs "$shard0")" -ge 1 ] && break; sleep 0.02; done
  scancel "${job}_0"
  wait_gone "$job"
  state0=$(scontrol show job "${job}_0" | grep -oE 'JobState=[A-Z_]+' | head -n1)
  stored0=$(count_runs "$shard0")
  owed0=$(/usr/bin/python3 -c "import sqlite3,sys; print(sqlite3.connect(sys.argv[1]).execute('SELECT COUNT(*) FROM experiment_runs WHERE experiment_id = (SELECT MAX(id) FROM experiments)').fetchone()[0])" "$shard0" 2>/dev/null || echo -1)
  echo "== task 0 of array $job (attempt $attempt): $state0 with $stored0 of its $owed0 runs stored"
  if [ "$state0" = "JobState=CANCELLED" ] && [ "$stored0" -gt 0 ] && [ "$owed0" -gt 0 ] && [ "$stored0" -lt "$owed0" ]; then
    caught=yes
    break
  fi
done
[ -n "$caught" ] || { echo "slurm_test: task 0 was not cancelled mid-way in 5 attempts (last: $state0, $stored0 of $owed0 runs)" >&2; exit 1; }
if bash out/slurm/merge.sbatch > merge-refused.log 2>&1; then
  echo "slurm_test: the merge accepted a shard with missing runs" >&2; exit 1
fi
grep -q "shard 0/4 .* lacks $(( owed0 - stored0 )) of its $owed0 runs" merge-refused.log \
  || { echo "slurm_test: the merge did not name the incomplete shard:" >&2; cat merge-refused.log >&2; exit 1; }
echo "== the merge refused: $(head -c 160 merge-refused.log)..."
again=$(sbatch --parsable --array=0 out/slurm/run.sbatch)
wait_gone "$again"
merge_again=$(sbatch --parsable out/slurm/merge.sbatch)
wait_gone "$merge_again"
scontrol show job "$merge_again" | grep -q 'JobState=COMPLETED .*' \
  || { echo "slurm_test: the merge after the resumed task did not complete" >&2; cat out/slurm/logs/merge-"$merge_again".out >&2; exit 1; }
grep "merged" out/slurm/logs/merge-"$merge_again".out
/usr/bin/python3 "$root/tests/slurm/compare_results.py" "$work/resume-single/out/results.sqlite" "$work/resume/out/results.sqlite"

# Stop the cluster now (the trap stays for failures) and check that no daemon it started is left.
pids=$(cat "$cluster"/*.pid 2>/dev/null | paste -sd' ')
bash "$root/tests/slurm/cluster.sh" stop "$cluster"
for pid in $pids; do
  if kill -0 "$pid" 2>/dev/null; then echo "slurm_test: daemon $pid still running" >&2; exit 1; fi
done
echo "== stopped munged, slurmctld and slurmd (pids $pids); none left"
echo "slurm_test: PASSED"
