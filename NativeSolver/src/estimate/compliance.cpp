// Verdicts from intervals, and honest intervals for a grid's minimum, maximum and ratios
// (docs/statistics.md, "Verdicts" and "Emin over noisy cells").
#include "lightsolver/compliance.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace lightsolver {

const char* to_string(VerdictKind v) {
  switch (v) {
    case VerdictKind::Pass:
      return "pass";
    case VerdictKind::Fail:
      return "fail";
    case VerdictKind::Undecided:
      break;
  }
  return "undecided";
}

const char* to_string(En17037Level level) {
  switch (level) {
    case En17037Level::Minimum:
      return "minimum";
    case En17037Level::Medium:
      return "medium";
    case En17037Level::High:
      return "high";
    case En17037Level::None:
      break;
  }
  return "";
}

std::optional<En17037Level> en17037_level(const std::string& name) {
  for (const En17037Level l : {En17037Level::Minimum, En17037Level::Medium, En17037Level::High}) {
    if (name == to_string(l)) return l;
  }
  return std::nullopt;
}

std::pair<double, double> en17037_illuminances(En17037Level level) {
  switch (level) {  // EN 17037:2018, Table A.1 (vertical and inclined daylight openings)
    case En17037Level::Minimum:
      return {300.0, 100.0};
    case En17037Level::Medium:
      return {500.0, 300.0};
    case En17037Level::High:
      return {750.0, 500.0};
    case En17037Level::None:
      break;
  }
  return {0.0, 0.0};
}

namespace {
// The explicit percentage, else the level's illuminance over the median, in percent.
std::optional<double> daylight_factor_in_force(const std::optional<double>& given,
                                               const Requirements& r, bool target) {
  if (given) return given;
  if (r.en17037 == En17037Level::None || !r.median_diffuse_lx) return std::nullopt;
  const auto [e_t, e_tm] = en17037_illuminances(r.en17037);
  return (target ? e_t : e_tm) / *r.median_diffuse_lx * 100.0;
}
}  // namespace

std::optional<double> Requirements::df_target() const {
  return daylight_factor_in_force(df_target_percent, *this, true);
}
std::optional<double> Requirements::df_minimum() const {
  return daylight_factor_in_force(df_minimum_percent, *this, false);
}

VerdictKind judge(double ci_low, double ci_high, double required) {
  if (ci_low >= required) return VerdictKind::Pass;  // [low, high] inside [required, inf)
  if (ci_high < required) return VerdictKind::Fail;  // no point of it is allowed
  return VerdictKind::Undecided;
}

VerdictKind judge_at_most(double ci_low, double ci_high, double required) {
  if (ci_high <= required) return VerdictKind::Pass;  // [low, high] inside (-inf, required]
  if (ci_low > required) return VerdictKind::Fail;
  return VerdictKind::Undecided;
}

VerdictKind overall(const std::vector<VerdictKind>& verdicts) {
  VerdictKind o = VerdictKind::Pass;
  for (const VerdictKind v : verdicts) {
    if (v == VerdictKind::Fail) return VerdictKind::Fail;
    if (v == VerdictKind::Undecided) o = VerdictKind::Undecided;
  }
  return o;
}

namespace {

// The smallest and largest lower and upper cell bounds, each cell's interval at the two-sided
// level 1 - alpha (each end: one-sided alpha / 2).
struct Extremes {
  double min_low = 0.0, min_high = 0.0, max_low = 0.0, max_high = 0.0;
};

Extremes cell_extremes(const GridSampler& s, double alpha) {
  Extremes x;
  for (std::uint32_t c = 0; c < s.cells; ++c) {
    const Estimate e = s.cell(c, alpha);
    if (c == 0) {
      x = {e.ci_low, e.ci_high, e.ci_low, e.ci_high};
      continue;
    }
    x.min_low = std::min(x.min_low, e.ci_low);
    x.min_high = std::min(x.min_high, e.ci_high);
    x.max_low = std::max(x.max_low, e.ci_low);
    x.max_high = std::max(x.max_high, e.ci_high);
  }
  return x;
}

// One-sided bounds of Emin and Emax whose tails are each at most `tail`:
//  - min_i low_i > Emin needs low_j > E_j for the (fixed, unknown) darkest cell j: one cell's
//    tail, so each cell's bound at one-sided `tail` serves;
//  - min_i high_i < Emin needs high_i < E_i for some cell: a union over all m cells, so each
//    cell's bound at one-sided tail / m (Bonferroni, whatever the correlation between cells).
// Emax mirrors it (its upper end is one cell's, its lower end the union's).
struct Bounds {
  double min_low, min_high, max_low, max_high;
};

Bounds extreme_bounds(const GridSampler& s, double tail) {
  const double m = double(s.cells);
  const Extremes one = cell_extremes(s, 2.0 * tail);      // one-sided tail per end
  const Extremes all = cell_extremes(s, 2.0 * tail / m);  // one-sided tail / m per end
  return {one.min_low, all.min_high, all.max_low, one.max_high};
}

// The interval of a/b for a in [a_low, a_high], b in [b_low, b_high] (all >= 0), knowing the
// true ratio is at most 1 (a minimum over its mean or maximum): [a_low / b_high, a_high / b_low]
// cut at 1, with 0/0 read as 0 and x/0 as 1 (no bound). It is made to hold `value`.
std::pair<double, double> ratio_interval(double a_low, double a_high, double b_low, double b_high,
                                         double value) {
  const double low = b_high > 0.0 ? a_low / b_high : 0.0;
  const double high = b_low > 0.0 ? std::min(1.0, a_high / b_low) : 1.0;
  return {std::min(low, value), std::max(high, value)};
}

}  // namespace

