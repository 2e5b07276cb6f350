#pragma once
// `lightsolver sun`: the sun's position for a site and a time (lightsolver/daylight.hpp).
// `lightsolver weather FILE.epw`: a weather file's location and EN 17037's median external
// diffuse illuminance (lightsolver/weather.hpp).
#include <CLI/CLI.hpp>

namespace lightsolver::cli {

/// Adds the `sun` subcommand: the position as text, or as one JSON object with --json.
void add_sun_command(CLI::App& app);

/// Adds the `weather` subcommand: location, hours and the median diffuse illuminance.
void add_weather_command(CLI::App& app);

}  // namespace lightsolver::cli
