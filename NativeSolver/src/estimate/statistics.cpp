#include "lightsolver/statistics.hpp"

#include <algorithm>
#include <boost/math/constants/constants.hpp>
#include <boost/math/special_functions/erf.hpp>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace lightsolver {

double z_for_confidence(double confidence) {
  if (!(confidence > 0.0 && confidence < 1.0)) {
    throw std::invalid_argument("confidence must lie in (0, 1)");
  }
  // z = sqrt(2) erf^-1(confidence). Near 1 the inverse of the complement keeps full relative
  // precision (1 - confidence is exact there, Sterbenz); below 0.5 erf^-1 itself does, where
  // 1 - confidence would round. Boost evaluates both in long double, so z is within about one
  // ulp (docs/statistics.md).
  using boost::math::constants::root_two;
  const double t =
      confidence < 0.5 ? boost::math::erf_inv(confidence) : boost::math::erfc_inv(1.0 - confidence);
  return root_two<double>() * t;
}

namespace {

// z of the last confidence this thread asked for: make_estimate runs per grid cell and the
// optimizer compares thousands of times, always at the run's one confidence.
double cached_z(double confidence) {
  thread_local double cached_confidence = -1.0, z = 0.0;
  if (confidence != cached_confidence) {
    z = z_for_confidence(confidence);  // throws before the cache changes
    cached_confidence = confidence;
  }
  return z;
}

// Per-path sample variance of the mean, (N Q - S^2) / (N^2 (N - 1)), with an exact integer
// numerator: the textbook Q/N - mean^2 cancels catastrophically when most paths deposit alike.
double variance_of_mean(const Tally& t, std::uint64_t n) {
  if (n < 2) return 0.0;
  const unsigned __int128 nq = static_cast<unsigned __int128>(n) * t.sum_sq;
  const unsigned __int128 s2 = static_cast<unsigned __int128>(t.sum) * t.sum;
  const double numerator = nq > s2 ? static_cast<double>(nq - s2) : 0.0;  // >= 0 by Cauchy-Schwarz
  const double nd = static_cast<double>(n);
  return numerator / nd / nd / (nd - 1.0);
}

}  // namespace

std::pair<double, double> wilson_interval(std::uint64_t hits, std::uint64_t n, double z) {
  if (hits > n) throw std::invalid_argument("wilson_interval: more hits than trials");
  if (n == 0) return {0.0, 1.0};  // no trial, no information
  const double nd = static_cast<double>(n), p = static_cast<double>(hits) / nd;
  const double z2n = z * z / nd;
  const double centre = (p + 0.5 * z2n) / (1.0 + z2n);
  const double half = z / (1.0 + z2n) * std::sqrt(p * (1.0 - p) / nd + 0.25 * z2n / nd);
  // The Wilson interval is the set of q with |p - q| <= z sqrt(q (1 - q) / n): it lies in [0, 1]
  // and holds p itself, exactly 0 at zero hits and exactly 1 at n hits. Rounding the centre and
  // half-width can miss those by a few ulps (at p = 1 the upper end came out one ulp below 1), so
  // the edges are set exactly and the bounds clamped to [0, p] and [p, 1]: honest, because the
  // exact bounds lie there and the clamp moves a rounded bound by those few ulps only.
  const double low = hits == 0 ? 0.0 : centre - half;
  const double high = hits == n ? 1.0 : centre + half;
  return {std::clamp(low, 0.0, p), std::clamp(high, p, 1.0)};
}

std::uint64_t max_photons(std::uint32_t max_bounces) {
  // A path traces at most max_bounces + 1 segments and deposits at most once per segment on a
  // bin, so c <= B + 1 and Q = sum c^2 <= N (B + 1)^2 (S and the ray-segment count are smaller).
  const unsigned __int128 per_path =
      static_cast<unsigned __int128>(max_bounces + 1ull) * (max_bounces + 1ull);
  const unsigned __int128 fits = std::numeric_limits<std::uint64_t>::max() / per_path;
  return static_cast<std::uint64_t>(std::min<unsigned __int128>(fits, kMaxPhotons));
}

namespace {

bool finite(const Estimate& e) {
  return std::isfinite(e.mean) && std::isfinite(e.sigma) && std::isfinite(e.ci_low) &&
         std::isfinite(e.ci_high);
}

}  // namespace

Estimate make_estimate(const Tally& t, std::uint64_t paths, double scale, double confidence) {
  return make_estimate_z(t, paths, scale, cached_z(confidence));
}

double z_for_alpha(double alpha) {
  if (!(alpha > 0.0 && alpha < 1.0)) throw std::invalid_argument("alpha must lie in (0, 1)");
  // erfc^-1 of alpha itself: full relative precision for the tiny alphas of simultaneous
  // intervals over many cells (1 - alpha would round there).
  return boost::math::constants::root_two<double>() * boost::math::erfc_inv(alpha);
}

Estimate make_estimate_z(const Tally& t, std::uint64_t paths, double scale, double z) {
  if (!(scale >= 0.0 && std::isfinite(scale))) {
    throw std::invalid_argument("make_estimate: scale must be finite and >= 0");
  }
  if (!(z >= 0.0 && std::isfinite(z))) throw std::invalid_argument("make_estimate: bad z");
  Estimate e;
  e.hits = t.sum;
  if (paths == 0) return e;
  const double n = static_cast<double>(paths);
  const double p = static_cast<double>(t.sum) / n;
  e.mean = scale * p;
  if (t.sum_sq == t.sum && t.sum <= paths) {
    // Each path deposited at most once (c_i in {0,1} <=> Q == S): binomial counts, for which
    // the Wilson score interval keeps its coverage at small and zero counts. Its fractions hold
    // p, and multiplying by scale > 0 rounds monotonically, so the bounds hold the mean.
    const auto [low, high] = wilson_interval(t.sum, paths, z);
    e.binomial = true;
    e.sigma = scale * std::sqrt(std::max(0.0, p * (1.0 - p)) / n);
    e.ci_low = scale * low;
    e.ci_high = scale * high;
  } else {
    e.sigma = scale * std::sqrt(variance_of_mean(t, paths));
    e.ci_low = std::max(0.0, e.mean - z * e.sigma);  // a - b <= a in floating point for b >= 0
    e.ci_high = e.mean + z * e.sigma;
  }
  // Containment by construction above; kept as an invariant here so no later change can break
  // it. Non-finite numbers cannot arise from validated scenes (docs/statistics.md, "Ranges"):
  // reaching this throw means a bug, which must not reach a results file as inf or NaN.
  e.ci_low = std::min(e.ci_low, e.mean);
  e.ci_high = std::max(e.ci_high, e.mean);
  if (!finite(e)) {
    throw std::overflow_error("make_estimate: non-finite estimate (scale " + std::to_string(scale) +
                              ", " + std::to_string(t.sum) + " hits)");
  }
  return e;
}

Relation compare(const Estimate& x, const Estimate& y, double confidence) {
  const double threshold = cached_z(confidence) * std::hypot(x.sigma, y.sigma);
  const double diff = x.mean - y.mean;
  if (diff > threshold) return Relation::Greater;
  if (-diff > threshold) return Relation::Less;
  return Relation::Indistinguishable;
}

}  // namespace lightsolver
