#pragma once
// Shared helpers for the photometry tests: paths, error expectations, histogram statistics.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "lightsolver/photometry.hpp"

namespace lightsolver::test {

inline std::string repo_path(const std::string& relative) {
  return std::string(LIGHTSOLVER_SOURCE_DIR) + "/" + relative;
}
inline std::string sample_file(const std::string& name) {
  return repo_path("Resources/luminaires/" + name);
}
inline std::string corpus_file(const std::string& name) {
  return repo_path("Tests/fuzz/corpus/" + name);
}

/// Expects `f` to throw InputError at `line` (0: any place) whose message contains `needle`.
inline void expect_input_error(const std::function<void()>& f, int line,
                               const std::string& needle) {
  try {
    f();
    ADD_FAILURE() << "expected an InputError containing '" << needle << "'";
  } catch (const InputError& e) {
    if (line > 0) EXPECT_EQ(e.where(), "line " + std::to_string(line)) << e.what();
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

/// Joins lines with CR LF, as LM-63 and EULUMDAT files are written.
inline std::string join_lines(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\r\n";
  return out;
}

/// Equal-solid-angle bins over the sphere: n_mu bands of -z (cos gamma), n_phi sectors of
/// atan2(y, x).
struct SphereBins {
  int n_mu = 12, n_phi = 16;
  int count() const { return n_mu * n_phi; }
  int index(const glm::dvec3& d) const {
    const double mu = std::clamp(-d.z, -1.0, 1.0);
    double phi = std::atan2(d.y, d.x);
    if (phi < 0) phi += 2 * std::numbers::pi;
    const int i = std::min(n_mu - 1, static_cast<int>((mu + 1.0) / 2.0 * n_mu));
    const int j = std::min(n_phi - 1, static_cast<int>(phi / (2 * std::numbers::pi) * n_phi));
    return i * n_phi + j;
  }
};

/// Probability of each bin under intensity I(d): integral of I over the bin (midpoint rule,
/// m x m points per bin, uniform in (cos gamma, phi) = uniform in solid angle) / total flux.
inline std::vector<double> expected_probabilities(const SphereBins& bins,
                                                  const std::function<double(glm::dvec3)>& I,
                                                  double total_flux_lm, int m = 24) {
  std::vector<double> p(bins.count(), 0.0);
  const double dmu = 2.0 / bins.n_mu / m, dphi = 2 * std::numbers::pi / bins.n_phi / m;
  for (int i = 0; i < bins.n_mu * m; ++i) {
    const double mu = -1.0 + (i + 0.5) * dmu, s = std::sqrt(1 - mu * mu);
    for (int j = 0; j < bins.n_phi * m; ++j) {
      const double phi = (j + 0.5) * dphi;
      const glm::dvec3 d{s * std::cos(phi), s * std::sin(phi), -mu};
      p[(i / m) * bins.n_phi + j / m] += I(d) * dmu * dphi / total_flux_lm;
    }
  }
  return p;
}

/// Largest |observed - expected| / sigma over the bins, with multinomial sigma
/// sqrt(N p (1 - p)). Bins expecting fewer than 20 counts are pooled into one, so the normal
/// approximation holds; a bin with p = 0 must stay empty (returns infinity otherwise).
inline double max_z_score(const std::vector<long>& observed, const std::vector<double>& p, long n) {
  double worst = 0.0, pooled_p = 0.0;
  long pooled_obs = 0;
  for (std::size_t b = 0; b < p.size(); ++b) {
    if (p[b] <= 0.0 && observed[b] > 0) return INFINITY;
    if (p[b] * n < 20.0) {
      pooled_p += p[b];
      pooled_obs += observed[b];
      continue;
    }
    const double sigma = std::sqrt(n * p[b] * (1 - p[b]));
    worst = std::max(worst, std::abs(observed[b] - n * p[b]) / sigma);
  }
  if (pooled_p * n >= 1.0) {
    const double sigma = std::sqrt(n * pooled_p * (1 - pooled_p));
    worst = std::max(worst, std::abs(pooled_obs - n * pooled_p) / sigma);
  } else if (pooled_obs > 5) {
    return INFINITY;  // essentially nothing expected there, yet several samples landed
  }
  return worst;
}

/// Histogram of n sampled directions (fixed seed).
inline std::vector<long> sample_histogram(const PhotometricSampler& s, const SphereBins& bins,
                                          long n, std::uint64_t seed) {
  std::vector<long> h(bins.count(), 0);
  for (long k = 0; k < n; ++k) {
    PathRng rng(seed, static_cast<std::uint64_t>(k));
    ++h[bins.index(s.sample_direction(rng))];
  }
  return h;
}

// Per-bin bound: with ~200 bins, |z| > 5 happens by chance with probability ~1e-4 in total
// (Bonferroni), so the tests are not flaky at any seed, let alone the fixed ones used.
inline constexpr double kZLimit = 5.0;

}  // namespace lightsolver::test
