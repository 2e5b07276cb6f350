#pragma once
// `lightsolver skymtx FILE.epw`: a year of sky vectors (lightsolver/sky_patches.hpp), Radiance's
// gendaymtx analogue, written as a numpy .npz (docs/daylight.md, "Sky patches and sky vectors").
#include <CLI/CLI.hpp>

namespace lightsolver::cli {

/// Adds the `skymtx` subcommand: a summary, and with --out the arrays as an .npz file.
void add_skymtx_command(CLI::App& app);

}  // namespace lightsolver::cli
