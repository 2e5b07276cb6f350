#pragma once
// Results::effects in the results JSON and in the CLI's text (results_io.cpp calls these).
#include <nlohmann/json.hpp>
#include <string>

#include "lightsolver/solver.hpp"

namespace lightsolver::detail {

/// {"simulated": [names], "skipped": [{"effect": name, "reason": why}]}.
nlohmann::json effects_json(const EffectsReport& effects);

/// "simulated: interreflection, diffuse reflection, ...", then one line per skipped effect,
/// "no glass: refraction not simulated".
/// One line naming what was simulated and how many effects the scene did not need; with
/// `list_skipped`, a line per skipped effect with its reason ("no glass: refraction not
/// simulated").
std::string effects_lines(const EffectsReport& effects, bool list_skipped);

}  // namespace lightsolver::detail
