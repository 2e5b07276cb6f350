// Electric light beside a year of daylight (annual/electric.hpp): the scene's electric luminaires
// traced once at full output, and per grid the occupied hours at which daylight alone misses the
// task's illuminance and the mean output a daylight-linked dimmer would need, each with an
// interval (docs/daylight.md, "Electric light beside daylight").
#include "annual/electric.hpp"

#include <algorithm>
#include <cmath>

#include "lightsolver/error.hpp"
#include "lightsolver/statistics.hpp"

namespace lightsolver {
namespace {

bool is_daylight(const Luminaire& l) {
  return l.type == Luminaire::Type::Sky || l.type == Luminaire::Type::Sun;
}

// The grid's mean over its cells each hour, and its ends at the per-hour z: the mean of the
// cells' distances (σ of a sum is at most the sum of σs, whatever the cells' correlation).
struct GridMean {
  double mean, low, high;
};
GridMean grid_mean(const HourlyGrid& g, int h, double z) {
  double area = 0.0, m = 0.0, lo = 0.0, hi = 0.0;
  for (int c = 0; c < g.cells; ++c) {
    const std::size_t at = std::size_t(h) * g.cells + c;
    const double a = g.cell_area_m2[c];
    area += a;
    m += a * g.mean[at];
    lo += a * g.spread_low[at];
    hi += a * g.spread_high[at];
  }
  m /= area;
  return {m, std::max(0.0, m - z * lo / area), m + z * hi / area};
}

}  // namespace

std::optional<Results> trace_electric(const Scene& scene, std::uint64_t photons,
                                      std::optional<std::uint64_t> seed, const std::string& backend,
                                      int threads, double confidence,
                                      std::shared_ptr<ProcessGroup> processes) {
  Scene s = scene;
  s.luminaires.clear();
  for (const Luminaire& l : scene.luminaires) {
    if (!is_daylight(l)) s.luminaires.push_back(l);
  }
  if (s.luminaires.empty()) return std::nullopt;
  std::vector<Target> grids;
  for (const Target& t : scene.targets) {
    if (t.type == Target::Type::Grid) grids.push_back(t);
  }
  s.targets = grids;
  for (Target& t : s.targets) t.quantity = Target::Quantity::Illuminance;
  validate(s);
  SolveOptions o;
  o.photons = photons;
  o.seed = seed;
  o.backend = backend;
  o.threads = threads;
  o.confidence = confidence;
  o.processes = std::move(processes);
  return solve(s, o);
}

ElectricYear electric_year(const Target& grid, const Estimate& electric, const HourlyGrid& day,
                           const std::vector<std::uint8_t>& occupied, double confidence) {
  ElectricYear y;
  y.target_lx = grid.requirements.em_lux.value_or(kDefaultTaskLux);
  y.electric_lx = electric;
  int hours = 0;
  for (std::uint8_t o : occupied) hours += o != 0;
  if (hours == 0) throw InputError("", "occupied", "no occupied hour");
  // α/2 for the electric estimate (taken at 1 − α/2 by the caller), α/2 over the hours.
  const double z = z_for_alpha((1.0 - confidence) / (2.0 * hours));
  y.z_hour = z;
  double on_est = 0, on_lo = 0, on_hi = 0, f_est = 0, f_lo = 0, f_hi = 0;
  const double el = electric.mean, el_lo = electric.ci_low, el_hi = electric.ci_high;
  auto fraction = [&](double daylight, double full) {
    if (!(full > 0.0)) return daylight < y.target_lx ? 1.0 : 0.0;
    return std::clamp((y.target_lx - daylight) / full, 0.0, 1.0);
  };
  for (int h = 0; h < day.hours; ++h) {
    if (!occupied[h]) continue;
    const GridMean d = grid_mean(day, h, z);
    on_est += d.mean < y.target_lx;
    on_lo += d.high < y.target_lx;  // surely below the target
    on_hi += d.low < y.target_lx;   // possibly below
    f_est += fraction(d.mean, el);
    f_lo += fraction(d.high, el_hi);
    f_hi += fraction(d.low, el_lo);
  }
  y.hours_on = {on_est, on_lo, on_hi};
  y.dimming = {f_est / hours, f_lo / hours, f_hi / hours};
  y.occupied_hours = hours;
  return y;
}

nlohmann::json electric_json(const ElectricYear& y) {
  auto interval = [](const MetricInterval& m) {
    return nlohmann::json{{"estimate", m.estimate}, {"low", m.low}, {"high", m.high}};
  };
  return {{"target_lx", y.target_lx},
          {"electric_lx",
           {{"estimate", y.electric_lx.mean},
            {"low", y.electric_lx.ci_low},
            {"high", y.electric_lx.ci_high}}},
          {"occupied_hours", y.occupied_hours},
          {"hours_below_target", interval(y.hours_on)},
          {"mean_output_fraction", interval(y.dimming)},
          {"critical_value_hour", y.z_hour}};
}

}  // namespace lightsolver
