#!/usr/bin/env bash
# The native GoogleTest suites (core, glare, optimizer, photometry; Vulkan on lavapipe where the
# backend is built) compiled with AddressSanitizer (leak check on), UndefinedBehaviorSanitizer and
# -D_GLIBCXX_ASSERTIONS into build-asan/, then run through CTest. A finding aborts the test that
# made it. scripts/test.sh runs this after the main suite; docs/testing.md "Sanitizer build".
# Extra arguments go to the CMake configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
dir=build-asan
jobs=$(nproc 2>/dev/null || echo 2)

# halt_on_error/abort: the first finding ends the test with a stack. Leak suppressions are for
# memory that libraries outside this project keep (each entry says which and why).
export ASAN_OPTIONS="detect_leaks=1:check_initialization_order=1:strict_string_checks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$root/Tests/sanitizers/lsan.supp:print_suppressions=0"

start=$(date +%s)
cmake -S . -B "$dir" -G Ninja -DLIGHTSOLVER_SANITIZE=ON -DCMAKE_BUILD_TYPE=Sanitize \
  -DLIGHTSOLVER_BUILD_PYTHON=OFF -DLIGHTSOLVER_BUILD_BENCHMARKS=OFF "$@"
# Only the test programs (no CLI): the suites that exist in this configuration.
mapfile -t targets < <(ninja -C "$dir" -t targets all | sed -n 's/^\([a-z_]*_tests\): phony$/\1/p')
cmake --build "$dir" -j "$jobs" --target "${targets[@]}"
built=$(date +%s)
ctest --test-dir "$dir" --output-on-failure -j "$jobs" --timeout 900
done_at=$(date +%s)
echo "test-sanitize: ${targets[*]}: build $((built - start)) s, tests $((done_at - built)) s"
