#include "lightsolver/optimizer/intention.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lightsolver::optimizer {

namespace {

Intention mean_illuminance(Goal goal, std::string target) {
  Intention in;
  in.goal = goal;
  in.objective = {MetricKind::kMeanIlluminance, std::move(target)};
  return in;
}

void check_sizes(const std::vector<Estimate>& e, const Intention& in) {
  if (e.size() != in.constraints.size())
    throw std::invalid_argument("optimizer: evaluator returned " + std::to_string(e.size()) +
                                " constraint estimates, the intention has " +
                                std::to_string(in.constraints.size()));
}

}  // namespace

Intention maximize_mean_illuminance(std::string target) {
  return mean_illuminance(Goal::kMaximize, std::move(target));
}

Intention minimize_mean_illuminance(std::string target) {
  return mean_illuminance(Goal::kMinimize, std::move(target));
}

Intention maximize_uniformity(const std::string& grid, double min_mean_lux) {
  Intention in;
  in.goal = Goal::kMaximize;
  in.objective = {MetricKind::kUniformity, grid};
  in.constraints.push_back({{MetricKind::kMeanIlluminance, grid}, Sense::kAtLeast, min_mean_lux});
  return in;
}

Intention minimize_installed_flux(const std::string& grid, double min_mean_lux,
                                  double min_uniformity) {
  Intention in;
  in.goal = Goal::kMinimize;
  in.objective = {MetricKind::kInstalledFlux, ""};
  in.constraints.push_back({{MetricKind::kMeanIlluminance, grid}, Sense::kAtLeast, min_mean_lux});
  in.constraints.push_back({{MetricKind::kUniformity, grid}, Sense::kAtLeast, min_uniformity});
  return in;
}

const char* to_string(Feasibility f) {
  switch (f) {
    case Feasibility::kMet:
      return "met";
    case Feasibility::kUncertain:
      return "uncertain";
    case Feasibility::kViolated:
      return "violated";
  }
  return "?";
}

Feasibility judge(const Estimate& e, const Constraint& c) {
  if (c.sense == Sense::kAtLeast) {
    if (e.ci_low >= c.bound) return Feasibility::kMet;
    if (e.ci_high < c.bound) return Feasibility::kViolated;
  } else {
    if (e.ci_high <= c.bound) return Feasibility::kMet;
    if (e.ci_low > c.bound) return Feasibility::kViolated;
  }
  return Feasibility::kUncertain;
}

std::vector<Feasibility> judge_each(const std::vector<Estimate>& e, const Intention& in) {
  check_sizes(e, in);
  std::vector<Feasibility> out(e.size());
  for (std::size_t i = 0; i < e.size(); ++i) out[i] = judge(e[i], in.constraints[i]);
  return out;
}

Feasibility judge_all(const std::vector<Estimate>& e, const Intention& in) {
  Feasibility worst = Feasibility::kMet;
  for (Feasibility f : judge_each(e, in)) worst = std::max(worst, f);  // enum order = severity
  return worst;
}

double violation(const std::vector<Estimate>& e, const Intention& in) {
  check_sizes(e, in);
  double v = 0.0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    const Constraint& c = in.constraints[i];
    const double miss = c.sense == Sense::kAtLeast ? c.bound - e[i].mean : e[i].mean - c.bound;
    // Relative so that lux and U0 constraints weigh alike; a zero bound falls back to absolute.
    if (miss > 0.0) v += miss / (c.bound != 0.0 ? std::abs(c.bound) : 1.0);
  }
  return v;
}

}  // namespace lightsolver::optimizer
