// Verdicts from intervals, and honest intervals for a grid's minimum, maximum and ratios
// (docs/statistics.md, "Verdicts" and "Emin over noisy cells").
#include "lightsolver/compliance.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

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

VerdictKind overall(const std::vector<VerdictKind>& verdicts) {
  VerdictKind o = VerdictKind::Pass;
  for (const VerdictKind v : verdicts) {
    if (v == VerdictKind::Fail) return VerdictKind::Fail;
    if (v == VerdictKind::Undecided) o = VerdictKind::Undecided;
  }
  return o;
}

namespace {

// Smallest and largest cell bounds of cell intervals that hold simultaneously with probability
// >= 1 - alpha (Bonferroni: each cell at alpha / m). If every cell's interval holds its true
// value, then min_i low_i <= min_i E_i <= min_i high_i (and likewise for the maximum): min and
// max are monotone in each argument. So [min low, min high] covers the true minimum at least
// as often as all cells are covered together, whatever the correlation between cells.
struct Extremes {
  double min_low = 0.0, min_high = 0.0, max_low = 0.0, max_high = 0.0;
};

Extremes simultaneous_extremes(const GridSampler& s, double alpha) {
  const double per_cell = alpha / double(std::max<std::uint32_t>(s.cells, 1));
  Extremes x;
  for (std::uint32_t c = 0; c < s.cells; ++c) {
    const Estimate e = s.cell(c, per_cell);
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
  // Emin, Emax and Ud from one set of simultaneous cell intervals at alpha: when all cells are
  // covered, all three are, so Ud needs no further split.
  const Extremes at_alpha = simultaneous_extremes(s, alpha);
  g.min_low = std::min(at_alpha.min_low, min_lux);  // contain the estimate against rounding
  g.min_high = std::max(at_alpha.min_high, min_lux);
  g.max_low = std::min(at_alpha.max_low, max_lux);
  g.max_high = std::max(at_alpha.max_high, max_lux);
  g.ud = max_lux > 0.0 ? min_lux / max_lux : 0.0;
  std::tie(g.ud_low, g.ud_high) =
      ratio_interval(g.min_low, g.min_high, g.max_low, g.max_high, g.ud);
  // U0 = Emin / Em: Emin's cells at alpha/2 and Em at alpha/2, so both hold together with
  // probability >= 1 - alpha (Bonferroni over the two).
  const Extremes at_half = simultaneous_extremes(s, 0.5 * alpha);
  const Estimate em = s.grid(0.5 * alpha);
  const double u0 = mean_lux > 0.0 ? min_lux / mean_lux : 0.0;
  std::tie(g.u0_low, g.u0_high) =
      ratio_interval(std::min(at_half.min_low, min_lux), std::max(at_half.min_high, min_lux),
                     std::min(em.ci_low, mean_lux), std::max(em.ci_high, mean_lux), u0);
  return g;
}

}  // namespace lightsolver
