#!/usr/bin/env bash
# The layering check: every library built shared and linked with -Wl,--no-undefined in
# build-shared/, so a library that uses what only a library above it defines (a core header
# declaring what the algorithms library defines, say) fails to link; then the command, linked
# against those shared libraries, plans a wall. Static link order hides such a cycle; this does
# not. Tests and benchmarks are left out (the static build runs them).
#   bash scripts/layers.sh
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh > /dev/null
build=build-shared
if [ ! -f $build/build.ninja ]; then
  cmake -S . -B $build -G Ninja -DBUILD_SHARED_LIBS=ON -DCMAKE_SHARED_LINKER_FLAGS=-Wl,--no-undefined \
    -DCOVERBENCH_BUILD_TESTS=OFF -DCOVERBENCH_BUILD_BENCHMARKS=OFF > /dev/null
fi
echo "== building every library shared, with -Wl,--no-undefined ($build)"
cmake --build $build -j 2
for lib in core metrics datasets algorithms reports experiments; do
  test -f "$build/libcoverbench_$lib.so" || { echo "layers: libcoverbench_$lib.so was not built" >&2; exit 1; }
done
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$build/coverbench" plan --wall datasets/canonical/living_room_north.json --planner zigzag --out "$out/plan.json"
echo "layers: 6 shared libraries linked with no undefined symbol; the command ran on them"
