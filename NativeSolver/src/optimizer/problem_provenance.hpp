#pragma once
// The provenance of a search (docs/optimization.md, "Provenance and configurations"): the
// results' provenance object with the search's own settings, the optimization block's hash and
// the domain searched.
#include <chrono>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "lightsolver/optimizer/scene_problem.hpp"

namespace lightsolver::optimizer {

/// What a search records: the base scene's source (scene_sha256 null for a scene built or
/// changed in memory), the build, the backend and device, processes and threads, the resolved
/// search settings `search` (photon counts, confidence, seed, limits, rules), reuse, the
/// next-event setting and spacing, whether N was to be matched to photon-only widths
/// (`match_widths`; `width_factor` the factor applied, once the search traced with N), the
/// times, host and command.
Provenance search_provenance(const SceneProblem& problem, const VnsOptions& search,
                             bool reuse_traces, const std::string& next_event,
                             const std::string& backend, const std::string& device, int threads,
                             int mpi_ranks, const std::string& command,
                             std::chrono::system_clock::time_point started,
                             std::chrono::system_clock::time_point finished, bool match_widths,
                             std::optional<double> width_factor = std::nullopt);

/// The output's "provenance" object: the results' fields (provenance_json) with
/// `optimization_sha256` (the block searched) and `domain` (each variable's name and cells,
/// with its range or levels: how a member's cells give its values).
nlohmann::ordered_json search_provenance_json(const SceneProblem& problem, const Provenance& p);

}  // namespace lightsolver::optimizer
