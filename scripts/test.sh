#!/usr/bin/env bash
# Builds everything and runs every test (unit, conformance, command line) with CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
ctest --test-dir build --output-on-failure -j 2
