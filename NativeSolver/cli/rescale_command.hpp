#pragma once
// `lightsolver rescale RESULTS.json --dim G=0.5 ...`: other dimming levels of luminaire groups
// from one traced result, without tracing (docs/statistics.md, "Groups").
#include <CLI/CLI.hpp>

namespace lightsolver::cli {

/// Adds the `rescale` subcommand to `app`. It runs from its own callback: exit status 0 when
/// done, 1 on an error (printed).
void add_rescale_command(CLI::App& app);

}  // namespace lightsolver::cli
