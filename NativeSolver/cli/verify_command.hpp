#pragma once
// `lightsolver verify SCENE RESULTS`: whether results belong to a scene (their provenance,
// lightsolver/provenance.hpp). `lightsolver check SCENE`: every error and warning of a scene,
// without tracing (lightsolver/scene_check.hpp).
#include <CLI/CLI.hpp>

namespace lightsolver::cli {

/// Adds the `verify` subcommand: exit status 0 and "results belong to SCENE" when they do, 1
/// with one line per difference (or a read error) when they do not.
void add_verify_command(CLI::App& app);

/// Adds the `check` subcommand: every error and warning, exit status 1 when there is an error.
void add_check_command(CLI::App& app);

}  // namespace lightsolver::cli
