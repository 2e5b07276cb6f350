#pragma once
// Hand-made hourly grids for the annual metrics' tests.
#include <cstdint>
#include <vector>

#include "lightsolver/annual.hpp"

namespace lightsolver::test {

/// A grid of `hours` × `cells`, every value `lx`, spreads 0, cells of 1 m².
inline HourlyGrid flat_grid(int hours, int cells, float lx = 0.0f) {
  HourlyGrid g;
  g.hours = hours;
  g.cells = cells;
  const std::size_t n = std::size_t(hours) * cells;
  g.mean.assign(n, lx);
  g.spread_low.assign(n, 0.0f);
  g.spread_high.assign(n, 0.0f);
  g.cell_area_m2.assign(std::size_t(cells), 1.0);
  return g;
}

/// Sets hour h, cell c: mean and both spreads.
inline void set(HourlyGrid& g, int h, int c, float mean, float spread = 0.0f) {
  const std::size_t i = std::size_t(h) * g.cells + c;
  g.mean[i] = mean;
  g.spread_low[i] = g.spread_high[i] = spread;
}

inline std::vector<std::uint8_t> all_hours(int hours) {
  return std::vector<std::uint8_t>(std::size_t(hours), 1);
}

}  // namespace lightsolver::test
