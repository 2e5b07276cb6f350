#pragma once
// `lightsolver sunlight SCENE`: EN 17037 sunlight exposure of a scene's reference points
// (lightsolver/sunlight.hpp), without tracing photons.
#include <CLI/CLI.hpp>

namespace lightsolver::cli {

/// Adds the `sunlight` subcommand: a table, one JSON object with --json, a file with --out.
void add_sunlight_command(CLI::App& app);

}  // namespace lightsolver::cli
