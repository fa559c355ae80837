#!/usr/bin/env bash
# The layering check (docs/architecture.md) on the build the tests use: every symbol a library
# uses from another CoverBench library must be defined in a layer below it (read from the static
# archives with nm, so link order hides nothing), and CMake may link each library only to those
# layers (`cmake --graphviz`). scripts/layers.py holds the table of layers; tests/layers shows the
# check refusing a call upward and a declared link upward.
#   bash scripts/layers.sh
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh > /dev/null
python3 scripts/layers.py "${COVERBENCH_BUILD_DIR:-build}"
