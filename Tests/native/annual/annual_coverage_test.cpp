// Coverage of the annual metrics' intervals: a known "truth" hours × cells, estimates drawn
// around it with known σ (fixed seeds), and the share of replicates whose interval holds the
// truth's metric, against the stated confidence within binomial limits c − 4·√(c(1−c)/n).
// Half the cells are built so that one wrong hour makes an end miss: hours surely on one side
// of a limit (300, 100, 2000, 3000 lx) beside hours 0.1 lx on the other side of it, where each
// can be counted wrongly. There coverage comes close to the stated one (Bonferroni over an
// hour's worth of such hours is nearly exact); a per-hour z of 1.96 would miss most of the time.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "annual_grids.hpp"
#include "lightsolver/weather.hpp"

namespace lightsolver {
namespace {

using test::all_hours;
using test::flat_grid;

constexpr int kHours = 120, kCells = 40, kReplicates = 300;

// Cells 0–9: DA's ends. Even: 59 hours at 400 lx and 61 at 299.7 (DA 59/120, just failing
// sDA's 50 %: one hour counted wrongly would pass it); odd: 60 at 300.3 and 60 at 200 (DA 0.5,
// just passing). Cells 10–19 the same round UDI's limits. Cells 20–39: a daylit room, a level
// falling with depth times a smooth daily profile.
float truth_lx(int h, int c) {
  if (c < 10) return c % 2 == 0 ? (h < 59 ? 400.0f : 299.7f) : (h % 2 ? 300.3f : 200.0f);
  if (c < 20) {
    const float in_or_near[] = {1000.0f, 99.9f, 2000.1f, 3000.1f};           // lower ends
    const float near_or_out[] = {100.1f, 20.0f, 1999.9f, 2999.9f, 6000.0f};  // upper ends
    return c % 2 == 0 ? in_or_near[h % 4] : near_or_out[h % 5];
  }
  const double depth = (c - 20) / 20.0, day = std::sin(M_PI * ((h % 12) + 0.5) / 12.0);
  return float(3000.0 * std::exp(-3.0 * depth) * (0.15 + day));
}

double sigma_lx(float truth) { return 0.05 * truth + 2.0; }

HourlyGrid truth_grid() {
  HourlyGrid g = flat_grid(kHours, kCells);
  for (int h = 0; h < kHours; ++h)
    for (int c = 0; c < kCells; ++c) test::set(g, h, c, truth_lx(h, c));
  return g;
}

HourlyGrid noisy(const HourlyGrid& truth, std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  HourlyGrid g = truth;
  for (std::size_t i = 0; i < g.mean.size(); ++i) {
    const double s = sigma_lx(truth.mean[i]);
    g.mean[i] = float(std::max(0.0, truth.mean[i] + s * normal(rng)));
    g.spread_low[i] = g.spread_high[i] = float(s);
  }
  return g;
}

// Hits and widths of one metric over the replicates.
struct Tally {
  std::string name;
  int hits = 0, trials = 0;
  double width = 0.0;
  void add(const MetricInterval& m, double truth) {
    ASSERT_TRUE(std::isfinite(m.low) && std::isfinite(m.high));
    ASSERT_LE(m.low, m.estimate);
    ASSERT_LE(m.estimate, m.high);
    hits += m.low <= truth && truth <= m.high;
    ++trials;
    width += m.high - m.low;
  }
};

TEST(AnnualCoverage, IntervalsHoldTheTruthAtTheStatedConfidence) {
  const HourlyGrid truth = truth_grid();
  const std::vector<std::uint8_t> all = all_hours(kHours);
  const AnnualMetrics t = annual_metrics(truth, all, all, {});  // spreads 0: the true metrics
  // Per cell: DA, UDI below, useful, above, useful to 3000; per level: EN 17037's two criteria.
  const auto per_cell = [](const AnnualCellMetrics& c) {
    return std::vector<MetricInterval>{c.da, c.udi_below, c.udi_useful, c.udi_above,
                                       c.udi_useful_alt};
  };
  const char* cell_names[] = {"DA", "UDI below", "UDI useful", "UDI above", "UDI useful 3000"};
  std::vector<Tally> grid = {{"sDA"}, {"DA (grid mean)"}, {"UDI useful (grid mean)"}};
  std::vector<std::vector<Tally>> cells(5, std::vector<Tally>(kCells, Tally{""}));
  std::vector<Tally> en(6, Tally{""});
  std::mt19937_64 rng(20261127);
  for (int r = 0; r < kReplicates; ++r) {
    const AnnualMetrics m = annual_metrics(noisy(truth, rng), all, all, {});
    grid[0].add(m.sda, t.sda.estimate);
    grid[1].add(m.da, t.da.estimate);
    grid[2].add(m.udi_useful, t.udi_useful.estimate);
    for (int c = 0; c < kCells; ++c) {
      const auto got = per_cell(m.cell[c]), want = per_cell(t.cell[c]);
      for (int k = 0; k < 5; ++k) cells[k][c].add(got[k], want[k].estimate);
    }
    for (int l = 0; l < 3; ++l) {
      en[2 * l].add(m.en17037[l].target.hours_fraction,
                    t.en17037[l].target.hours_fraction.estimate);
      en[2 * l + 1].add(m.en17037[l].minimum.hours_fraction,
                        t.en17037[l].minimum.hours_fraction.estimate);
    }
  }
  const double c = 0.95, n = kReplicates, floor = c - 4.0 * std::sqrt(c * (1.0 - c) / n);
  std::printf(
      "annual coverage, %d replicates, %d hours x %d cells, z_cell %.3f z_grid %.3f, "
      "floor %.3f\n",
      kReplicates, kHours, kCells, t.z_cell, t.z_grid, floor);
  const auto check = [&](const std::string& name, const Tally& x, double width) {
    const double coverage = double(x.hits) / x.trials;
    std::printf("  %-34s coverage %.3f  mean width %.4f\n", name.c_str(), coverage, width);
    EXPECT_GE(coverage, floor) << name;
  };
  for (const Tally& x : grid) check(x.name, x, x.width / x.trials);
  // Cells: the worst cell's coverage; widths over the near-limit cells (0–19) and the daylit
  // room's (20–39) apart.
  for (int k = 0; k < 5; ++k) {
    const Tally* worst = &cells[k][0];
    double near = 0.0, room = 0.0;
    for (int i = 0; i < kCells; ++i) {
      if (cells[k][i].hits < worst->hits) worst = &cells[k][i];
      (i < 20 ? near : room) += cells[k][i].width / kReplicates / 20.0;
    }
    check(std::string(cell_names[k]) + " (worst cell)", *worst, near);
    std::printf("  %-34s                 mean width %.4f\n",
                (std::string(cell_names[k]) + " (daylit cells)").c_str(), room);
  }
  const char* levels[] = {"minimum", "medium", "high"};
  for (int i = 0; i < 6; ++i)
    check(std::string("EN 17037 ") + levels[i / 2] + (i % 2 ? " E_TM" : " E_T"), en[i],
          en[i].width / en[i].trials);
}

// A year at full size (8760 hours, LM-83 occupancy, 300 cells of a side-lit room, σ = 5 %):
// the intervals' widths and the time, printed; the truth's sDA inside its interval.
TEST(AnnualCoverage, AYearOfThreeHundredCellsIsQuickAndNarrow) {
  const int hours = 8760, cells = 300;
  std::vector<int> stamps;
  std::vector<double> diffuse;
  HourlyGrid truth = flat_grid(hours, cells);
  for (int h = 0; h < hours; ++h) {
    const int day = h / 24, stamp = h % 24 + 1;
    stamps.push_back(stamp);
    const double season = 0.6 + 0.4 * std::cos(2.0 * M_PI * (day - 172) / 365.0);
    const double sun = std::max(0.0, std::sin(M_PI * (stamp - 0.5 - 6.0) / 12.0)) * season;
    diffuse.push_back(20000.0 * sun);
    for (int c = 0; c < cells; ++c) {
      const double depth = (c / 10) * 0.2;  // 30 rows of 10 cells, 0.2 m apart
      test::set(truth, h, c, float(8000.0 * sun * std::exp(-depth / 1.2)));
    }
  }
  const std::vector<std::uint8_t> occupied = lm83_occupancy(stamps);
  const std::vector<std::uint8_t> daylight = en17037_daylight_hours(diffuse);
  std::mt19937_64 rng(7);
  const HourlyGrid estimate = noisy(truth, rng);
  const auto start = std::chrono::steady_clock::now();
  const AnnualMetrics m = annual_metrics(estimate, occupied, daylight, {});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const AnnualMetrics t = annual_metrics(truth, occupied, daylight, {});
  double da_width = 0.0;
  for (const AnnualCellMetrics& c : m.cell) da_width += (c.da.high - c.da.low) / cells;
  std::printf("a year, 300 cells: %.2f s; z_cell %.3f z_grid %.3f\n", seconds, m.z_cell, m.z_grid);
  std::printf("  sDA %.3f [%.3f, %.3f] (truth %.3f); mean DA width per cell %.4f\n", m.sda.estimate,
              m.sda.low, m.sda.high, t.sda.estimate, da_width);
  std::printf("  EN 17037 minimum target fraction %.3f [%.3f, %.3f] (truth %.3f)\n",
              m.en17037[0].target.hours_fraction.estimate, m.en17037[0].target.hours_fraction.low,
              m.en17037[0].target.hours_fraction.high, t.en17037[0].target.hours_fraction.estimate);
  EXPECT_EQ(m.occupied_hours, 3650);
  EXPECT_EQ(m.daylight_hours, 4380);
  EXPECT_LE(m.sda.low, t.sda.estimate);
  EXPECT_GE(m.sda.high, t.sda.estimate);
}

}  // namespace
}  // namespace lightsolver
