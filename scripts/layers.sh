#!/usr/bin/env bash
# The layering check: every library built shared and linked with -Wl,--no-undefined in
# build-shared/, so a library that uses what only a library above it defines (a planning header
# declaring what the algorithms library defines, say) fails to link; each library's links checked
# against the layers below it; then the command, linked against those shared libraries, plans a
# wall and scores it with both judges. Static link order hides such a cycle; this does
# not. Tests and benchmarks are left out (the static build runs them).
#   bash scripts/layers.sh
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh > /dev/null
build=build-shared
if [ ! -f $build/build.ninja ]; then
  cmake -S . -B $build -G Ninja -DBUILD_SHARED_LIBS=ON -DCMAKE_SHARED_LINKER_FLAGS=-Wl,--no-undefined \
    -DCOVERBENCH_BUILD_TESTS=OFF -DCOVERBENCH_BUILD_BENCHMARKS=OFF -DCOVERBENCH_BUILD_PYTHON=OFF > /dev/null
fi
libs="base identity files geometry formats transits planning vehicles metrics judge datasets imports algorithms records runner reports experiments"
# The libraries and the command only: the plug-ins are linked with -Wl,--no-undefined in every
# build already, and the Python module and the examples add nothing to this check.
echo "== building every library shared, with -Wl,--no-undefined ($build)"
cmake --build $build -j 2 --target coverbench $(for lib in $libs; do echo "coverbench_$lib"; done)
for lib in $libs; do
  test -f "$build/libcoverbench_$lib.so" || { echo "layers: libcoverbench_$lib.so was not built" >&2; exit 1; }
done
# Each library may link only the CoverBench libraries of the layers below it (docs/architecture.md).
# The judge and the fast metrics engine stand on the geometry layer alone (the judge on nothing of
# CoverBench: it reads the value types' headers only), so neither can call the planners' code.
allowed() {
  case $1 in
    base|identity|judge) echo "" ;;
    files|geometry) echo "base" ;;
    formats) echo "base files geometry" ;;
    transits|metrics) echo "base geometry" ;;
    planning) echo "base files formats geometry transits" ;;
    vehicles) echo "base files formats geometry planning transits" ;;
    datasets|imports) echo "base files formats geometry identity" ;;
    algorithms) echo "base files formats geometry planning transits vehicles" ;;
    records) echo "base files formats geometry identity metrics planning transits" ;;
    runner) echo "algorithms base files formats geometry identity metrics planning records transits vehicles" ;;
    reports) echo "base files formats geometry metrics planning records transits" ;;
    experiments) echo "algorithms base datasets files formats geometry identity imports judge metrics planning records runner transits vehicles" ;;
  esac
}
for lib in $libs; do
  needed=$(readelf -d "$build/libcoverbench_$lib.so" | sed -n 's/.*Shared library: \[libcoverbench_\(.*\)\.so\]/\1/p' | sort | tr '\n' ' ')
  for n in $needed; do
    case " $(allowed $lib) " in *" $n "*) ;; *) echo "layers: libcoverbench_$lib.so links libcoverbench_$n.so, a layer it must not use" >&2; exit 1 ;; esac
  done
done
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$build/coverbench" plan --wall datasets/canonical/living_room_north.json --planner zigzag --out "$out/plan.json"
"$build/coverbench" metrics --wall datasets/canonical/living_room_north.json --plan "$out/plan.json" --judge exact \
  --arc-vertices 32 > /dev/null
echo "layers: 17 shared libraries linked with no undefined symbol, each only to the layers below it; the command ran on them"
