#pragma once
// Synthetic evaluators for the optimizer tests: a known true function plus Gaussian noise whose
// standard deviation shrinks as 1/sqrt(photons), drawn deterministically from the request's
// seed, exactly like a photon tracer whose estimate depends only on (configuration, photons,
// seed).

#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "lightsolver/optimizer/evaluator.hpp"
#include "lightsolver/statistics.hpp"

namespace lightsolver::optimizer::testing {

/// Standard normal draw by Box-Muller on 53-bit uniforms (portable, unlike
/// std::normal_distribution).
inline double standard_normal(std::uint64_t seed, std::uint64_t stream) {
  std::mt19937_64 g(seed ^ (0x9e3779b97f4a7c15ull * (stream + 1)));
  const double u1 = (static_cast<double>(g() >> 11) + 0.5) * 0x1p-53;
  const double u2 = static_cast<double>(g() >> 11) * 0x1p-53;
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

/// A metric with noise: sigma(photons) = sigma_ref * sqrt(photons_ref / photons).
struct NoisyMetric {
  std::function<double(const std::vector<double>&)> truth;
  double sigma_ref = 1.0;  ///< sigma at photons_ref; 0 makes the metric exact
  std::uint64_t photons_ref = 1;

  double sigma(std::uint64_t photons) const {
    return sigma_ref * std::sqrt(static_cast<double>(photons_ref) / static_cast<double>(photons));
  }

  /// Symmetric CI mean ± z·sigma, as make_estimate() gives for multi-hit tallies.
  Estimate estimate(const std::vector<double>& values, std::uint64_t photons, std::uint64_t seed,
                    std::uint64_t stream, double z) const {
    Estimate e;
    e.sigma = sigma(photons);
    e.mean = truth(values) + e.sigma * standard_normal(seed, stream);
    e.ci_low = e.mean - z * e.sigma;
    e.ci_high = e.mean + z * e.sigma;
    e.hits = photons;
    return e;
  }
};

/// An evaluator made of noisy metrics that records every call.
class SyntheticEvaluator final : public Evaluator {
 public:
  SyntheticEvaluator(NoisyMetric objective, std::vector<NoisyMetric> constraints, double confidence)
      : objective_(std::move(objective)),
        constraints_(std::move(constraints)),
        z_(z_for_confidence(confidence)) {}

  Evaluation evaluate(const EvaluationRequest& r) override {
    ++calls_[{r.cell_index, r.photons}];
    seeds_[{r.cell_index, r.photons}] = r.seed;
    ++total_calls_;
    Evaluation e;
    e.objective = objective_.estimate(r.values, r.photons, r.seed, 0, z_);
    for (std::size_t i = 0; i < constraints_.size(); ++i)
      e.constraints.push_back(constraints_[i].estimate(r.values, r.photons, r.seed, i + 1, z_));
    e.update_seconds = 1e-3;  // pretend costs, so the time split can be checked exactly
    e.trace_seconds = 2e-3;
    return e;
  }

  /// Calls per (cell index, photons).
  const std::map<std::pair<std::uint64_t, std::uint64_t>, int>& calls() const { return calls_; }
  /// Seed received per (cell index, photons).
  const std::map<std::pair<std::uint64_t, std::uint64_t>, std::uint64_t>& seeds() const {
    return seeds_;
  }
  std::uint64_t total_calls() const { return total_calls_; }
  const NoisyMetric& objective() const { return objective_; }
  const NoisyMetric& constraint(std::size_t i) const { return constraints_.at(i); }

 private:
  NoisyMetric objective_;
  std::vector<NoisyMetric> constraints_;
  double z_;
  std::map<std::pair<std::uint64_t, std::uint64_t>, int> calls_;
  std::map<std::pair<std::uint64_t, std::uint64_t>, std::uint64_t> seeds_;
  std::uint64_t total_calls_ = 0;
};

/// Gaussian bump of height `height` centred at (cx, cy) with width w, on top of `base`.
inline double bump(const std::vector<double>& v, double cx, double cy, double w, double height,
                   double base = 0.0) {
  const double dx = v[0] - cx, dy = v[1] - cy;
  return base + height * std::exp(-(dx * dx + dy * dy) / (2.0 * w * w));
}

}  // namespace lightsolver::optimizer::testing
