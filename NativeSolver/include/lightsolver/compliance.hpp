#pragma once
/// \file compliance.hpp
/// Requirements on targets (EN 12464-1 style: Em, U0, Emin, Ud) and verdicts decided from the
/// confidence intervals: pass when the whole interval lies on the allowed side, fail when it
/// lies wholly on the other, undecided otherwise (docs/statistics.md, "Verdicts").

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lightsolver/statistics.hpp"

namespace lightsolver {

/// EN 17037:2018's daylight-factor levels (Table A.1, vertical and inclined openings).
enum class En17037Level { None, Minimum, Medium, High };

/// "minimum", "medium", "high" ("" for None).
const char* to_string(En17037Level level);

/// The level named `name`, or nullopt for any other text.
std::optional<En17037Level> en17037_level(const std::string& name);

/// The target illuminances (E_T, E_TM) in lx of a level: (300, 100) minimum, (500, 300)
/// medium, (750, 500) high; (0, 0) for None.
std::pair<double, double> en17037_illuminances(En17037Level level);

/// What a target must reach; every value is a lower bound (relation ">="), except ugr_max, an
/// upper bound (relation "<=", observers only). Any subset.
struct Requirements {
  std::optional<double> em_lux;    ///< maintained mean illuminance Em
  std::optional<double> u0;        ///< Emin / Em (grids only)
  std::optional<double> emin_lux;  ///< smallest cell (grids only)
  std::optional<double> ud;        ///< Emin / Emax (grids only)
  std::optional<double> ugr_max;   ///< largest allowed UGR (observers only; EN 12464-1 UGR_L)
  std::string task;                ///< the requirements table row it came from, or empty
  std::string source;              ///< the table's source (e.g. "EN 12464-1:2021 ..."), or empty
  /// Daylight-factor grids only (docs/scene-format.md, "Targets"): D >= df_target_percent over
  /// half the grid's area, D >= df_minimum_percent over 95 % of it, as given, or derived from
  /// the EN 17037 level and the site's median external diffuse illuminance where not given.
  std::optional<double> df_target_percent, df_minimum_percent;
  En17037Level en17037 = En17037Level::None;
  std::optional<double> median_diffuse_lx;  ///< E_v,d,med (lx), with `en17037`

  /// D_T and D_TM in force: the explicit value, else E_T (E_TM) / median_diffuse_lx x 100 for
  /// the EN 17037 level; empty when neither applies.
  std::optional<double> df_target() const;
  std::optional<double> df_minimum() const;
  /// Any daylight-factor key given (df_*_percent, en17037, median_diffuse_lx).
  bool any_daylight_factor() const {
    return df_target_percent || df_minimum_percent || en17037 != En17037Level::None ||
           median_diffuse_lx;
  }
  bool any() const {
    return em_lux || u0 || emin_lux || ud || ugr_max || df_target() || df_minimum();
  }
};

/// Outcome of one requirement.
enum class VerdictKind { Pass, Fail, Undecided };

/// "pass", "fail", "undecided".
const char* to_string(VerdictKind v);

/// One requirement judged: value and its interval against `required` (value >= required, or
/// value <= required for "ugr").
struct Verdict {
  std::string name;  ///< "em", "u0", "emin", "ud" or "ugr"
  VerdictKind verdict = VerdictKind::Undecided;
  double value = 0.0, ci_low = 0.0, ci_high = 0.0, required = 0.0;
  const char* relation = ">=";  ///< ">=" (a lower bound) or "<=" (ugr: an upper bound)
  /// UGR only: false when the value or the interval's upper end is unbounded (no background
  /// luminance measured: L_b = 0 or its lower bound 0); the JSON then writes null.
  bool value_known = true, ci_high_known = true;
  /// Undecided only: estimated photons (of a whole run) and tracing seconds to decide it;
  /// empty when no estimate can be made (value exactly at the bound, nothing traced).
  std::optional<double> photons_to_decide, seconds_to_decide;
};

/// The interval rule for "value >= required": Pass iff ci_low >= required (the interval lies in
/// the allowed set [required, inf), its end included); Fail iff ci_high < required (no point
/// of it is allowed); Undecided otherwise, including ci_high == required.
VerdictKind judge(double ci_low, double ci_high, double required);

/// The interval rule for "value <= required" (UGR): Pass iff ci_high <= required, Fail iff
/// ci_low > required, Undecided otherwise.
VerdictKind judge_at_most(double ci_low, double ci_high, double required);

/// Intervals of a grid's statistics at the run's confidence c = 1 - alpha. Every interval holds
/// its estimate; all finite.
struct GridIntervals {
  double min_low = 0.0, min_high = 0.0;          ///< Emin
  double max_low = 0.0, max_high = 0.0;          ///< Emax
  double u0_low = 0.0, u0_high = 0.0;            ///< U0 = Emin / Em
  double ud = 0.0, ud_low = 0.0, ud_high = 0.0;  ///< Ud = Emin / Emax (0 when Emax is 0)
};

/// A grid's interval inputs: its whole-grid estimate and its cells' estimates, each at the
/// two-sided level 1 - alpha it is called with.
struct GridSampler {
  std::uint32_t cells = 0;
  std::function<Estimate(double alpha)> grid;
  std::function<Estimate(std::uint32_t cell, double alpha)> cell;
};

/// Emin, Emax, U0 and Ud intervals at `confidence` (docs/statistics.md, "Emin over noisy
/// cells"): Emin's lower end is the smallest cell lower bound, its upper end the smallest upper
/// bound of cell intervals that hold simultaneously (Bonferroni), so it is honest about being
/// a minimum over many noisy cells; Emax mirrors it; U0 and Ud split alpha between their two
/// factors. `min_lux`, `max_lux`, `mean_lux` are the point estimates.
GridIntervals grid_intervals(const GridSampler& s, double confidence, double min_lux,
                             double max_lux, double mean_lux);

/// The cell rank of the value a grid reaches or exceeds over at least `fraction` (0..1] of its
/// area, its m cells equal in area: k = ceil(fraction m) (at least 1), the k-th largest cell.
std::uint32_t area_fraction_rank(std::uint32_t cells, double fraction);

/// An order statistic of a grid's cells with its interval.
struct OrderStatistic {
  double value = 0.0, low = 0.0, high = 0.0;
};

/// The k-th largest cell (k = 1: the largest, k = m: the smallest) with an interval at
/// `confidence` honest for an order statistic over noisy cells (docs/statistics.md, "Order
/// statistics of noisy cells"): its lower end the k-th largest of the cells' lower bounds at
/// one-sided alpha / (2 (m - k + 1)), its upper end the k-th largest of their upper bounds at
/// one-sided alpha / (2 k). `values`: the cells' estimates (the statistic is theirs).
OrderStatistic order_statistic(const GridSampler& s, const std::vector<double>& values,
                               std::uint32_t k, double confidence);

/// The overall verdict of a list: Fail if any fails, else Undecided if any is, else Pass.
VerdictKind overall(const std::vector<VerdictKind>& verdicts);

}  // namespace lightsolver
