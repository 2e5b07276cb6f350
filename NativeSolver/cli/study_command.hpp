#pragma once
// `lightsolver study SCENE.json`: what accuracy costs, shown (docs/accuracy.md).
#include <CLI/CLI.hpp>

namespace lightsolver::cli {

/// Adds the `study` subcommand to `app`. It runs from its own callback: exit status 0 when
/// done, 1 on an error (printed), 130 when interrupted (the rows so far are still written).
void add_study_command(CLI::App& app);

}  // namespace lightsolver::cli
