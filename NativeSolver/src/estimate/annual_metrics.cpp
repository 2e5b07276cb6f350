// Annual daylight metrics of a grid from hourly illuminance with intervals (docs/daylight.md,
// "A year of daylight: annual metrics"; the interval rule: docs/statistics.md, "Annual
// metrics"). Every count is bracketed by the hours surely in its band (the hour's interval
// inside it) and the hours possibly in it (the interval meeting it): both ends hold whenever
// every hour's interval holds its true value, which Bonferroni over the hours (or cell-hours)
// makes happen with probability at least the confidence.
#include "estimate/annual_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "lightsolver/error.hpp"
#include "lightsolver/statistics.hpp"

namespace lightsolver {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A band of illuminance, each end open or closed: E ≥ T is {T, true, inf}, E < T {-inf, _, T,
// false}.
struct Band {
  double lo = -kInf;
  bool lo_closed = true;
  double hi = kInf;
  bool hi_closed = true;
  bool above_lo(double v) const { return lo_closed ? v >= lo : v > lo; }
  bool below_hi(double v) const { return hi_closed ? v <= hi : v < hi; }
};

// Hours surely in a band (low), in it by the means (estimate), possibly in it (high).
struct Count {
  int low = 0, estimate = 0, high = 0;
};

// One hour's interval at a critical value.
struct HourValue {
  double low = 0.0, mean = 0.0, high = 0.0;
};

HourValue hour_value(const HourlyGrid& g, std::size_t i, double z) {
  const double mean = g.mean[i];
  return {std::max(0.0, mean - z * double(g.spread_low[i])), mean,
          mean + z * double(g.spread_high[i])};
}

void tally(Count& c, const HourValue& v, const Band& b) {
  c.low += b.above_lo(v.low) && b.below_hi(v.high);  // [low, high] inside the band
  c.estimate += b.above_lo(v.mean) && b.below_hi(v.mean);
  c.high += b.above_lo(v.high) && b.below_hi(v.low);  // [low, high] meets the band
}

// A count over `of` hours (1: the count itself). Division, not a product with 1/of: a count of
// exactly half the hours must give exactly 0.5 against sDA's 50 %.
MetricInterval fraction(const Count& c, double of) {
  return {c.estimate / of, c.low / of, c.high / of};
}

// The bands of one cell's counts, in a fixed order: DA, the five UDI bands, the thresholds.
std::vector<Band> count_bands(const AnnualOptions& o) {
  std::vector<Band> b;
  b.push_back({o.da_threshold_lx, true, kInf, true});
  b.push_back({-kInf, true, o.udi_low_lx, false});
  b.push_back({o.udi_low_lx, true, o.udi_high_lx, true});
  b.push_back({o.udi_high_lx, false, kInf, true});
  b.push_back({o.udi_low_lx, true, o.udi_high_alt_lx, true});
  b.push_back({o.udi_high_alt_lx, false, kInf, true});
  for (const double t : o.hour_thresholds_lx) b.push_back({t, true, kInf, true});
  return b;
}
constexpr std::size_t kDa = 0, kUdi = 1, kThresholds = 6;

// The occupied hours at which the LM-83 blinds rule closes the blinds: more than the area
// fraction gets more than the direct illuminance.
std::vector<std::uint8_t> blinds_closed_hours(const HourlyGrid& g,
                                              const std::vector<std::uint8_t>& occupied,
                                              const std::vector<float>& direct_sun_lx,
                                              const AnnualOptions& o, double area) {
  std::vector<std::uint8_t> closed(std::size_t(g.hours), 0);
  for (int h = 0; h < g.hours; ++h) {
    if (!occupied[h]) continue;
    double sunlit = 0.0;
    for (int c = 0; c < g.cells; ++c)
      if (direct_sun_lx[std::size_t(h) * g.cells + c] > o.blinds_direct_lx)
        sunlit += g.cell_area_m2[c];
    closed[h] = sunlit > o.blinds_area_fraction * area;
  }
  return closed;
}

// Every count of one cell over the occupied hours, at the cell's and the grid's level. DA's
// band reads the blinds-closed grid at the hours the blinds are closed.
struct CellCounts {
  std::vector<Count> at_cell, at_grid;
};

CellCounts cell_counts(const HourlyGrid& open, const HourlyGrid* closed,
                       const std::vector<std::uint8_t>& occupied,
                       const std::vector<std::uint8_t>& blinds, const std::vector<Band>& bands,
                       int c, double z_cell, double z_grid) {
  CellCounts k{std::vector<Count>(bands.size()), std::vector<Count>(bands.size())};
  for (int h = 0; h < open.hours; ++h) {
    if (!occupied[h]) continue;
    const std::size_t i = std::size_t(h) * open.cells + c;
    const HourlyGrid& da_grid = closed && blinds[h] ? *closed : open;
    tally(k.at_cell[kDa], hour_value(da_grid, i, z_cell), bands[kDa]);
    tally(k.at_grid[kDa], hour_value(da_grid, i, z_grid), bands[kDa]);
    const HourValue vc = hour_value(open, i, z_cell), vg = hour_value(open, i, z_grid);
    for (std::size_t b = kUdi; b < bands.size(); ++b) {
      tally(k.at_cell[b], vc, bands[b]);
      tally(k.at_grid[b], vg, bands[b]);
    }
  }
  return k;
}

// Area-weighted sums of the cells' intervals, divided by the area at the end; the estimate is
// held against rounding.
struct AreaMean {
  double estimate = 0.0, low = 0.0, high = 0.0;
  void add(const MetricInterval& m, double a) {
    estimate += a * m.estimate;
    low += a * m.low;
    high += a * m.high;
  }
  MetricInterval over(double area) const {
    const double e = estimate / area;
    return {e, std::min(low / area, e), std::max(high / area, e)};
  }
};

// The fraction of daylight hours at which the grid reaches `lx` over the area fraction of rank
// k, per level, from the hours' order statistics.
void en17037(const HourlyGrid& g, const std::vector<std::uint8_t>& daylight_hour, int daylight,
             AnnualMetrics& m) {
  const AnnualOptions& o = m.options;
  const auto m_cells = std::uint32_t(g.cells);
  const std::uint32_t k_target = area_fraction_rank(m_cells, o.en17037_target_area);
  const std::uint32_t k_minimum = area_fraction_rank(m_cells, o.en17037_minimum_area);
  // Each hour's order statistic at two-sided alpha / H_d: a fraction's end misses only when
  // some daylight hour's does (Bonferroni over the hours).
  const double hour_confidence = 1.0 - (1.0 - o.confidence) / double(daylight);
  std::vector<double> values(m_cells);
  std::size_t row = 0;
  GridSampler s;
  s.cells = m_cells;
  s.cell = [&g, &row, alpha = -1.0, z = 0.0](std::uint32_t c, double a) mutable {
    if (a != alpha) z = z_for_alpha(alpha = a);
    const HourValue v = hour_value(g, row + c, z);
    Estimate e;
    e.mean = v.mean;
    e.ci_low = v.low;
    e.ci_high = v.high;
    return e;
  };
  const En17037Level levels[] = {En17037Level::Minimum, En17037Level::Medium, En17037Level::High};
  std::vector<Count> target(3), minimum(3);
  for (int h = 0; h < g.hours; ++h) {
    if (!daylight_hour[h]) continue;
    row = std::size_t(h) * g.cells;
    for (std::uint32_t c = 0; c < m_cells; ++c) values[c] = g.mean[row + c];
    const OrderStatistic qt = order_statistic(s, values, k_target, hour_confidence);
    const OrderStatistic qm = order_statistic(s, values, k_minimum, hour_confidence);
    for (int l = 0; l < 3; ++l) {
      const auto [e_t, e_tm] = en17037_illuminances(levels[l]);
      tally(target[l], {qt.low, qt.value, qt.high}, {e_t, true, kInf, true});
      tally(minimum[l], {qm.low, qm.value, qm.high}, {e_tm, true, kInf, true});
    }
  }
  const auto criterion = [&](const Count& c, double lx, double area) {
    En17037Criterion r{lx, area, fraction(c, daylight)};
    r.verdict = judge(r.hours_fraction.low, r.hours_fraction.high, o.en17037_hours);
    return r;
  };
  for (int l = 0; l < 3; ++l) {
    const auto [e_t, e_tm] = en17037_illuminances(levels[l]);
    En17037Illuminance r;
    r.level = levels[l];
    r.target = criterion(target[l], e_t, o.en17037_target_area);
    r.minimum = criterion(minimum[l], e_tm, o.en17037_minimum_area);
    r.verdict = overall({r.target.verdict, r.minimum.verdict});
    m.en17037.push_back(r);
  }
}

int count_set(const std::vector<std::uint8_t>& mask) {
  return int(std::count(mask.begin(), mask.end(), std::uint8_t(1)));
}

}  // namespace

double annual_strictest_z(const AnnualOptions& o, int occupied_hours, int daylight_hours,
                          int cells) {
  const double alpha = 1.0 - o.confidence;
  const auto m = std::uint32_t(std::max(cells, 1));
  const auto ranks = {area_fraction_rank(m, o.en17037_target_area),
                      area_fraction_rank(m, o.en17037_minimum_area)};
  double widest = 1.0;  // the largest Bonferroni divisor of an EN 17037 cell bound
  for (const std::uint32_t k : ranks) widest = std::max({widest, double(k), double(m - k + 1)});
  const double grid = double(std::max(occupied_hours, 1)) * m;
  const double en = double(std::max(daylight_hours, 1)) * widest;
  return z_for_alpha(alpha / std::max(grid, en));
}

std::vector<std::uint8_t> lm83_occupancy(const std::vector<int>& hour_stamps, int first, int last) {
  std::vector<std::uint8_t> occupied(hour_stamps.size(), 0);
  for (std::size_t i = 0; i < hour_stamps.size(); ++i) {
    const int s = hour_stamps[i];
    if (s < 1 || s > 24)
      throw InputError("", "hour_stamps[" + std::to_string(i) + "]",
                       "an EPW hour stamp lies in 1 … 24, not " + std::to_string(s));
    occupied[i] = s >= first && s <= last;
  }
  return occupied;
}

AnnualMetrics annual_metrics(const HourlyGrid& grid, const std::vector<std::uint8_t>& occupied,
                             const std::vector<std::uint8_t>& daylight_hour,
                             const std::vector<float>& direct_sun_lx, const AnnualOptions& options,
                             const HourlyGrid* blinds_closed) {
  detail::check_annual_inputs(grid, occupied, daylight_hour, direct_sun_lx, options, blinds_closed);
  AnnualMetrics m;
  m.options = options;
  m.hours = grid.hours;
  m.cells = grid.cells;
  m.occupied_hours = count_set(occupied);
  m.daylight_hours = count_set(daylight_hour);
  for (const double a : grid.cell_area_m2) m.area_m2 += a;
  const double alpha = 1.0 - options.confidence, h_occ = m.occupied_hours;
  m.z_cell = z_for_alpha(alpha / h_occ);
  m.z_grid = z_for_alpha(alpha / (h_occ * grid.cells));
  m.sun_given = !direct_sun_lx.empty();
  m.blinds_given = blinds_closed != nullptr;
  std::vector<std::uint8_t> blinds;
  if (m.blinds_given)
    blinds = blinds_closed_hours(grid, occupied, direct_sun_lx, options, m.area_m2);
  m.blinds_closed_hours = count_set(blinds);

  const std::vector<Band> bands = count_bands(options);
  std::vector<AreaMean> means(bands.size());
  double sda = 0.0, sda_low = 0.0, sda_high = 0.0, ase_area = 0.0;
  for (int c = 0; c < grid.cells; ++c) {
    const CellCounts k =
        cell_counts(grid, blinds_closed, occupied, blinds, bands, c, m.z_cell, m.z_grid);
    const double a = grid.cell_area_m2[c];
    AnnualCellMetrics cm;
    MetricInterval* fractions[] = {&cm.da,        &cm.udi_below,      &cm.udi_useful,
                                   &cm.udi_above, &cm.udi_useful_alt, &cm.udi_above_alt};
    for (std::size_t b = 0; b < bands.size(); ++b) {
      const double of = b < kThresholds ? h_occ : 1.0;  // fractions, or hours
      if (b < kThresholds)
        *fractions[b] = fraction(k.at_cell[b], of);
      else
        cm.hours_above.push_back(fraction(k.at_cell[b], of));
      means[b].add(fraction(k.at_grid[b], of), a);
    }
    // sDA's cells decided at the grid's level: its ends hold when every cell-hour's does.
    const MetricInterval da = fraction(k.at_grid[kDa], h_occ);
    cm.sda = judge(da.low, da.high, options.sda_fraction);
    sda += a * (cm.da.estimate >= options.sda_fraction);
    sda_low += a * (cm.sda == VerdictKind::Pass);
    sda_high += a * (cm.sda != VerdictKind::Fail);
    if (m.sun_given) {
      for (int h = 0; h < grid.hours; ++h)
        cm.ase_hours +=
            occupied[h] && direct_sun_lx[std::size_t(h) * grid.cells + c] > options.ase_direct_lx;
      ase_area += a * (cm.ase_hours > options.ase_hours);
    }
    m.cell.push_back(std::move(cm));
  }
  MetricInterval* grid_means[] = {&m.da,        &m.udi_below,      &m.udi_useful,
                                  &m.udi_above, &m.udi_useful_alt, &m.udi_above_alt};
  for (std::size_t b = 0; b < bands.size(); ++b) {
    if (b < kThresholds)
      *grid_means[b] = means[b].over(m.area_m2);
    else
      m.hours_above.push_back(means[b].over(m.area_m2));
  }
  const double s = sda / m.area_m2;
  m.sda = {s, std::min(sda_low / m.area_m2, s), std::max(sda_high / m.area_m2, s)};
  m.sda_nominal = judge(m.sda.low, m.sda.high, options.sda_nominal);
  m.sda_preferred = judge(m.sda.low, m.sda.high, options.sda_preferred);
  m.ase = ase_area / m.area_m2;
  m.ase_verdict =
      m.sun_given ? judge_at_most(m.ase, m.ase, options.ase_maximum) : VerdictKind::Undecided;
  en17037(grid, daylight_hour, m.daylight_hours, m);
  return m;
}

}  // namespace lightsolver
