#!/usr/bin/env bash
# Issue "Fast from the first command to the last figure", acceptance 1: the main job on a fresh
# machine, from clone to results/default/report/index.html, in a clean Debian bookworm chroot
# that holds only a base system and the build tools every machine of ours has (g++, cmake,
# ninja-build, python3, git): no library CoverBench uses, no ccache of earlier builds.
#   sudo bash bench/fresh_machine/run.sh [WORKDIR]      (default /var/tmp/coverbench-fresh)
# The base system is made once with debootstrap (several minutes, kept in WORKDIR/base); every
# run copies it, clones this repository's HEAD into it, runs `bash scripts/run_main.sh` there and
# prints each phase's wall time (apt, build, experiment and report) with the machine's load.
set -euo pipefail
repo="$(cd "$(dirname "$0")/../.." && pwd)"
work="${1:-/var/tmp/coverbench-fresh}"
[ "$(id -u)" -eq 0 ] || { echo "fresh_machine: needs root (debootstrap, chroot, mount)" >&2; exit 2; }
command -v debootstrap > /dev/null || apt-get install -y -qq debootstrap > /dev/null
mkdir -p "$work"
if [ ! -f "$work/base/.complete" ]; then
  rm -rf "$work/base"
  debootstrap --variant=minbase --include=g++,cmake,ninja-build,python3,git,ca-certificates \
    bookworm "$work/base" http://deb.debian.org/debian > "$work/debootstrap.log"
  rm -f "$work/base/var/cache/apt/archives/"*.deb
  touch "$work/base/.complete"
fi
root="$work/run"
cleanup() {
  umount -R "$root/dev" 2>/dev/null || true
  umount "$root/proc" 2>/dev/null || true
}
trap cleanup EXIT
cleanup
rm -rf "$root"
cp -a "$work/base" "$root"
cp /etc/resolv.conf "$root/etc/resolv.conf"
if [ -f /etc/apt/sources.list.d/debian.sources ]; then  # this machine's mirrors, as on the image
  cp /etc/apt/sources.list.d/debian.sources "$root/etc/apt/sources.list.d/"
  rm -f "$root/etc/apt/sources.list"
fi
mount -t proc proc "$root/proc"
mount --rbind /dev "$root/dev"
git -C "$repo" bundle create "$root/root/coverbench.bundle" HEAD > /dev/null 2>&1
echo "== fresh machine: $(git -C "$repo" rev-parse --short HEAD), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
start=$(date +%s.%N)
chroot "$root" /usr/bin/env -i HOME=/root PATH=/usr/sbin:/usr/bin:/sbin:/bin LANG=C.UTF-8 bash -c '
  set -e
  cd /root && git -c advice.detachedHead=false clone -q coverbench.bundle coverbench && cd coverbench
  bash scripts/run_main.sh' 2>&1 | while IFS= read -r line; do
  printf '%7.1f s  %s\n' "$(echo "$(date +%s.%N) - $start" | bc)" "$line"
done
end=$(date +%s.%N)
test -f "$root/root/coverbench/results/default/report/index.html" \
  || { echo "fresh_machine: no report was written" >&2; exit 1; }
printf '== clone to report: %.0f s wall (load now %s)\n' "$(echo "$end - $start" | bc)" "$(cut -d' ' -f1-3 /proc/loadavg)"
