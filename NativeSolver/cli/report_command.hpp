#pragma once
// `lightsolver report SCENE.json [--results R.json] --out report.pdf|.html`: the calculation
// report, made by the Python package lightsolver_report (NativeSolver/python/).
#include <CLI/CLI.hpp>

namespace lightsolver::cli {

/// Adds the `report` subcommand to `app`. It runs from its own callback by replacing this
/// process with `python3 -m lightsolver_report ...` (its exit status is the command's); a
/// missing interpreter or package is an error (status 1) that says what to install or set.
/// PYTHONPATH: LIGHTSOLVER_PYTHONPATH if set, else the build's module folder and the package's
/// source folder (compiled in); the interpreter: LIGHTSOLVER_PYTHON, else /usr/bin/python3.
void add_report_command(CLI::App& app);

}  // namespace lightsolver::cli
