#pragma once
// The results JSON of luminaire groups: the top-level `groups` and `luminaires` lists,
// `rescaled`, and each target's `contributions` (with the integer tallies `rescale` rebuilds
// every interval from).
#include <nlohmann/json.hpp>

#include "lightsolver/solver.hpp"

namespace lightsolver::detail {

/// Adds `groups` and `luminaires` (always) and `rescaled` (a rescaled result) to the results
/// object.
void add_groups_json(const Results& r, nlohmann::json& j);

/// Adds the target's `contributions` object (keyed by group), when it has any.
void add_contributions_json(const TargetResult& t, nlohmann::json& j);

}  // namespace lightsolver::detail
