#pragma once
// `lightsolver annual SCENE --weather FILE.epw`: a year of daylight by daylight coefficients
// (lightsolver/annual_run.hpp; docs/daylight.md, "Daylight coefficients: a year in one trace").
#include <CLI/CLI.hpp>

namespace lightsolver::cli {

/// Adds the `annual` subcommand: a summary on stdout, annual.json and annual.npz in --out-dir.
void add_annual_command(CLI::App& app);

}  // namespace lightsolver::cli
