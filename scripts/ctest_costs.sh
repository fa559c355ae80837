# Sourced by scripts/test.sh and scripts/sanitizers.sh: seeds CTest's scheduler with the suite's
# long tests (tests/ctest_costs.txt: name, runs, seconds here), so that `ctest -j` starts them
# first instead of last (one 2-minute test started last adds two minutes to the run). CTest keeps
# its own measured costs from then on; a test it has no cost for (a fresh build, or a build where
# only some tests were run, `ctest -R ...`) takes the seeded one.
#   seed_ctest_costs BUILD_DIR
seed_ctest_costs() {
  local dir="$1/Testing/Temporary"
  local data="$dir/CTestCostData.txt"
  mkdir -p "$dir"
  [ -f "$data" ] || { cp tests/ctest_costs.txt "$data"; return 0; }
  # CTest's file: "name runs cost" lines, then "---" and the tests that failed last. The seeded
  # lines of tests not yet in it go before the "---".
  awk 'FILENAME == ARGV[1] { if ($0 == "---") done = 1; else if (!done) { sub(/ [0-9]+ [0-9.e+-]+$/, ""); have[$0] = 1 }; next }
       { line = $0; sub(/ [0-9]+ [0-9.e+-]+$/, "", line); if (!(line in have)) print }' "$data" tests/ctest_costs.txt > "$data.seed"
  if [ -s "$data.seed" ]; then
    awk -v seed="$data.seed" 'BEGIN { while ((getline l < seed) > 0) extra = extra l "\n" }
         $0 == "---" && !put { printf "%s", extra; put = 1 } { print } END { if (!put) printf "%s", extra }' "$data" > "$data.new"
    mv "$data.new" "$data"
  fi
  rm -f "$data.seed"
}
