#pragma once
// Verdicts of a run's targets, and the `decide` stopping rule with its cost estimates: the
// Simulation's loop calls these (docs/statistics.md, "Deciding").
#include <vector>

#include "lightsolver/solver.hpp"

namespace lightsolver::detail {

/// Whether a run judges requirements (some target has them), and checks a decide request:
/// InputError when deciding is asked without requirements or together with an accuracy goal.
bool judges_requirements(const Scene& scene, bool decide, bool accuracy_goal);

/// The confidence at which a decide run judges its verdicts at look `look` (1, 2, ...):
/// 1 - alpha * 6 / (pi^2 look^2), so the error rates of all looks add up to at most alpha
/// (alpha spending; docs/statistics.md, "Deciding"): stopping at the first decided look does
/// not make a wrong verdict likelier than one look at `confidence` would.
double look_confidence(double confidence, int look);

/// Sets each target's verdicts and overall verdict (targets with requirements; grids need
/// their intervals filled) and the run's overall verdict.
void add_verdicts(Results& r);

/// True when no verdict of `targets` (with verdicts added) is undecided.
bool all_decided(std::vector<TargetResult>& targets);

/// For each undecided verdict: photons (of a whole run) and tracing seconds estimated to decide
/// it, from interval width ~ N^-1/2 and the run's rate of `photons_per_second` (0: unknown).
void add_to_decide(Results& r, double photons_per_second);

/// Photons a decide run is expected to trace in all: the most any undecided verdict of
/// `targets` needs at `photons` traced, within [photons, budget]; the budget when one cannot be
/// estimated.
std::uint64_t photons_to_decide_all(std::vector<TargetResult>& targets, std::uint64_t photons,
                                    std::uint64_t budget);

/// Photons a run would need for an interval [low, high] around `value` (from `photons`) to
/// exclude or clear `required`: photons * (w / |value - required|)^2, w the half-width on
/// the side facing the bound. Empty when the value sits on the bound or nothing was traced.
std::optional<double> photons_to_decide(double value, double low, double high, double required,
                                        std::uint64_t photons);

}  // namespace lightsolver::detail
