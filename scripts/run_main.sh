#!/usr/bin/env bash
# The main job: build, run the default experiment (every registered planner on a few hundred
# generated walls and the seeds' cases; about a minute on 2 cores, with the report) and write its
# report: rankings, paired statistics, plots, galleries and the reproducibility record.
#   results/default/report/index.html   the report (open it in a browser; works from disk)
#   results/default/report/report.md    its tables (also report.csv, report.tex for papers)
#   results/default/results.sqlite      every run: status, metrics, path
# Running it again reuses the stored runs (no planner work) and writes the same report.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh main
./build/coverbench run experiments/default.yaml
echo "== open the report: results/default/report/index.html"
