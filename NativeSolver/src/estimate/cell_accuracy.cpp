// Per-cell accuracy: the measure of `--accuracy X --per-cell` and `lightsolver study`.
// Compliance is decided by the worst cell (Emin, U0 = Emin/Em), so a goal on the grid's mean
// says little: this rule bounds every cell. Why dark cells are judged against 1 % of their
// grid's mean: docs/statistics.md, "Per-cell accuracy".
#include "estimate/cell_accuracy.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "lightsolver/accuracy.hpp"
#include "types/target_types.hpp"

namespace lightsolver {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double half_width(const Estimate& e) { return 0.5 * (e.ci_high - e.ci_low); }

// A surface target is judged by its own mean (it has no cells, and no grid mean to lean on).
double target_relative_half_width(const Estimate& e) {
  return e.mean > 0.0 ? half_width(e) / e.mean : kInf;
}

void add(CellWidths& w, double width) {
  w.worst = std::max(w.worst, width);
  w.mean += width;  // divided by the count at the end
  ++w.units;
}

}  // namespace

double cell_relative_half_width(const Estimate& cell, double grid_mean_lux) {
  if (!(grid_mean_lux > 0.0)) return kInf;
  return half_width(cell) / std::max(cell.mean, kDarkCellFraction * grid_mean_lux);
}

std::optional<double> cell_relative_error(double value_lux, double reference_lux,
                                          double reference_grid_mean_lux) {
  const double scale = std::max(reference_lux, kDarkCellFraction * reference_grid_mean_lux);
  if (!(scale > 0.0)) return std::nullopt;
  return std::abs(value_lux - reference_lux) / scale;
}

CellWidths cell_widths(const TargetResult& t) {
  CellWidths w;
  if (!t.is_grid) {
    add(w, target_relative_half_width(t.estimate));
  } else {
    for (const Estimate& c : t.cells) add(w, cell_relative_half_width(c, t.estimate.mean));
  }
  if (w.units > 0) w.mean /= double(w.units);
  return w;
}

CellWidths cell_widths(const std::vector<TargetResult>& targets) {
  CellWidths all;
  for (const TargetResult& t : targets) {
    const CellWidths w = cell_widths(t);
    all.worst = std::max(all.worst, w.worst);
    all.mean += w.mean * double(w.units);
    all.units += w.units;
  }
  if (all.units > 0) all.mean /= double(all.units);
  return all;
}

namespace detail {

double worst_cell_relative_half_width(const Scene& scene, const PreparedScene& s,
                                      const TallyBlock& t, std::uint64_t photons,
                                      double confidence) {
  double worst = 0.0;
  const GroupedTallies tallies = grouped_tallies(s, t.bins, photons);
  for (std::size_t i = 0; i < scene.targets.size(); ++i) {
    const PreparedTarget& at = s.targets[i];
    const auto estimate = [&](std::uint32_t b) {
      return tallies.estimate(b, s.bins[b].area_m2, confidence);
    };
    const Estimate whole = estimate(at.bin);
    if (whole.hits == 0 || !(whole.mean > 0.0)) return kInf;
    if (at.cells == 0) {
      for (std::uint32_t k = 0; k < at.goal_count(); ++k) {  // each eye of an observer grid
        const Estimate e = estimate(at.goal_bin(k));
        if (e.hits == 0 || !(e.mean > 0.0)) return kInf;
        worst = std::max(worst, target_relative_half_width(e));
      }
      continue;
    }
    for (std::uint32_t c = 0; c < at.cells; ++c) {
      worst = std::max(worst, cell_relative_half_width(estimate(at.cell_bin(c)), whole.mean));
    }
  }
  return worst;
}

}  // namespace detail
}  // namespace lightsolver
