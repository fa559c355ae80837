#!/usr/bin/env bash
# The main job: build, then plan every canonical wall with every registered planner and write
# plan files, SVG pictures, a summary table and an HTML page to results/showcase/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
out=results/showcase
rm -rf "$out"
./build/coverbench showcase --walls datasets/canonical --out "$out"
echo "== open $out/index.html (or read $out/summary.md)"
