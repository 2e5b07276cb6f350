#!/usr/bin/env bash
# Configures and builds everything (library, CLI, Python module, tests) into build/.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
# Through ccache when it is installed (a launcher given in "$@" wins): the test build_without_mpi
# builds the library, CLI and module again without MPI and takes their objects from the cache
# (Tests/build/no_mpi.sh). Paths relative to the source root, so another folder hits too.
launcher=()
if command -v ccache > /dev/null && [[ " $* " != *COMPILER_LAUNCHER* ]]; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$PWD}"
fi
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" "$@"
cmake --build build -j "$jobs"
