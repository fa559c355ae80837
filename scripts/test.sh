#!/usr/bin/env bash
# Builds everything and runs every test (unit, conformance, command line) with CTest.
# Another compiler: CC=clang CXX=clang++ COVERBENCH_BUILD_DIR=build-clang bash scripts/test.sh
# (the cost and quality gates are then skipped with their reason: they are pinned to one build).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
source scripts/ctest_costs.sh
seed_ctest_costs "${COVERBENCH_BUILD_DIR:-build}"
# One test more than cores: a fifth of the suite's time is spent waiting (browsers drawing,
# servers and runners waiting out their deadlines), and the extra test fills it.
ctest --test-dir "${COVERBENCH_BUILD_DIR:-build}" --output-on-failure -j "$(( $(nproc) + 1 ))"
