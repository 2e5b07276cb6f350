#pragma once
// The results JSON of luminaire groups: the top-level `groups` and `luminaires` lists,
// `rescaled`, and each target's `contributions` (with the integer tallies `rescale` rebuilds
// every interval from).
#include <nlohmann/json.hpp>

#include "io/json_reader.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver::detail {

/// Adds `groups` and `luminaires` (always) and `rescaled` (a rescaled result) to the results
/// object.
void add_groups_json(const Results& r, nlohmann::json& j);

/// Adds the target's `contributions` object (keyed by group), when it has any.
void add_contributions_json(const TargetResult& t, nlohmann::json& j);

/// The inverse of add_groups_json (results_from_json): `groups`, `luminaires` and `rescaled`
/// (in group order) of the results object `root`, where present; InputError naming the field.
void read_groups_json(const JsonNode& root, Results& r);

/// The inverse of add_contributions_json: target `n`'s contributions in the order of
/// `groups` (the JSON keys them by name), with their tallies (an observer grid's per point;
/// `t` says which kind of target it is).
std::vector<Contribution> read_contributions_json(const JsonNode& n, const TargetResult& t,
                                                  const std::vector<GroupResult>& groups);

}  // namespace lightsolver::detail
