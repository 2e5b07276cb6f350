#pragma once
/// \file statistics.hpp
/// Illuminance estimates with confidence intervals, and the comparison operators of
/// Avas & Fernández (Eq. 7-9) used by the optimizer.
///
/// Every photon carries the same power, so a tally is a count. Per photon path we know how many
/// times it deposited on a bin (c_i); a bin keeps S = sum c_i and Q = sum c_i^2 over paths.
/// The estimate is E = scale * S / N with scale = Phi_total / area, and its standard error comes
/// from the sample variance of the per-path totals, (N Q - S^2) / (N^2 (N-1)), computed exactly
/// in 128-bit integers. That stays honest when a path hits a bin many times (reflective rooms),
/// where the binomial formula of the paper underestimates the variance.

#include <cstdint>
#include <utility>

namespace lightsolver {

/// One bin's integer tally.
struct Tally {
  std::uint64_t sum = 0;     ///< S: total deposits (= hits)
  std::uint64_t sum_sq = 0;  ///< Q: sum over paths of (deposits of that path)^2
};

/// An estimate with its two-sided confidence interval (same unit as `mean`, e.g. lux).
struct Estimate {
  double mean = 0.0;
  double sigma = 0.0;  ///< estimated standard deviation of `mean`
  double ci_low = 0.0;
  double ci_high = 0.0;
  std::uint64_t hits = 0;
  bool binomial = false;  ///< no path deposited twice: the Wilson interval was used
};

/// Wilson score interval for `hits` successes in `n` trials at critical value `z`, as fractions
/// (multiply by the estimate's scale). Always 0 <= low <= hits/n <= high <= 1 in double (the
/// fraction computed as double(hits) / double(n)); exactly 0 at zero hits and exactly 1 at
/// n hits. [0, 1] for n = 0; throws std::invalid_argument for hits > n.
std::pair<double, double> wilson_interval(std::uint64_t hits, std::uint64_t n, double z);

/// Largest photon count of one run, whatever max_bounces (docs/statistics.md, "Overflow").
inline constexpr std::uint64_t kMaxPhotons = 10'000'000'000'000ull;

/// Largest photon count whose 64-bit tallies cannot overflow: min(kMaxPhotons,
/// (2^64 - 1) / (max_bounces + 1)^2), since a path deposits at most max_bounces + 1 times on a bin.
std::uint64_t max_photons(std::uint32_t max_bounces);

/// Two-sided standard-normal critical value: P(|Z| <= z) = confidence (0.95 -> 1.95996).
double z_for_confidence(double confidence);

/// Estimate from a tally over `paths` photon paths. `scale` converts a per-path mean deposit to
/// the reported unit (lux: Phi_total / area). If no path deposited twice, the counts are
/// binomial and the Wilson score interval is used; otherwise mean ± z·sigma (clamped at 0).
/// Invariant: ci_low <= mean <= ci_high, ci_low >= 0, all finite. Throws std::invalid_argument
/// for a negative or non-finite scale, std::overflow_error if a number would not be finite.
Estimate make_estimate(const Tally& t, std::uint64_t paths, double scale, double confidence);

/// Two-sided standard-normal critical value for P(|Z| > z) = alpha, precise for tiny alpha.
double z_for_alpha(double alpha);

/// make_estimate() at the critical value `z` instead of a confidence (z_for_alpha gives it for
/// the small alphas of simultaneous intervals).
Estimate make_estimate_z(const Tally& t, std::uint64_t paths, double scale, double z);

/// Outcome of comparing two estimates at a confidence level.
enum class Relation { Greater, Less, Indistinguishable };

/// Eq. 7-9: x >α y iff E(x) - E(y) > z·sqrt(σx² + σy²); <α symmetric; otherwise =α.
Relation compare(const Estimate& x, const Estimate& y, double confidence);

inline bool greater_alpha(const Estimate& x, const Estimate& y, double c) {
  return compare(x, y, c) == Relation::Greater;
}
inline bool less_alpha(const Estimate& x, const Estimate& y, double c) {
  return compare(x, y, c) == Relation::Less;
}
inline bool equal_alpha(const Estimate& x, const Estimate& y, double c) {
  return compare(x, y, c) == Relation::Indistinguishable;
}
inline bool distinguishable_alpha(const Estimate& x, const Estimate& y, double c) {
  return !equal_alpha(x, y, c);
}

}  // namespace lightsolver
