#pragma once
/// \file accuracy.hpp
/// Per-cell accuracy: how well every grid cell (and every surface target) is known, the measure
/// behind `--accuracy X --per-cell` and `lightsolver study` (docs/statistics.md, "Per-cell
/// accuracy").

#include <cstddef>
#include <optional>
#include <vector>

#include "lightsolver/solver.hpp"

namespace lightsolver {

/// A cell darker than this fraction of its grid's mean is judged by its absolute half-width
/// against this fraction of the mean, not by its own mean (which may be 0: full shadow).
inline constexpr double kDarkCellFraction = 0.01;

/// Relative half-width of a cell under the per-cell rule: half-width / max(cell mean,
/// kDarkCellFraction * grid mean). Infinity when the grid's mean is 0 (no light reached it
/// yet: nothing can be judged).
double cell_relative_half_width(const Estimate& cell, double grid_mean_lux);

/// Relative error of `value` against a reference under the same rule: |value - reference| /
/// max(reference, kDarkCellFraction * reference grid mean); nullopt when the reference grid's
/// mean is 0 (no scale to judge by).
std::optional<double> cell_relative_error(double value_lux, double reference_lux,
                                          double reference_grid_mean_lux);

/// The units the per-cell rule judges: every cell of every grid target and every surface target
/// as a whole (its relative half-width). Worst and mean over all of them; `units` = their number.
struct CellWidths {
  double worst = 0.0;  ///< largest relative half-width (infinity while one cannot be judged)
  double mean = 0.0;   ///< mean relative half-width (infinity likewise)
  std::size_t units = 0;
};

/// The per-cell measure of a set of target results (a run's or a checkpoint's).
CellWidths cell_widths(const std::vector<TargetResult>& targets);

/// The measure of one target: its cells for a grid, itself for a surface.
CellWidths cell_widths(const TargetResult& target);

}  // namespace lightsolver
