# Sourced by scripts/test.sh and scripts/sanitizers.sh: seeds CTest's scheduler with the suite's
# long tests (tests/ctest_costs.txt: name, runs, seconds here), so that `ctest -j` starts them
# first on a fresh build instead of last (one 2-minute test started last adds two minutes to the
# run). CTest keeps its own measured costs from then on; a build that has them is left alone.
#   seed_ctest_costs BUILD_DIR
seed_ctest_costs() {
  local dir="$1/Testing/Temporary"
  [ -f "$dir/CTestCostData.txt" ] && return 0
  mkdir -p "$dir"
  cp tests/ctest_costs.txt "$dir/CTestCostData.txt"
}
