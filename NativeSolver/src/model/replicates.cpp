#include "model/replicates.hpp"

#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "model/groups.hpp"

namespace lightsolver::detail {

double student_t_for_z(double z, std::uint32_t dof) {
  if (!(z >= 0.0 && std::isfinite(z))) throw std::invalid_argument("student_t_for_z: bad z");
  if (dof < 1) throw std::invalid_argument("student_t_for_z: needs a degree of freedom");
  thread_local double cached_z = -1.0, t = 0.0;
  thread_local std::uint32_t cached_dof = 0;
  if (z != cached_z || dof != cached_dof) {
    // The tail beyond z on one side, from erfc (precise for tiny tails), kept above the
    // smallest normal double so that the quantile stays finite for any finite z.
    const double tail =
        std::max(0.5 * std::erfc(z / std::sqrt(2.0)), std::numeric_limits<double>::min());
    const boost::math::students_t_distribution<double> dist(dof);
    t = boost::math::quantile(boost::math::complement(dist, tail));
    cached_z = z;
    cached_dof = dof;
  }
  return t;
}

Estimate replicate_interval(std::span<const double> values, double z, std::uint64_t hits) {
  const std::size_t r = values.size();
  if (r < 2) throw std::invalid_argument("replicate_interval: needs 2 replicates or more");
  double mean = 0.0;
  for (const double v : values) mean += v;
  mean /= double(r);
  double squares = 0.0;
  for (const double v : values) squares += (v - mean) * (v - mean);
  Estimate e;
  e.mean = mean;
  e.hits = hits;
  e.sigma = std::sqrt(squares / double(r - 1) / double(r));
  const double half = student_t_for_z(z, static_cast<std::uint32_t>(r - 1)) * e.sigma;
  e.ci_low = std::min(std::max(0.0, mean - half), mean);
  e.ci_high = std::max(mean + half, mean);
  if (!(std::isfinite(e.mean) && std::isfinite(e.sigma) && std::isfinite(e.ci_high))) {
    throw std::overflow_error("replicate estimate: non-finite value");
  }
  return e;
}

Estimate replicate_estimate(const GroupedTallies& t, std::optional<std::size_t> group,
                            std::uint32_t bin, double area_m2, double z) {
  const std::size_t groups = t.photons.size(), r_count = t.replicates;
  std::vector<double> values(r_count, 0.0);
  std::uint64_t hits = 0, direct_lit = 0;
  double zero_hit_high = 0.0;  // each group's zero-hit bound, summed (conservative)
  double direct_lux = 0.0, direct_variance = 0.0;  // the shared direct parts, summed
  bool lit = false, photons_count = false, has_direct = false;
  for (std::size_t g = 0; g < groups; ++g) {
    if (group && g != *group) continue;
    // Every replicate traced the same photons of each group: its total over R.
    const std::uint64_t per = t.photons[g] / r_count;
    if (per == 0 || !(t.flux_lm[g] > 0.0)) continue;
    lit = true;
    const bool direct_part = t.has_direct_part(g);
    if (direct_part) {
      has_direct = true;
      // One direct part per group, shared by the replicates and independent of all of them
      // (docs/statistics.md, "Quasi-random photons"): added once, its variance in quadrature.
      const DirectPart& d = (*t.direct)[g * t.bin_count + bin];
      direct_lux += d.lux * t.direct_scale[g];
      direct_variance += d.variance * t.direct_scale[g] * t.direct_scale[g];
      direct_lit += d.lit;
      // Where nothing reflects, the group's photons deposit nothing, exactly.
      if (!t.photons_reflect) continue;
    }
    photons_count = true;
    const double scale = t.flux_lm[g] / area_m2;
    for (std::size_t r = 0; r < r_count; ++r) {
      const Tally& c = (*t.bins)[(r * groups + g) * t.bin_count + bin];
      values[r] += scale * double(c.sum) / double(per);
      hits += c.sum;
    }
    zero_hit_high += scale * wilson_interval(0, t.photons[g], z).second;
  }
  if (!lit) return Estimate{};  // no light: exactly zero
  // The photon part: exactly zero where only direct parts are left.
  Estimate e;
  if (photons_count) {
    e = replicate_interval(values, z, hits);
    if (hits == 0) e.ci_high = zero_hit_high;
  }
  if (!has_direct) return e;
  return with_direct_part(e, direct_lux, direct_variance, direct_lit, z);
}

}  // namespace lightsolver::detail
