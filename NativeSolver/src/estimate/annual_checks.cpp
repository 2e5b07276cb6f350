// The inputs of the annual metrics checked before any is used: a size that does not match, a
// negative or non-finite value, an empty mask would give NaN or a silent wrong metric.
#include <cmath>
#include <string>

#include "estimate/annual_metrics.hpp"
#include "lightsolver/error.hpp"

namespace lightsolver::detail {
namespace {

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw InputError("", where, what);
}

// A fraction of hours or area: 0 … 1.
void check_fraction(const std::string& name, double v) {
  if (!(v >= 0.0 && v <= 1.0)) fail("options." + name, "must be a fraction from 0 to 1");
}

void check_lux(const std::string& name, double v) {
  if (!(v >= 0.0 && std::isfinite(v))) fail(name, "an illuminance must be finite and >= 0");
}

void check_options(const AnnualOptions& o) {
  if (!(o.confidence > 0.0 && o.confidence < 1.0))
    fail("options.confidence", "must lie strictly between 0 and 1");
  for (const auto& [name, v] : {std::pair{"sda_fraction", o.sda_fraction},
                                {"sda_nominal", o.sda_nominal},
                                {"sda_preferred", o.sda_preferred},
                                {"ase_maximum", o.ase_maximum},
                                {"blinds_area_fraction", o.blinds_area_fraction},
                                {"en17037_hours", o.en17037_hours}})
    check_fraction(name, v);
  for (const auto& [name, v] : {std::pair{"en17037_target_area", o.en17037_target_area},
                                {"en17037_minimum_area", o.en17037_minimum_area}})
    if (!(v > 0.0 && v <= 1.0)) fail(std::string("options.") + name, "must lie in (0, 1]");
  for (const auto& [name, v] : {std::pair{"da_threshold_lx", o.da_threshold_lx},
                                {"ase_direct_lx", o.ase_direct_lx},
                                {"blinds_direct_lx", o.blinds_direct_lx},
                                {"udi_low_lx", o.udi_low_lx},
                                {"udi_high_lx", o.udi_high_lx},
                                {"udi_high_alt_lx", o.udi_high_alt_lx}})
    check_lux(std::string("options.") + name, v);
  if (!(o.udi_low_lx < o.udi_high_lx && o.udi_low_lx < o.udi_high_alt_lx))
    fail("options.udi_low_lx", "must lie below udi_high_lx and udi_high_alt_lx");
  if (o.ase_hours < 0) fail("options.ase_hours", "must be >= 0");
  for (std::size_t i = 0; i < o.hour_thresholds_lx.size(); ++i)
    check_lux("options.hour_thresholds_lx[" + std::to_string(i) + "]", o.hour_thresholds_lx[i]);
}

std::string at(const std::string& name, std::size_t i, int cells) {
  return name + "[" + std::to_string(i) + "] (hour " + std::to_string(i / cells) + ", cell " +
         std::to_string(i % cells) + ")";
}

void check_values(const std::string& name, const std::vector<float>& v, std::size_t n, int cells) {
  if (v.size() != n)
    fail(name, "has " + std::to_string(v.size()) + " values, hours × cells = " + std::to_string(n));
  for (std::size_t i = 0; i < n; ++i)
    if (!(v[i] >= 0.0f && std::isfinite(v[i]))) fail(at(name, i, cells), "must be finite and >= 0");
}

void check_grid(const std::string& name, const HourlyGrid& g) {
  if (g.hours < 1) fail(name + ".hours", "must be at least 1");
  if (g.cells < 1) fail(name + ".cells", "must be at least 1");
  const std::size_t n = std::size_t(g.hours) * std::size_t(g.cells);
  check_values(name + ".mean", g.mean, n, g.cells);
  check_values(name + ".spread_low", g.spread_low, n, g.cells);
  check_values(name + ".spread_high", g.spread_high, n, g.cells);
  if (g.cell_area_m2.size() != std::size_t(g.cells))
    fail(name + ".cell_area_m2", "needs one area per cell (" + std::to_string(g.cells) + ")");
  const double first = g.cell_area_m2[0];
  for (std::size_t c = 0; c < g.cell_area_m2.size(); ++c) {
    const double a = g.cell_area_m2[c];
    const std::string where = name + ".cell_area_m2[" + std::to_string(c) + "]";
    if (!(a > 0.0 && std::isfinite(a))) fail(where, "an area must be finite and > 0");
    // EN 17037's "over 50 % of the area" is a rank among the cells (area_fraction_rank).
    if (std::abs(a - first) > 1e-6 * first)
      fail(where, "the cells' areas differ (EN 17037's area fractions need equal cells)");
  }
}

int check_mask(const std::string& name, const std::vector<std::uint8_t>& mask, int hours) {
  if (mask.size() != std::size_t(hours))
    fail(name, "has " + std::to_string(mask.size()) + " hours, the grid " + std::to_string(hours));
  int set = 0;
  for (std::size_t h = 0; h < mask.size(); ++h) {
    if (mask[h] > 1) fail(name + "[" + std::to_string(h) + "]", "must be 0 or 1");
    set += mask[h];
  }
  if (set == 0) fail(name, "has no hour set: the fractions would divide by zero");
  return set;
}

}  // namespace

void check_annual_inputs(const HourlyGrid& grid, const std::vector<std::uint8_t>& occupied,
                         const std::vector<std::uint8_t>& daylight_hour,
                         const std::vector<float>& direct_sun_lx, const AnnualOptions& options,
                         const HourlyGrid* blinds_closed) {
  check_options(options);
  check_grid("grid", grid);
  check_mask("occupied", occupied, grid.hours);
  check_mask("daylight_hour", daylight_hour, grid.hours);
  const std::size_t n = std::size_t(grid.hours) * std::size_t(grid.cells);
  if (!direct_sun_lx.empty()) check_values("direct_sun_lx", direct_sun_lx, n, grid.cells);
  if (!blinds_closed) return;
  check_grid("blinds_closed", *blinds_closed);
  if (blinds_closed->hours != grid.hours || blinds_closed->cells != grid.cells)
    fail("blinds_closed", "must have the grid's hours and cells");
  if (direct_sun_lx.empty())
    fail("direct_sun_lx", "the blinds rule needs the direct sun (it decides when they close)");
}

}  // namespace lightsolver::detail
