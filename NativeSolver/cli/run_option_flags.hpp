#pragma once
// The run options' flags (`--photons`, `--confidence`, ...), made from the run options table
// (lightsolver/run_options.hpp): names, help and ranges, with the library's range message.
#include <CLI/CLI.hpp>

#include "lightsolver/solver.hpp"

namespace lightsolver::cli {

/// Adds the flag of every table row that has one, bound to `options` (a flag left out leaves
/// the member unset: the scene's setting applies). `checkpointed`: only the rows that `cost`
/// and `study` take (seed, confidence, threads, backend).
void add_run_option_flags(CLI::App* command, SolveOptions& options, bool checkpointed = false);

/// The flag of run option `name` ("target_accuracy" -> "--accuracy").
const char* flag_of(const char* name);

}  // namespace lightsolver::cli
