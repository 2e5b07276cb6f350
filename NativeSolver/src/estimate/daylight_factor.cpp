// Daylight factor of a grid: the sky group's tallies alone over the sky's outside illuminance.
#include "estimate/daylight_factor.hpp"

#include <algorithm>

#include "types/sky_daylight.hpp"

namespace lightsolver::detail {
namespace {

// Every field of `e` times f > 0: multiplying rounds monotonically, so the interval still
// holds the mean.
Estimate scaled(Estimate e, double f) {
  e.mean *= f;
  e.sigma *= f;
  e.ci_low *= f;
  e.ci_high *= f;
  return e;
}

}  // namespace

DaylightFactorResult daylight_factor_result(const TargetTallies& tt) {
  const DaylightFactorBasis& b = *tt.daylight;
  // The sky's part at the flux it was traced with: a rescale that dims the sky dims E_out with
  // it, so D does not move (and a sky dimmed to 0 keeps its daylight factor).
  GroupedTallies sky = tt.tallies;
  sky.flux_lm.at(b.group) = b.sky_flux_lm;
  const double percent = 100.0 / b.outside_lx;
  const auto estimate = [&](std::uint32_t bin, double z) {
    Estimate e = sky.group_estimate_z(b.group, bin, tt.bins[bin].area_m2, z);
    // No photon of the sky traced yet (a run of fewer photons than groups): nothing is known,
    // so not [0, 0] but Wilson's [0, 1] of no trial, times the scale.
    if (sky.photons.at(b.group) == 0) e.ci_high = b.sky_flux_lm / tt.bins[bin].area_m2;
    return scaled(e, percent);
  };
  const PreparedTarget& at = tt.layout;
  DaylightFactorResult r;
  r.sky = b.sky;
  r.outside_illuminance_lx = b.outside_lx;
  const double z = z_for_confidence(tt.confidence);
  r.mean = estimate(at.bin, z);
  std::vector<double> values;
  for (std::uint32_t c = 0; c < at.cells; ++c) {
    r.cells.push_back(estimate(at.cell_bin(c), z));
    values.push_back(r.cells.back().mean);
  }
  // Cells at any alpha, z computed once per alpha (the cells share it).
  GridSampler s;
  s.cells = at.cells;
  s.cell = [estimate, at, alpha = -1.0, z = 0.0](std::uint32_t c, double a) mutable {
    if (a != alpha) z = z_for_alpha(alpha = a);
    return estimate(at.cell_bin(c), z);
  };
  s.grid = [estimate, at](double a) { return estimate(at.bin, z_for_alpha(a)); };
  r.min = order_statistic(s, values, at.cells, tt.confidence);
  r.p50 = order_statistic(s, values, area_fraction_rank(at.cells, 0.5), tt.confidence);
  r.p95 = order_statistic(s, values, area_fraction_rank(at.cells, 0.95), tt.confidence);
  return r;
}

std::optional<DaylightFactorBasis> daylight_factor_basis(const Scene& scene,
                                                         const std::vector<PreparedGroup>& groups) {
  const bool any = std::any_of(scene.targets.begin(), scene.targets.end(), [](const Target& t) {
    return t.quantity == Target::Quantity::DaylightFactor;
  });
  const auto sky = daylight_factor_sky(scene);
  if (!any || !sky) return std::nullopt;
  const Luminaire& l = scene.luminaires[*sky];
  const auto g = std::find_if(groups.begin(), groups.end(), [&](const PreparedGroup& p) {
    return std::find(p.luminaires.begin(), p.luminaires.end(), *sky) != p.luminaires.end();
  });
  const double outside_lx = sky_outside_illuminance_lx(l);
  if (g == groups.end() || !(outside_lx > 0.0)) return std::nullopt;
  DaylightFactorBasis b;
  b.sky = l.name;
  b.group = static_cast<std::size_t>(g - groups.begin());
  b.sky_flux_lm = l.flux_lm;
  b.outside_lx = outside_lx;
  return b;
}

}  // namespace lightsolver::detail
