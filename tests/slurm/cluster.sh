#!/usr/bin/env bash
# A real single-node Slurm cluster on this machine, from Debian's packages (slurm-wlm, munge), for
# tests: `cluster.sh start DIR` brings it up with every file (config, state, spool, logs, pids)
# under DIR and prints `export SLURM_CONF=DIR/slurm.conf`; `cluster.sh stop DIR` stops every
# daemon it started, by the pids it recorded, and waits for them to exit. Needs root (slurmd runs
# jobs as their submitter; SlurmUser=root keeps it to one user). Safe to call stop twice.
set -euo pipefail

usage() { echo "usage: $0 start|stop DIR" >&2; exit 2; }
[ $# -eq 2 ] || usage
action=$1
dir=$(mkdir -p "$2" && cd "$2" && pwd)

stop() {
  local name pid
  for name in slurmd slurmctld munged; do
    [ -f "$dir/$name.pid" ] || continue
    pid=$(cat "$dir/$name.pid")
    if kill -0 "$pid" 2>/dev/null; then
      kill -TERM "$pid" 2>/dev/null || true
      for _ in $(seq 1 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.2; done
      kill -0 "$pid" 2>/dev/null && kill -KILL "$pid" 2>/dev/null || true
      for _ in $(seq 1 25); do kill -0 "$pid" 2>/dev/null || break; sleep 0.2; done
    fi
    if kill -0 "$pid" 2>/dev/null; then echo "cluster.sh: $name (pid $pid) did not stop" >&2; exit 1; fi
    rm -f "$dir/$name.pid"
  done
}

# Waits until FILE holds the pid of a live process; the daemons write their pid files themselves.
wait_pid() {
  local file=$1 name=$2
  for _ in $(seq 1 100); do
    if [ -s "$file" ] && kill -0 "$(cat "$file")" 2>/dev/null; then return 0; fi
    sleep 0.1
  done
  echo "cluster.sh: $name did not start; its log: $dir/$name.log" >&2
  tail -n 20 "$dir/$name.log" >&2 2>/dev/null || true
  stop
  exit 1
}

start() {
  [ "$(id -u)" -eq 0 ] || { echo "cluster.sh: must run as root" >&2; exit 1; }
  for cmd in munged slurmctld slurmd sbatch; do
    command -v "$cmd" >/dev/null || { echo "cluster.sh: $cmd not found (apt-get install -y slurm-wlm munge)" >&2; exit 1; }
  done
  local host cpus mem
  host=$(hostname -s)
  cpus=$(nproc)
  mem=$(( $(awk '/MemTotal/ {print $2}' /proc/meminfo) / 1024 - 1024 ))
  mkdir -p "$dir/state" "$dir/spool"

  # munge: a key owned by munge, mode 400; its socket folder owned by munge.
  if [ ! -s /etc/munge/munge.key ]; then
    mkdir -p /etc/munge
    dd if=/dev/urandom bs=1 count=1024 of=/etc/munge/munge.key status=none
  fi
  chown munge:munge /etc/munge /etc/munge/munge.key
  chmod 700 /etc/munge
  chmod 400 /etc/munge/munge.key
  mkdir -p /run/munge /var/lib/munge /var/log/munge
  chown munge:munge /run/munge /var/lib/munge /var/log/munge
  chmod 755 /run/munge
  touch "$dir/munged.log" "$dir/munged.pid"
  chown munge "$dir/munged.log" "$dir/munged.pid"
  runuser -u munge -- munged --force --log-file="$dir/munged.log" --pid-file="$dir/munged.pid"
  wait_pid "$dir/munged.pid" munged

  cat > "$dir/slurm.conf" <<CONF
ClusterName=coverbench-test
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU_Memory
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
MpiDefault=none
ReturnToService=2
SchedulerType=sched/backfill
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
SlurmctldPort=6817
SlurmdPort=6818
MaxArraySize=100001
NodeName=$host CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
  export SLURM_CONF="$dir/slurm.conf"
  slurmctld -f "$SLURM_CONF" -i
  wait_pid "$dir/slurmctld.pid" slurmctld
  slurmd -f "$SLURM_CONF"
  wait_pid "$dir/slurmd.pid" slurmd
  # Ready when the node takes jobs.
  for _ in $(seq 1 100); do
    state=$(sinfo -h -N -o '%t' 2>/dev/null | head -n1 || true)
    case "$state" in idle|mix|alloc) echo "export SLURM_CONF=$SLURM_CONF"; return 0 ;; esac
    sleep 0.2
  done
  echo "cluster.sh: the node did not become idle (state '${state:-none}'); logs in $dir" >&2
  tail -n 20 "$dir/slurmctld.log" "$dir/slurmd.log" >&2 || true
  stop
  exit 1
}

case "$action" in
  start) start ;;
  stop) stop ;;
  *) usage ;;
esac
