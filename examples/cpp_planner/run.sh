#!/bin/sh
# Starts the planner: built here (cmake -S . -B build) or by CoverBench's build.
for b in build/column_sweep "${COVERBENCH_BUILD_DIR:-../../build}/examples/cpp_planner/column_sweep"; do
  [ -x "$b" ] && exec "$b"
done
echo "column_sweep is not built: cmake -S . -B build && cmake --build build" >&2
exit 127
