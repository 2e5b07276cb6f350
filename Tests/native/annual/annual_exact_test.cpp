// The annual metrics on hand-made grids where each value is known exactly: DA, sDA, UDI, hours
// above thresholds, ASE, the LM-83 blinds rule, EN 17037, the masks, and intervals from spreads.
#include <gtest/gtest.h>

#include "annual_grids.hpp"
#include "lightsolver/statistics.hpp"

namespace lightsolver {
namespace {

using test::all_hours;
using test::flat_grid;
using test::set;

void expect_exact(const MetricInterval& m, double value) {
  EXPECT_DOUBLE_EQ(m.estimate, value);
  EXPECT_DOUBLE_EQ(m.low, value);
  EXPECT_DOUBLE_EQ(m.high, value);
}

void expect_interval(const MetricInterval& m, double estimate, double low, double high) {
  EXPECT_DOUBLE_EQ(m.estimate, estimate);
  EXPECT_DOUBLE_EQ(m.low, low);
  EXPECT_DOUBLE_EQ(m.high, high);
}

// 10 hours × 4 cells, spreads 0; hours 8 and 9 unoccupied at 5000 lx everywhere (they must not
// count). Cell 0: 2500, 3000, then 500; cell 1: 300 (exactly T) for 4 hours, then 299.9;
// cell 2: 1000 for 3 hours, then 0; cell 3: 0.
HourlyGrid four_cells() {
  HourlyGrid g = flat_grid(10, 4);
  for (int h = 0; h < 8; ++h) {
    set(g, h, 0, h == 0 ? 2500.0f : h == 1 ? 3000.0f : 500.0f);
    set(g, h, 1, h < 4 ? 300.0f : 299.9f);
    set(g, h, 2, h < 3 ? 1000.0f : 0.0f);
  }
  for (int h = 8; h < 10; ++h)
    for (int c = 0; c < 4; ++c) set(g, h, c, 5000.0f);
  return g;
}

std::vector<std::uint8_t> first_hours(int hours, int set_hours) {
  std::vector<std::uint8_t> m(std::size_t(hours), 0);
  for (int h = 0; h < set_hours; ++h) m[h] = 1;
  return m;
}

TEST(AnnualExact, DaSdaUdiAndHoursAboveFromTheMeans) {
  const AnnualMetrics m = annual_metrics(four_cells(), first_hours(10, 8), all_hours(10), {});
  ASSERT_EQ(m.cell.size(), 4u);
  EXPECT_EQ(m.occupied_hours, 8);
  EXPECT_EQ(m.daylight_hours, 10);
  EXPECT_DOUBLE_EQ(m.z_cell, z_for_alpha(0.05 / 8));
  EXPECT_DOUBLE_EQ(m.z_grid, z_for_alpha(0.05 / 32));
  const double da[] = {1.0, 0.5, 3.0 / 8, 0.0};
  const VerdictKind sda[] = {VerdictKind::Pass, VerdictKind::Pass, VerdictKind::Fail,
                             VerdictKind::Fail};
  for (int c = 0; c < 4; ++c) {
    expect_exact(m.cell[c].da, da[c]);
    EXPECT_EQ(m.cell[c].sda, sda[c]) << "cell " << c;
  }
  expect_exact(m.sda, 0.5);
  expect_exact(m.da, (1.0 + 0.5 + 0.375) / 4);
  EXPECT_EQ(m.sda_nominal, VerdictKind::Fail);  // 50 % < 55 %
  EXPECT_EQ(m.sda_preferred, VerdictKind::Fail);
  // UDI: 2500 and 3000 exceed 2000; 3000 is still within 100–3000 (inclusive).
  expect_exact(m.cell[0].udi_useful, 6.0 / 8);
  expect_exact(m.cell[0].udi_above, 2.0 / 8);
  expect_exact(m.cell[0].udi_useful_alt, 1.0);
  expect_exact(m.cell[0].udi_above_alt, 0.0);
  expect_exact(m.cell[1].udi_useful, 1.0);
  expect_exact(m.cell[2].udi_below, 5.0 / 8);
  expect_exact(m.cell[3].udi_below, 1.0);
  expect_exact(m.udi_below, (0.0 + 0.0 + 5.0 / 8 + 1.0) / 4);
  // Hours with E ≥ T for T = 100, 300, 500, 750, 1000, 2000, 3000.
  const double cell0[] = {8, 8, 8, 2, 2, 2, 1}, cell2[] = {3, 3, 3, 3, 3, 0, 0};
  ASSERT_EQ(m.cell[0].hours_above.size(), 7u);
  for (int t = 0; t < 7; ++t) {
    expect_exact(m.cell[0].hours_above[t], cell0[t]);
    expect_exact(m.cell[2].hours_above[t], cell2[t]);
  }
  expect_exact(m.hours_above[1], (8.0 + 4.0 + 3.0 + 0.0) / 4);  // ≥ 300 lx
  EXPECT_FALSE(m.sun_given);
  EXPECT_FALSE(m.blinds_given);
}

// EN 17037 over 4 equal cells: E_T over 50 % = the 2nd largest cell, E_TM over 95 % = the
// smallest. Hour by hour the 2nd largest is 1000, 1000, 500, 300, then 299.9 (4 hours), then
// 5000 twice; the smallest is 0 but for the last two hours (5000).
TEST(AnnualExact, En17037FractionsOfDaylightHours) {
  const AnnualMetrics m = annual_metrics(four_cells(), all_hours(10), all_hours(10), {});
  ASSERT_EQ(m.en17037.size(), 3u);
  const double target[] = {0.6, 0.5, 0.4};  // ≥ 300, ≥ 500, ≥ 750 lx
  const VerdictKind target_verdict[] = {VerdictKind::Pass, VerdictKind::Pass, VerdictKind::Fail};
  for (int l = 0; l < 3; ++l) {
    const En17037Illuminance& e = m.en17037[l];
    expect_exact(e.target.hours_fraction, target[l]);
    EXPECT_EQ(e.target.verdict, target_verdict[l]);
    expect_exact(e.minimum.hours_fraction, 0.2);  // 100, 300, 500 lx: only the 5000 lx hours
    EXPECT_EQ(e.minimum.verdict, VerdictKind::Fail);
    EXPECT_EQ(e.verdict, VerdictKind::Fail);
  }
  EXPECT_EQ(m.en17037[0].level, En17037Level::Minimum);
  EXPECT_DOUBLE_EQ(m.en17037[2].target.illuminance_lx, 750.0);
  EXPECT_DOUBLE_EQ(m.en17037[2].minimum.illuminance_lx, 500.0);
  // Only the first 4 hours as daylight hours: all reach 300 lx over half the area.
  const AnnualMetrics d = annual_metrics(four_cells(), all_hours(10), first_hours(10, 4), {});
  EXPECT_EQ(d.daylight_hours, 4);
  expect_exact(d.en17037[0].target.hours_fraction, 1.0);
  expect_exact(d.en17037[0].minimum.hours_fraction, 0.0);
}

// Hours whose interval straddles the threshold are neither surely in nor surely out: 4 hours
// at 400 ± 0, 3 at 310 ± 100 z, 3 at 290 ± 100 z (z ≥ 2.8 here). A dark cell at 50 ± 100 z
// clamps its lower end at 0 and may still reach 300.
TEST(AnnualExact, IntervalsCountTheHoursThatStraddle) {
  HourlyGrid g = flat_grid(10, 2);
  for (int h = 0; h < 10; ++h) {
    set(g, h, 0, h < 4 ? 400.0f : h < 7 ? 310.0f : 290.0f, h < 4 ? 0.0f : 100.0f);
    set(g, h, 1, 50.0f, 100.0f);
  }
  const AnnualMetrics m = annual_metrics(g, all_hours(10), all_hours(10), {});
  ASSERT_GE(m.z_cell, 2.8);
  expect_interval(m.cell[0].da, 0.7, 0.4, 1.0);
  EXPECT_EQ(m.cell[0].sda, VerdictKind::Undecided);
  expect_interval(m.cell[1].da, 0.0, 0.0, 1.0);
  expect_interval(m.cell[1].udi_below, 1.0, 0.0, 1.0);
  EXPECT_EQ(m.cell[1].sda, VerdictKind::Undecided);
  expect_interval(m.sda, 0.5, 0.0, 1.0);
  EXPECT_EQ(m.sda_nominal, VerdictKind::Undecided);
  // EN 17037 over 50 % of 2 cells: the larger cell, sure at 400 ± 0, straddling 300 lx at
  // 310 and 290 ± 100 z: the fraction is 0.7 in [0.4, 1], undecided against 0.5.
  expect_interval(m.en17037[0].target.hours_fraction, 0.7, 0.4, 1.0);
  EXPECT_EQ(m.en17037[0].target.verdict, VerdictKind::Undecided);
}

// ASE: direct sun > 1000 lx (strictly) for > 250 occupied hours (strictly). 300 occupied hours
// and 50 unoccupied ones at 1001 lx everywhere (not counted).
TEST(AnnualExact, AseCountsOccupiedHoursOfDirectSunExactly) {
  const int hours = 350, cells = 10;
  const HourlyGrid g = flat_grid(hours, cells, 400.0f);
  std::vector<float> sun(std::size_t(hours) * cells, 0.0f);
  for (int h = 0; h < hours; ++h) {
    float* row = &sun[std::size_t(h) * cells];
    if (h >= 300) {
      for (int c = 0; c < cells; ++c) row[c] = 1001.0f;
      continue;
    }
    row[0] = h < 251 ? 1001.0f : 0.0f;  // 251 hours: counts
    row[1] = 1000.0f;                   // not above 1000
    row[2] = h < 250 ? 1001.0f : 0.0f;  // 250 hours: not more than 250
  }
  const AnnualMetrics m = annual_metrics(g, first_hours(hours, 300), all_hours(hours), sun);
  EXPECT_TRUE(m.sun_given);
  EXPECT_EQ(m.cell[0].ase_hours, 251);
  EXPECT_EQ(m.cell[1].ase_hours, 0);
  EXPECT_EQ(m.cell[2].ase_hours, 250);
  EXPECT_DOUBLE_EQ(m.ase, 0.1);
  EXPECT_EQ(m.ase_verdict, VerdictKind::Pass);  // 10 % ≤ 10 %
  AnnualOptions o;
  o.ase_maximum = 0.05;
  EXPECT_EQ(annual_metrics(g, first_hours(hours, 300), all_hours(hours), sun, o).ase_verdict,
            VerdictKind::Fail);
}

// LM-83's blinds: closed at an occupied hour when more than 2 % of the area gets more than
// 1000 lx of direct sun. 50 cells (1 cell = 2 %): hour 0 one sunlit cell (not more than 2 %),
// hour 1 two (closed), hour 2 every cell at exactly 1000 lx (not above), hour 3 none.
TEST(AnnualExact, BlindsRuleSwapsInTheClosedGridForDa) {
  const int hours = 4, cells = 50;
  const HourlyGrid open = flat_grid(hours, cells, 500.0f);
  const HourlyGrid closed = flat_grid(hours, cells, 100.0f);
  std::vector<float> sun(std::size_t(hours) * cells, 0.0f);
  sun[0 * cells + 7] = 1001.0f;
  sun[1 * cells + 3] = sun[1 * cells + 4] = 1001.0f;
  for (int c = 0; c < cells; ++c) sun[2 * cells + c] = 1000.0f;
  const AnnualMetrics m =
      annual_metrics(open, all_hours(hours), all_hours(hours), sun, {}, &closed);
  EXPECT_TRUE(m.blinds_given);
  EXPECT_EQ(m.blinds_closed_hours, 1);
  for (const AnnualCellMetrics& c : m.cell) {
    expect_exact(c.da, 0.75);
    expect_exact(c.udi_useful, 1.0);  // UDI reads the grid as given
  }
  expect_exact(m.sda, 1.0);
  // Without the closed grid, or with hour 1 unoccupied, nothing changes DA.
  expect_exact(annual_metrics(open, all_hours(hours), all_hours(hours), sun).da, 1.0);
  std::vector<std::uint8_t> occupied = all_hours(hours);
  occupied[1] = 0;
  const AnnualMetrics u = annual_metrics(open, occupied, all_hours(hours), sun, {}, &closed);
  EXPECT_EQ(u.blinds_closed_hours, 0);
  expect_exact(u.da, 1.0);
}

// The cells' areas weight sDA and the grid means.
TEST(AnnualExact, AreasWeightTheGridValues) {
  HourlyGrid g = flat_grid(2, 4, 0.0f);
  for (int h = 0; h < 2; ++h) set(g, h, 0, 400.0f);
  g.cell_area_m2.assign(4, 0.25);
  const AnnualMetrics m = annual_metrics(g, all_hours(2), all_hours(2), {});
  EXPECT_DOUBLE_EQ(m.area_m2, 1.0);
  expect_exact(m.sda, 0.25);
  expect_exact(m.da, 0.25);
}

// DA at exactly half the hours meets sDA's 50 % (49 of 98: 49 × (1/98) rounds below 0.5).
TEST(AnnualExact, HalfTheHoursIsExactlyFiftyPercent) {
  ASSERT_LT(49.0 * (1.0 / 98.0), 0.5);
  HourlyGrid g = flat_grid(98, 1, 0.0f);
  for (int h = 0; h < 49; ++h) set(g, 2 * h, 0, 400.0f);
  const AnnualMetrics m = annual_metrics(g, all_hours(98), all_hours(98), {});
  EXPECT_EQ(m.cell[0].da.estimate, 0.5);
  EXPECT_EQ(m.cell[0].sda, VerdictKind::Pass);
  expect_exact(m.sda, 1.0);
}

// The caller's level for Wilson ends covers every critical value the metrics use.
TEST(AnnualExact, StrictestZCoversEveryLevel) {
  const AnnualOptions o;
  const double z = annual_strictest_z(o, 3650, 4380, 300);
  EXPECT_GE(z, z_for_alpha(0.05 / (3650.0 * 300)));
  EXPECT_GE(z, z_for_alpha(0.05 / (4380.0 * 285)));  // E_TM over 95 %: k = 285 of 300
  EXPECT_LT(z, 6.0);
}

}  // namespace
}  // namespace lightsolver
