// Bad input to the annual metrics (an InputError naming the field, never NaN), the mask
// helpers (LM-83 occupancy, EN 17037 daylight hours) and the metrics' JSON.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "annual_grids.hpp"
#include "lightsolver/error.hpp"
#include "lightsolver/weather.hpp"

namespace lightsolver {
namespace {

using test::all_hours;
using test::flat_grid;
using test::set;

// `f` throws an InputError whose field starts with `where`.
void expect_input_error(const std::function<void()>& f, const std::string& where) {
  try {
    f();
    ADD_FAILURE() << "no error for " << where;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().rfind(where, 0), 0u) << e.what();
  }
}

struct Inputs {
  HourlyGrid grid = flat_grid(4, 3, 200.0f);
  std::vector<std::uint8_t> occupied = all_hours(4), daylight = all_hours(4);
  std::vector<float> sun;
  AnnualOptions options;
  const HourlyGrid* blinds = nullptr;
  void run() const { annual_metrics(grid, occupied, daylight, sun, options, blinds); }
};

TEST(AnnualInput, BadInputNamesTheField) {
  const auto bad = [](const std::function<void(Inputs&)>& edit, const std::string& where) {
    Inputs in;
    edit(in);
    expect_input_error([&] { in.run(); }, where);
  };
  const float nan = std::numeric_limits<float>::quiet_NaN();
  bad([](Inputs& in) { in.grid.mean.pop_back(); }, "grid.mean");
  bad([](Inputs& in) { in.grid.mean[5] = -1.0f; }, "grid.mean[5] (hour 1, cell 2)");
  bad([nan](Inputs& in) { in.grid.spread_low[0] = nan; }, "grid.spread_low[0]");
  bad([](Inputs& in) { in.grid.spread_high[1] = std::numeric_limits<float>::infinity(); },
      "grid.spread_high[1]");
  bad([](Inputs& in) { in.grid.cell_area_m2.pop_back(); }, "grid.cell_area_m2");
  bad([](Inputs& in) { in.grid.cell_area_m2[1] = 0.0; }, "grid.cell_area_m2[1]");
  bad([](Inputs& in) { in.grid.cell_area_m2[2] = 1.5; }, "grid.cell_area_m2[2]");
  bad([](Inputs& in) { in.grid = flat_grid(0, 3); }, "grid.hours");
  bad([](Inputs& in) { in.occupied.assign(4, 0); }, "occupied");
  bad([](Inputs& in) { in.occupied.push_back(1); }, "occupied");
  bad([](Inputs& in) { in.occupied[2] = 2; }, "occupied[2]");
  bad([](Inputs& in) { in.daylight.assign(4, 0); }, "daylight_hour");
  bad([](Inputs& in) { in.sun.assign(5, 0.0f); }, "direct_sun_lx");
  bad([nan](Inputs& in) { in.sun.assign(12, nan); }, "direct_sun_lx[0]");
  bad([](Inputs& in) { in.options.confidence = 1.0; }, "options.confidence");
  bad([](Inputs& in) { in.options.sda_fraction = 1.5; }, "options.sda_fraction");
  bad([](Inputs& in) { in.options.udi_high_lx = 50.0; }, "options.udi_low_lx");
  bad(
      [](Inputs& in) {
        in.options.hour_thresholds_lx = {300.0, -1.0};
      },
      "options.hour_thresholds_lx[1]");
  static const HourlyGrid other = flat_grid(5, 3);
  bad(
      [](Inputs& in) {
        in.sun.assign(12, 0.0f);
        in.blinds = &other;
      },
      "blinds_closed");
  static const HourlyGrid same = flat_grid(4, 3);
  bad([](Inputs& in) { in.blinds = &same; }, "direct_sun_lx");  // blinds need the sun
}

TEST(AnnualInput, Lm83OccupancyIsEightToSixEveryDay) {
  std::vector<int> stamps;
  for (int d = 0; d < 365; ++d)
    for (int h = 1; h <= 24; ++h) stamps.push_back(h);
  const std::vector<std::uint8_t> occ = lm83_occupancy(stamps);
  EXPECT_EQ(std::count(occ.begin(), occ.end(), 1), 3650);
  EXPECT_EQ(occ[7], 0);   // 7:00–8:00
  EXPECT_EQ(occ[8], 1);   // stamp 9: 8:00–9:00
  EXPECT_EQ(occ[17], 1);  // stamp 18: 17:00–18:00
  EXPECT_EQ(occ[18], 0);
  expect_input_error([] { lm83_occupancy({9, 25}); }, "hour_stamps[1]");
  expect_input_error([] { lm83_occupancy({0}); }, "hour_stamps[0]");
}

TEST(AnnualInput, DaylightHoursAreTheBrighterHalf) {
  const std::vector<std::uint8_t> m = en17037_daylight_hours({5.0, 1.0, 5.0, 0.0, 2.0});
  EXPECT_EQ(m, (std::vector<std::uint8_t>{1, 0, 1, 0, 0}));  // ⌊5/2⌋ = 2 hours
  // Ties at the boundary go to the earlier hours.
  EXPECT_EQ(en17037_daylight_hours({3.0, 3.0, 3.0, 3.0}), (std::vector<std::uint8_t>{1, 1, 0, 0}));
  expect_input_error([] { en17037_daylight_hours({1.0, -1.0}); }, "diffuse_horizontal_lx[1]");
  expect_input_error(
      [] {
        en17037_daylight_hours({1.0, std::nan("")});
      },
      "diffuse_horizontal_lx[1]");
  expect_input_error([] { en17037_daylight_hours({1.0}); }, "diffuse_horizontal_lx");
}

// Chicago's year: 4380 daylight hours, and E_v,d,med is the median over exactly those.
TEST(AnnualInput, DaylightHoursOfChicagoGiveItsMedian) {
  const WeatherFile w =
      read_epw(std::filesystem::path(LIGHTSOLVER_SOURCE_DIR) /
               "Tests/native/sun/data/USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw");
  std::vector<double> lux;
  for (const WeatherHour& h : w.hours) lux.push_back(*h.diffuse_horizontal_lx);
  const std::vector<std::uint8_t> d = en17037_daylight_hours(lux);
  EXPECT_EQ(std::count(d.begin(), d.end(), 1), 4380);
  int above = 0, below = 0;  // the median splits the daylight hours in halves
  const double median = median_external_diffuse_illuminance(w);
  for (std::size_t i = 0; i < lux.size(); ++i) {
    if (!d[i]) continue;
    above += lux[i] > median;
    below += lux[i] < median;
  }
  EXPECT_LE(above, 2190);
  EXPECT_LE(below, 2190);
}

// Every number in `j` is finite (a NaN would be written as null and read back as nothing).
void expect_finite(const nlohmann::json& j) {
  if (j.is_number()) EXPECT_TRUE(std::isfinite(j.get<double>()));
  if (j.is_structured())
    for (const auto& v : j) expect_finite(v);
}

TEST(AnnualInput, JsonCarriesEveryMetricWithUnits) {
  HourlyGrid g = flat_grid(4, 2, 500.0f);
  set(g, 0, 1, 50.0f, 10.0f);
  std::vector<float> sun(8, 0.0f);
  const AnnualMetrics m = annual_metrics(g, all_hours(4), all_hours(4), sun);
  const nlohmann::json j = annual_metrics_json(m);
  EXPECT_DOUBLE_EQ(j["sda_percent"]["estimate"].get<double>(), 100.0 * m.sda.estimate);
  EXPECT_DOUBLE_EQ(j["da_fraction"]["low"].get<double>(), m.da.low);
  EXPECT_DOUBLE_EQ(j["udi_useful_fraction"]["high"].get<double>(), m.udi_useful.high);
  EXPECT_DOUBLE_EQ(j["ase_percent"].get<double>(), 0.0);
  EXPECT_EQ(j["ase_verdict"], "pass");
  EXPECT_EQ(j["occupied_hours"], 4);
  EXPECT_EQ(j["cells"]["da_fraction"]["estimate"].size(), 2u);
  EXPECT_DOUBLE_EQ(j["cells"]["da_fraction"]["estimate"][1].get<double>(), 0.75);
  EXPECT_EQ(j["cells"]["sda_verdict"][0], "pass");
  EXPECT_EQ(j["cells"]["hours_above"].size(), m.options.hour_thresholds_lx.size());
  EXPECT_EQ(j["cells"]["ase_hours"][0], 0);
  ASSERT_EQ(j["en17037"].size(), 3u);
  EXPECT_EQ(j["en17037"][2]["level"], "high");
  EXPECT_DOUBLE_EQ(j["en17037"][2]["target"]["illuminance_lx"].get<double>(), 750.0);
  EXPECT_TRUE(j["blinds_closed_hours"].is_null());
  expect_finite(j);
  // Without sun: no ASE at all, not a 0.
  const nlohmann::json n = annual_metrics_json(annual_metrics(g, all_hours(4), all_hours(4), {}));
  EXPECT_TRUE(n["ase_percent"].is_null());
  EXPECT_TRUE(n["cells"]["ase_hours"].is_null());
}

}  // namespace
}  // namespace lightsolver
