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
ctest --test-dir build --output-on-failure -j 2 --timeout 900
bash scripts/test-sanitize.sh
