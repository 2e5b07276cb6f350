#pragma once
/// \file rescale.hpp
/// Dimming luminaire groups without tracing (docs/statistics.md, "Groups"): illuminance is
/// linear in each group's flux and each group was traced with its own photon stream, so a
/// results document with per-group contributions gives the results of any dimming levels.
#include <string>
#include <utility>
#include <vector>

#include "lightsolver/solver.hpp"

namespace lightsolver {

/// Dimming factors by group name: 0 switches a group off, 0.5 halves its flux, 2 doubles it.
using GroupFactors = std::vector<std::pair<std::string, double>>;

/// The results of `results_json` (format lightsolver.results/1, traced with contributions:
/// `--contributions`, settings.contributions) with each group's flux multiplied by its factor
/// (groups not listed keep theirs): estimates, intervals, grid statistics, glare and verdicts
/// recomputed from the per-group tallies by the code that builds a traced result, and
/// `rescaled` recording every group's factor (times those of an earlier rescale). Throws
/// InputError (with `source` as the file) for results without contributions, an unknown
/// group, a repeated group, or a factor that is negative or not finite.
std::string rescale_results_json(const std::string& results_json, const GroupFactors& factors,
                                 const std::string& source = "");

/// rescale_results_json(), as Results (results_to_json() gives the text).
Results rescale_results(const std::string& results_json, const GroupFactors& factors,
                        const std::string& source = "");

}  // namespace lightsolver
