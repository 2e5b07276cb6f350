#!/usr/bin/env bash
# The build without MPI (-DLIGHTSOLVER_MPI=OFF) still configures, builds and runs: the CLI and
# the Python module are built in a folder of their own, then the CLI and MPI tests run against
# them (the MPI ones skip; a launcher start is refused clearly).
# Usage: no_mpi.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src="$1"
build="$2"
launcher=()
if command -v ccache > /dev/null; then
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  # The library's, the CLI's and the module's objects do not depend on MPI: compiled with the
  # same flags, from a folder as deep as the main build's (Tests/CMakeLists.txt puts it beside
  # it), they come from the cache the main build filled (scripts/build.sh), paths relative to
  # the source root. Only report_command.cpp (it holds the build folder's path) and the MPI
  # stand-in are compiled again.
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$src}"
fi
mkdir -p "$build"  # its logs go inside it (a folder beside build/ is ignored by git, files not)
cmake -S "$src" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DLIGHTSOLVER_MPI=OFF \
  -DLIGHTSOLVER_BUILD_BENCHMARKS=OFF "${launcher[@]}" > "$build/configure.log"
grep -q "lightsolver: MPI support off" "$build/configure.log" || {
  echo "no_mpi.sh: -DLIGHTSOLVER_MPI=OFF did not turn MPI off"; exit 1; }
cmake --build "$build" -j 2 --target lightsolver_cli lightsolver_python
cli="$build/NativeSolver/cli/lightsolver"
if command -v mpirun > /dev/null; then
  if mpirun --allow-run-as-root -np 2 "$cli" run "$src/Examples/room/room.json" --photons 1000 -q \
      2> "$build/mpirun.log"; then
    echo "no_mpi.sh: a build without MPI ran under mpirun instead of refusing"; exit 1
  fi
  grep -q "built without MPI" "$build/mpirun.log"
fi
PYTHONPATH="$build/NativeSolver/python" LIGHTSOLVER_CLI="$cli" LIGHTSOLVER_SOURCE_DIR="$src" \
  /usr/bin/python3 -m pytest -q -p no:cacheprovider --basetemp "$build/pytest-tmp" \
  "$src/Tests/python/test_cli.py" \
  "$src/Tests/python/test_mpi.py" "$src/Tests/python/test_module.py"