GridIntervals grid_intervals(const GridSampler& s, double confidence, double min_lux,
                             double max_lux, double mean_lux) {
  if (!(confidence > 0.0 && confidence < 1.0)) {
    throw std::invalid_argument("grid_intervals: confidence must lie in (0, 1)");
  }
  if (s.cells == 0) throw std::invalid_argument("grid_intervals: a grid without cells");
  const double alpha = 1.0 - confidence;
  GridIntervals g;
  // Emin and Emax: alpha / 2 on each side (docs/statistics.md). The estimates are held
  // against rounding (each lies between its cell's bounds).
  const Bounds b = extreme_bounds(s, 0.5 * alpha);
  g.min_low = std::min(b.min_low, min_lux);
  g.min_high = std::max(b.min_high, min_lux);
  g.max_low = std::min(b.max_low, max_lux);
  g.max_high = std::max(b.max_high, max_lux);
  // Ratios: each side of the interval rests on two bounds, alpha / 4 each, so each side
  // misses with probability <= alpha / 2 (Bonferroni over the two bounds of that side).
  const Bounds q = extreme_bounds(s, 0.25 * alpha);
  const double q_min_low = std::min(q.min_low, min_lux), q_min_high = std::max(q.min_high, min_lux);
  g.ud = max_lux > 0.0 ? min_lux / max_lux : 0.0;
  std::tie(g.ud_low, g.ud_high) = ratio_interval(
      q_min_low, q_min_high, std::min(q.max_low, max_lux), std::max(q.max_high, max_lux), g.ud);
  const Estimate em = s.grid(0.5 * alpha);  // two-sided alpha / 2: one-sided alpha / 4 per end
  const double u0 = mean_lux > 0.0 ? min_lux / mean_lux : 0.0;
  std::tie(g.u0_low, g.u0_high) = ratio_interval(
      q_min_low, q_min_high, std::min(em.ci_low, mean_lux), std::max(em.ci_high, mean_lux), u0);
  return g;
}

std::uint32_t area_fraction_rank(std::uint32_t cells, double fraction) {
  // The 1e-9 keeps 0.5 x 16 = 8 from rounding up to 9 when the product is 8.000000000001.
  const double k = std::ceil(fraction * double(cells) - 1e-9);
  return static_cast<std::uint32_t>(std::clamp(k, 1.0, double(std::max(cells, 1u))));
}

namespace {
// The k-th largest (1-based) of `v`.
double kth_largest(std::vector<double> v, std::uint32_t k) {
  std::nth_element(v.begin(), v.begin() + (k - 1), v.end(), std::greater<>());
  return v[k - 1];
}
}  // namespace

OrderStatistic order_statistic(const GridSampler& s, const std::vector<double>& values,
                               std::uint32_t k, double confidence) {
  if (!(confidence > 0.0 && confidence < 1.0)) {
    throw std::invalid_argument("order_statistic: confidence must lie in (0, 1)");
  }
  const std::uint32_t m = s.cells;
  if (m == 0 || values.size() != m || k == 0 || k > m) {
    throw std::invalid_argument("order_statistic: k must lie in 1..cells");
  }
  const double alpha = 1.0 - confidence;
  // One-sided alpha / 2 per end, shared by Bonferroni over the cells that can make that end
  // miss: the m - k + 1 darkest for the lower end, the k brightest for the upper end.
  std::vector<double> lows(m), highs(m);
  for (std::uint32_t c = 0; c < m; ++c) lows[c] = s.cell(c, alpha / double(m - k + 1)).ci_low;
  for (std::uint32_t c = 0; c < m; ++c) highs[c] = s.cell(c, alpha / double(k)).ci_high;
  OrderStatistic o;
  o.value = kth_largest(values, k);
  o.low = std::min(kth_largest(std::move(lows), k), o.value);
  o.high = std::max(kth_largest(std::move(highs), k), o.value);
  return o;
}

}  // namespace lightsolver
