#!/usr/bin/env bash
# The report as a user sees it: a small experiment (walls and a dataset label that hold markup
# and quotes), its report and the showcase page opened in headless Chromium; no console error,
# every image loaded (lazy, with its size), every section there, the markup shown as text; the
# first screen drawn before the images below it load (its times printed). Screenshots are kept in
# build/test-artifacts/browser/ to look at.
# usage: report_browser_test.sh COVERBENCH_BINARY SOURCE_DIR ARTIFACTS_DIR
set -euo pipefail
bin=$1 src=$2 shots=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/walls" "$shots"
cat > "$work/walls/a.json" <<'JSON'
{"name": "<script>alert(\"wall\")</script> 'q'", "width": 2.0, "height": 1.2,
 "obstacles": [{"type": "rect", "x": 0.8, "y": 0.4, "width": 0.4, "height": 0.3, "label": "<b>win</b>"}]}
JSON
cat > "$work/walls/b.json" <<'JSON'
{"name": "plain wall", "width": 1.5, "height": 1.0}
JSON
cat > "$work/c.yaml" <<'YAML'
name: "browser <i>check</i>"
output: out
datasets:
  - folder: walls
    label: "<img src=x onerror=alert(1)> \"quoted\""
  - family: residential
    count: 3
    seed: 2
planners:
  - zigzag
  - spiral
  - name: boustrophedon
  - name: zigzag
    params:
      sweep_angle: [30, 90]
YAML
"$bin" run "$work/c.yaml" > "$work/run.log"
python=${COVERBENCH_PYTHON:-/usr/bin/python3}
"$python" "$src/tests/browser/check_page.py" "$work/out/report/index.html" "$shots/report" \
  --section headline --section outcomes --section paired --section plots --section galleries --section record \
  --min-images 20 --min-tables 10 --play --lazy \
  --expect-text '<script>alert("wall")</script> '"'q'" --expect-text '<img src=x onerror=alert(1)> "quoted"'
"$bin" showcase --walls "$src/datasets/canonical" --out "$work/showcase" > /dev/null
"$python" "$src/tests/browser/check_page.py" "$work/showcase/index.html" "$shots/showcase" --section walls --min-images 30 --lazy
# The coat's picture (docs/deposition.md), as a page shows it: loaded, no error; its screenshot kept.
"$bin" plan --wall "$src/datasets/canonical/gable_round_window.json" --planner boustrophedon --tool-width 0.3 \
  --profile beta --beta 2.5 --param coat_ripple=0.02 --out "$work/coat-plan.json" > /dev/null
"$bin" metrics --wall "$src/datasets/canonical/gable_round_window.json" --plan "$work/coat-plan.json" \
  --profile beta --beta 2.5 --coat-svg "$work/coat.svg" > /dev/null
printf '<!doctype html><html><head><meta charset="utf-8"><title>coat</title></head><body><img src="coat.svg" alt="the coat"></body></html>\n' > "$work/coat.html"
"$python" "$src/tests/browser/check_page.py" "$work/coat.html" "$shots/coat" --min-images 1 --min-tables 0
# A report of a tool with a flux profile: every run of the gallery with its coat beside its path
# (loaded, lazy, sized); the first wall's pair kept as coat-report-shot-0.png.
mkdir -p "$work/coat-walls"
cp "$work/walls/b.json" "$work/coat-walls/"
cat > "$work/coat.yaml" <<'YAML'
name: coat
output: coat-out
datasets:
  - folder: coat-walls
planners:
  - zigzag
  - name: boustrophedon
    params:
      coat_ripple: 0.02
tool:
  width: 0.3
  profile: {kind: beta, beta: 2.5}
YAML
"$bin" run "$work/coat.yaml" > "$work/coat-run.log"
coats=$(ls "$work/coat-out/report/gallery/coat" | wc -l)
[ "$coats" -ge 2 ] || { echo "FAIL: $coats coat pictures in the gallery, expected 2 or more" >&2; exit 1; }
"$python" "$src/tests/browser/check_page.py" "$work/coat-out/report/index.html" "$shots/coat-report" --section galleries \
  --min-images 4 --lazy --shot-of '.coat-pair'
