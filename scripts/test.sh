#!/usr/bin/env bash
# Fresh Debian 12 -> every test run: packages, build, then CTest (GoogleTest suites, pytest,
# FreeCAD headless and GUI tests), then the native suites again built with ASan, UBSan and
# _GLIBCXX_ASSERTIONS (scripts/test-sanitize.sh). Exits non-zero on any failure.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
# A cache of this clone's own, empty at first: the Release build fills it and the build without
# MPI (a CTest entry) takes the objects it shares from it; nothing comes from earlier builds.
export CCACHE_DIR="${CCACHE_DIR:-$PWD/build/ccache}"
bash scripts/build.sh
# The sanitizer build compiles beside the main CTest run at the lowest priority: the FreeCAD GUI
# entries leave a core idle for much of their time (FreeCAD waiting in its event loop: 10 s of
# CPU in a 40 s entry), which the build takes, while a busy core gives it a 1.5 % share (nice
# 19), so the tests hardly wait for it. Its own session, so that a failing run stops all of it;
# a new session is a new scheduling autogroup (Linux's sched_autogroup), whose share nice does
# not lower, so the autogroup's own nice is set too. Its log is printed when it ends.
# docs/testing.md "CI time".
sanitize_log=build/sanitize-build.log
LIGHTSOLVER_SANITIZE_STEPS=build setsid bash -c \
  'echo 19 > /proc/self/autogroup 2> /dev/null || true; exec nice -n 19 bash scripts/test-sanitize.sh' \
  > "$sanitize_log" 2>&1 &
sanitize_build=$!
trap 'kill -- -"$sanitize_build" 2> /dev/null || true' EXIT
ctest --test-dir build --output-on-failure -j 2 --timeout 900
echo "test.sh: waiting for the sanitizer build (started beside the main tests)"
sanitize_rc=0
wait "$sanitize_build" || sanitize_rc=$?
trap - EXIT
tail -n 40 "$sanitize_log"
[ "$sanitize_rc" -eq 0 ] || { echo "test.sh: the sanitizer build failed ($sanitize_log)" >&2; exit 1; }
LIGHTSOLVER_SANITIZE_STEPS=test bash scripts/test-sanitize.sh
