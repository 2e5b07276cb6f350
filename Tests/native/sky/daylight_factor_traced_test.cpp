// Daylight-factor grids traced (docs/daylight.md, "Daylight factor and EN 17037"), on every
// backend: an open grid under a CIE clear sky beside a lamp of another group reads D = 100 %
// in every cell and statistic; a roof opening in a black room under the uniform sky gives
// D = 100 F (F the configuration factor to the opening). And the coverage of the order
// statistics' intervals over 600 seeds where every cell ties (docs/statistics.md, "Order
// statistics of noisy cells").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "lightsolver/angles.hpp"
#include "lightsolver/simulation.hpp"
#include "scene_builders.hpp"
#include "sky_rooms.hpp"

namespace lightsolver::test {
namespace {

Target df_grid(const std::string& name, dvec3 corner, dvec3 e1, dvec3 e2, unsigned nu,
               unsigned nv) {
  Target t = grid(name, corner, e1, e2, nu, nv);
  t.quantity = Target::Quantity::DaylightFactor;
  return t;
}

Estimate as_estimate(const OrderStatistic& o) {
  Estimate e;
  e.mean = o.value;
  e.ci_low = o.low;
  e.ci_high = o.high;
  return e;
}

void report_df(const Estimate& e, double exact, const std::string& what) {
  report(e, exact, "daylight factor (%), " + what);
}

class DaylightFactorTraced : public ::testing::TestWithParam<std::string> {};

// No geometry: every point of the grid sees the whole sky, so E_in = E_out and D = 100 % in
// every cell, whatever the sky's distribution. The ground's light crosses the grid from behind
// (not counted), and the lamp above, another group, adds lux but no daylight factor.
TEST_P(DaylightFactorTraced, OpenGridUnderAClearSkyReadsOneHundredPercent) {
  Scene s;
  Luminaire clear = sky("cie", 4000.0, 0.2);
  clear.sky.cie_type = 12;
  clear.sky.sun_direction = dvec3(0.3, -0.6, 0.5);
  clear.sky.site_centre = dvec3(0.0);
  clear.sky.site_radius_m = 1.2;
  s.luminaires.push_back(clear);
  s.luminaires.push_back(named(point_light({0, 0, 1}, 100000.0), "lamp", "electric"));
  s.targets.push_back(df_grid("open", {-0.8, -0.8, 0}, {1.6, 0, 0}, {0, 1.6, 0}, 2, 2));
  const Results r = run_on_backend(GetParam(), s, 600'000, 5);
  const TargetResult& t = r.targets[0];
  ASSERT_TRUE(t.daylight_factor);
  const DaylightFactorResult& d = *t.daylight_factor;
  EXPECT_EQ(d.sky, "sky");
  report_df(d.mean, 100.0, "open grid, mean");
  expect_in_ci(d.mean, 100.0, 0.03, "mean");
  for (std::size_t c = 0; c < d.cells.size(); ++c) {
    expect_in_ci(d.cells[c], 100.0, 0.06, "cell " + std::to_string(c));
  }
  for (const auto& [o, what] : {std::pair{d.min, "min"}, {d.p50, "p50"}, {d.p95, "p95"}}) {
    report_df(as_estimate(o), 100.0, std::string("open grid, ") + what);
    expect_in_ci(as_estimate(o), 100.0, 0.10, what);
  }
  // The lux are all groups' light: the lamp's is there, the daylight factor does not see it.
  EXPECT_GT(t.estimate.mean, 1.1 * d.outside_illuminance_lx);
}

// A 1 x 1 m roof opening (portal in the ceiling's hole) of a black 4 x 4 x 3 m room under the
// uniform sky L: E_in = L pi F, E_out = pi L, so D = 100 F, F averaged over each cell by a
// midpoint rule of the closed-form parallel-rectangle factor.
TEST_P(DaylightFactorTraced, RoofOpeningGivesOneHundredTimesTheConfigurationFactor) {
  Scene s;
  add_material(s, "black", Material::Type::Diffuse, 0.0);
  s.meshes.push_back(room_with_hole(0, {0, 0, 0}, {4, 4, 3}, true, {0.375, 0.625, 0.375, 0.625}));
  Luminaire l = sky("uniform", 1000.0, 0.0);
  l.sky.portals.push_back({{1.5, 1.5, 3}, {0, 1, 0}, {1, 0, 0}});
  s.luminaires.push_back(l);
  const dvec3 corner(0.9, 1.4, 0);  // off the opening's axis: four different cells
  const double side = 1.6;
  s.targets.push_back(df_grid("floor", corner, {side, 0, 0}, {0, side, 0}, 2, 2));
  const Results r = run_on_backend(GetParam(), s, 2'000'000, 7);
  const DaylightFactorResult& d = r.targets[0].daylight_factor.value();
  EXPECT_NEAR(d.outside_illuminance_lx, kPi * 1000.0, 1e-9 * kPi * 1000.0);
  std::vector<double> exact;
  const double cell = side / 2;
  for (int iv = 0; iv < 2; ++iv) {
    for (int iu = 0; iu < 2; ++iu) {
      double sum = 0.0;
      const int n = 40;
      for (int a = 0; a < n; ++a) {
        for (int b = 0; b < n; ++b) {
          const dvec3 p =
              corner + dvec3((iu + (a + 0.5) / n) * cell, (iv + (b + 0.5) / n) * cell, 0);
          sum += parallel_rect_factor(1.5 - p.x, 2.5 - p.x, 1.5 - p.y, 2.5 - p.y, 3.0);
        }
      }
      exact.push_back(100.0 * sum / (n * n));
    }
  }
  for (std::size_t c = 0; c < exact.size(); ++c) {
    report_df(d.cells[c], exact[c], "roof opening, cell " + std::to_string(c));
    expect_in_ci(d.cells[c], exact[c], 0.06, "cell " + std::to_string(c));
  }
  double mean = 0.0;
  for (const double e : exact) mean += e / 4.0;
  report_df(d.mean, mean, "roof opening, mean");
  expect_in_ci(d.mean, mean, 0.03, "mean");
  std::sort(exact.begin(), exact.end(), std::greater<>());
  report_df(as_estimate(d.p50), exact[1], "roof opening, p50");
  report_df(as_estimate(d.min), exact[3], "roof opening, min");
  // 4 cells: p50 is the 2nd largest, p95 and min the smallest.
  expect_in_ci(as_estimate(d.p50), exact[1], 0.12, "p50");
  expect_in_ci(as_estimate(d.p95), exact[3], 0.12, "p95");
  expect_in_ci(as_estimate(d.min), exact[3], 0.12, "min");
}

INSTANTIATE_TEST_SUITE_P(Backends, DaylightFactorTraced, ::testing::ValuesIn(backends()));

bool holds(double low, double truth, double high) { return low <= truth && truth <= high; }

// Sixteen tied cells (an open grid: D = 100 % each; ties are the hard case for an order
// statistic), ~100 hits a cell: the order statistics' intervals must cover 100 % in at least
// c - 4 sd of the coverage of 500 runs, hold their estimates, and not be vacuous.
TEST(DaylightFactorCoverage, OrderStatisticsCoverTiedCellsOver500Seeds) {
  Scene s;
  Luminaire u = sky("uniform", 1000.0, 0.0);
  u.sky.site_centre = dvec3(0.0);
  u.sky.site_radius_m = 1.5;
  s.luminaires.push_back(u);
  s.targets.push_back(df_grid("open", {-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 4, 4));
  validate(s);
  Simulation sim(s, {"embree", 0, {}});
  constexpr int kRuns = 500;
  int min_in = 0, p50_in = 0, p95_in = 0;
  double width = 0.0;
  for (int seed = 1; seed <= kRuns; ++seed) {
    SolveOptions o;
    o.photons = 6000;
    o.seed = seed;
    const Results r = sim.run(o);
    const DaylightFactorResult& d = r.targets[0].daylight_factor.value();
    min_in += holds(d.min.low, 100.0, d.min.high);
    p50_in += holds(d.p50.low, 100.0, d.p50.high);
    p95_in += holds(d.p95.low, 100.0, d.p95.high);
    width += (d.p50.high - d.p50.low) / 100.0 / kRuns;
    for (const OrderStatistic& x : {d.min, d.p50, d.p95}) {
      EXPECT_TRUE(holds(x.low, x.value, x.high));
    }
  }
  const double floor = 0.95 - 4.0 * std::sqrt(0.95 * 0.05 / kRuns);
  std::printf(
      "[ sky      ] coverage over %d seeds: min %.3f, p50 %.3f, p95 %.3f, mean relative "
      "p50 width %.3f\n",
      kRuns, double(min_in) / kRuns, double(p50_in) / kRuns, double(p95_in) / kRuns, width);
  EXPECT_GE(double(min_in) / kRuns, floor);
  EXPECT_GE(double(p50_in) / kRuns, floor);
  EXPECT_GE(double(p95_in) / kRuns, floor);
  EXPECT_LT(width, 0.7);  // not vacuous: ~100 hits a cell, +-10 % each
}

}  // namespace
}  // namespace lightsolver::test
