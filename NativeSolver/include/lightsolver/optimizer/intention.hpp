#pragma once
/// \file intention.hpp
/// Lighting intentions: what to optimise and under which constraints. The engine only sees
/// estimates; the evaluator (the scene integration) computes the metrics named here.
///
/// Feasibility is judged statistically from a constraint's CI at the run's confidence:
/// "met" when the CI lies entirely on the allowed side of the bound, "violated" when entirely
/// on the forbidden side, "uncertain" otherwise. How uncertain candidates are treated is set by
/// UncertainPolicy (see vns.hpp and docs/optimization.md).

#include <string>
#include <vector>

#include "lightsolver/optimizer/isoc.hpp"
#include "lightsolver/statistics.hpp"

namespace lightsolver::optimizer {

/// A quantity the evaluator must estimate for a configuration.
enum class MetricKind {
  kMeanIlluminance,  ///< mean illuminance (lux) of a target (surface or grid)
  kUniformity,       ///< U0 = min cell / mean of a grid target
  kInstalledFlux,    ///< total luminous flux of the luminaires (lm); exact, sigma = 0
  kCustom,           ///< anything else the evaluator understands by `target`
};

/// Which metric of which target.
struct Metric {
  MetricKind kind = MetricKind::kMeanIlluminance;
  std::string target;  ///< target name in the scene (empty for kInstalledFlux)
};

/// Which side of the bound is allowed.
enum class Sense { kAtLeast, kAtMost };

/// metric >= bound (kAtLeast) or metric <= bound (kAtMost).
struct Constraint {
  Metric metric;
  Sense sense = Sense::kAtLeast;
  double bound = 0.0;
};

/// Goal + objective + constraints. The evaluator returns one Estimate per constraint, in order.
struct Intention {
  Goal goal = Goal::kMaximize;
  Metric objective;
  std::vector<Constraint> constraints;
};

/// The paper's problem: maximise the mean illuminance of one target.
Intention maximize_mean_illuminance(std::string target);
/// Minimise the mean illuminance of one target (e.g. glare on a screen).
Intention minimize_mean_illuminance(std::string target);
/// Maximise U0 of a grid subject to its mean illuminance Em >= min_mean_lux.
Intention maximize_uniformity(const std::string& grid, double min_mean_lux);
/// Minimise installed flux subject to Em >= min_mean_lux and U0 >= min_uniformity on a grid.
Intention minimize_installed_flux(const std::string& grid, double min_mean_lux,
                                  double min_uniformity);

/// Statistical verdict on one constraint or on all of them.
enum class Feasibility { kMet, kUncertain, kViolated };

/// "met", "uncertain" or "violated".
const char* to_string(Feasibility f);

/// Verdict from the estimate's CI: kAtLeast is met when ci_low >= bound, violated when
/// ci_high < bound (mirrored for kAtMost).
Feasibility judge(const Estimate& e, const Constraint& c);

/// Per-constraint verdicts. Throws std::invalid_argument if the counts differ.
std::vector<Feasibility> judge_each(const std::vector<Estimate>& e, const Intention& in);

/// The worst verdict over all constraints (kMet when there are none).
Feasibility judge_all(const std::vector<Estimate>& e, const Intention& in);

/// Sum over constraints of the relative amount by which the *mean* misses its bound
/// (0 when every mean is on the allowed side). Steers the search out of infeasible regions;
/// never used to admit anything.
double violation(const std::vector<Estimate>& e, const Intention& in);

}  // namespace lightsolver::optimizer
