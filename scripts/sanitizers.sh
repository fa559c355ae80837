#!/usr/bin/env bash
# The test suite built with AddressSanitizer and UndefinedBehaviorSanitizer (gcc), in build-asan/.
# Any report fails the run (-fno-sanitize-recover), leaks included. About 12 minutes on 2 cores
# from scratch. Two tests are left out: they expect a run past its memory limit (RLIMIT_AS) to end
# as `memory_limit`, and under AddressSanitizer, whose allocator reserves its own address space,
# such a run ends as `crash` (the worker aborts in the sanitizer's allocator).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh > /dev/null
flags="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
if [ ! -f build-asan/build.ninja ]; then
  cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" > /dev/null
fi
cmake --build build-asan -j 2
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1:allocator_may_return_null=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir build-asan --output-on-failure -j 2 \
  -E "RunLimitsBecomeStatusesInTheTables|EachMisbehavingPlannerYieldsItsStatusAndTheRestIsUntouched"
