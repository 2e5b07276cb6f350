#pragma once
// `lightsolver optimize SCENE.json`: the inverse-lighting search on a scene's optimization block.
#include <CLI/CLI.hpp>

namespace lightsolver::cli {

/// Adds the `optimize` subcommand to `app`. It runs from its own callback: exit status 0 when
/// done, 1 on an error (printed), 130 when interrupted (the ISOC found so far is still written).
void add_optimize_command(CLI::App& app);

}  // namespace lightsolver::cli
