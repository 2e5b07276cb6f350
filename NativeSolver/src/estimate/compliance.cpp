// Verdicts from intervals, and honest intervals for a grid's minimum, maximum and ratios
// (docs/statistics.md, "Verdicts" and "Emin over noisy cells").
#include "lightsolver/compliance.hpp"

#include <algorithm>
#include <cmath>
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

}  // namespace lightsolver
