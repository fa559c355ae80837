#!/usr/bin/env bash
# Installs CoverBench's build dependencies (Debian packages) when any is missing, then configures
# and builds in build/ (Release). Safe to run again: it only does what is missing.
#   bash scripts/setup.sh        everything: the command, tests, benchmarks, the Python package
#   bash scripts/setup.sh main   what the main job needs (scripts/run_main.sh): the command and the
#                                report's Python packages; no test tools, TeX, browser or compilers
#                                for the sanitizers, and only the command is built, without its
#                                plug-ins (OMPL, GDAL, the server: `coverbench` says in one line
#                                which command needs them; `bash scripts/setup.sh` adds them)
set -euo pipefail
cd "$(dirname "$0")/.."
mode="${1:-all}"

# What the command and its report need.
MAIN_PACKAGES=(g++ cmake ninja-build pkg-config ccache
          libpolyclipping-dev nlohmann-json3-dev libcli11-dev libboost-graph-dev
          libyaml-cpp-dev libsqlite3-dev libssl-dev zlib1g-dev libpng-dev
          libcgal-dev libgmp-dev libmpfr-dev                       # the exact judge
          python3 python3-numpy python3-scipy python3-matplotlib   # the report's statistics and plots
          libeigen3-dev)                                           # import placements
# And the plug-ins, the tests, the gates, the benchmarks and the Python package.
PACKAGES=("${MAIN_PACKAGES[@]}"
          libcpp-httplib-dev                                       # coverbench serve (a plug-in)
          libompl-dev                                              # the sampling transits and Reeds-Shepp cars (a plug-in)
          libgdal-dev                                              # dataset import: GeoJSON, GML, KML, Shapefile, DXF, maps (a plug-in)
          libgtest-dev libbenchmark-dev
          python3-jsonschema                                       # the planner protocol's schema test
          pybind11-dev python3-dev                                 # the Python package (import coverbench)
          python3-venv python3-pip mypy python3-pandas             # its install, type and DataFrame tests
          chromium python3-websocket                               # the browser test of the report
          node-typescript                                          # type-checks the explorer's JavaScript (ctest web_types)
          texlive-latex-base texlive-latex-recommended             # the test that the LaTeX tables compile
          time                                                     # peak memory in the wall-time report
          universal-ctags                                          # the functions' sizes (scripts/unit_sizes.sh)
          ompl-demos                                               # OMPL's log parser, for the export-ompl test
          valgrind                                                 # the cost gate (callgrind)
          clang libclang-rt-14-dev)                                # the sanitizer build and the fuzz targets

[ "$mode" = main ] && PACKAGES=("${MAIN_PACKAGES[@]}")
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "== installing: ${missing[*]}"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq -o DPkg::Lock::Timeout=300 "${missing[@]}" >/dev/null
fi

# COVERBENCH_BUILD_DIR (default build) holds the build; CC and CXX pick the compiler when it is
# first configured (the gates run on the pinned build and are skipped, with the reason, on others).
build="${COVERBENCH_BUILD_DIR:-build}"
export CCACHE_BASEDIR="$(cd .. && pwd)"
if [ "$mode" = main ]; then
  # The command alone: a build configured for everything keeps its settings.
  if [ ! -f "$build/build.ninja" ]; then
    cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCOVERBENCH_BUILD_TESTS=OFF \
      -DCOVERBENCH_BUILD_BENCHMARKS=OFF -DCOVERBENCH_BUILD_PYTHON=OFF -DCOVERBENCH_PLUGINS=OFF >/dev/null
  fi
  echo "== building the command in $build"
  cmake --build "$build" -j 2 --target coverbench
  exit 0
fi
if [ ! -f "$build/build.ninja" ] || grep -qE '^COVERBENCH_(BUILD_TESTS|BUILD_BENCHMARKS|BUILD_PYTHON|PLUGINS):BOOL=OFF' "$build/CMakeCache.txt"; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCOVERBENCH_BUILD_TESTS=ON -DCOVERBENCH_BUILD_BENCHMARKS=ON \
    -DCOVERBENCH_BUILD_PYTHON=ON -DCOVERBENCH_PLUGINS=ON >/dev/null
fi
echo "== building $build (a first build without ccache took 7 min 20 s on 2 idle cores)"
cmake --build "$build" -j 2

# The explorer's front-end packages from the npm registry, pinned, into reports/web/vendor (not in
# git; one install for every build): Observable Plot on d3, which the Plots tab draws with and
# `coverbench serve` serves (the page needs no network), and axe-core, which the accessibility
# test (ctest serve_a11y) injects into the page (Debian packages none of them).
vendor="reports/web/vendor"
npm_packages=(@observablehq/plot@0.6.17 d3@7.9.0 axe-core@4.14.1)
installed() {
  local p
  for p in "${npm_packages[@]}"; do
    local name="${p%@*}" version="${p##*@}"
    grep -q "\"version\": \"$version\"" "$vendor/node_modules/$name/package.json" 2>/dev/null || return 1
  done
}
if ! installed; then
  echo "== installing the explorer's npm packages into $vendor: ${npm_packages[*]}"
  if ! command -v npm >/dev/null; then  # Debian's npm, unless the Node.js installed brings its own
    SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
    $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq -o DPkg::Lock::Timeout=300 npm >/dev/null
  fi
  mkdir -p "$vendor"
  npm install --prefix "$vendor" --no-audit --no-fund --no-save --ignore-scripts --loglevel=error "${npm_packages[@]}" >/dev/null
fi

# `import coverbench` anywhere: `python3 -m pip install ./python` into a virtual environment (or
# --user), which reuses this build (README.md, "From Python").
