// Daylight-factor grids (docs/scene-format.md, "Targets"; docs/daylight.md, "Daylight factor
// and EN 17037"): the scene keys and every error named by field, EN 17037's targets, the order
// statistics' ranks and intervals on hand-made cells, a decide run deciding a DF requirement
// each way, the results file both ways and a rescale that leaves the daylight factor alone.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "lightsolver/compliance.hpp"
#include "lightsolver/rescale.hpp"
#include "lightsolver/results_io.hpp"
#include "lightsolver/scene_io.hpp"
#include "scene_builders.hpp"
#include "sky_rooms.hpp"

namespace lightsolver::test {
namespace {

// A scene file with a sky through a roof opening, `extra_luminaires` after it (JSON objects,
// each with a leading comma) and the target `target`.
std::string df_scene(const std::string& target, const std::string& extra_luminaires = "",
                     const std::string& sky_group = "") {
  return R"({"format": "lightsolver.scene/1",
  "materials": {"grey": {"type": "diffuse", "reflectance": 0.5}},
  "meshes": [{"name": "floor", "material": "grey",
              "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "triangles": [[0,1,2],[0,2,3]]}],
  "luminaires": [{"name": "sky", "type": "sky", "model": "cie_overcast",
                  "diffuse_horizontal_lx": 10000)" +
         (sky_group.empty() ? "" : ", \"group\": \"" + sky_group + "\"") +
         R"(, "portals": [{"corner": [0,0,3], "edge1": [0,1,0], "edge2": [1,0,0]}]})" +
         extra_luminaires + R"(],
  "targets": [)" +
         target + "]}";
}

std::string df_target(const std::string& requirements,
                      const std::string& quantity = "daylight_factor") {
  return R"({"name": "df", "type": "grid", "quantity": ")" + quantity +
         R"(", "corner": [0,0,0.8], "edge1": [1,0,0], "edge2": [0,1,0], "cells": [2,2])" +
         (requirements.empty() ? "" : ", \"requirements\": " + requirements) + "}";
}

std::string df_error_of(const std::string& text) {
  try {
    scene_from_json(text, "scene.json", "");
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no error>";
}

const char* kLamp =
    R"(, {"name": "lamp", "type": "point", "flux_lm": 1000, "position": [0.5,0.5,2]})";

TEST(DaylightFactorScene, ReadsTheQuantityAndEn17037Targets) {
  const Scene s =
      scene_from_json(df_scene(df_target(R"({"en17037": "medium", "median_diffuse_lx": 15900})")),
                      "scene.json", "");
  const Target& t = s.targets[0];
  EXPECT_EQ(t.quantity, Target::Quantity::DaylightFactor);
  EXPECT_EQ(t.requirements.en17037, En17037Level::Medium);
  EXPECT_DOUBLE_EQ(*t.requirements.df_target(), 500.0 / 15900.0 * 100.0);
  EXPECT_DOUBLE_EQ(*t.requirements.df_minimum(), 300.0 / 15900.0 * 100.0);
  EXPECT_EQ(t.requirements.source, "EN 17037:2018, daylight factor method, medium");
  // An explicit key replaces the derived one; the other stays derived.
  const Scene e = scene_from_json(
      df_scene(df_target(
          R"({"en17037": "high", "median_diffuse_lx": 20000, "df_target_percent": 4.5})")),
      "scene.json", "");
  EXPECT_DOUBLE_EQ(*e.targets[0].requirements.df_target(), 4.5);
  EXPECT_DOUBLE_EQ(*e.targets[0].requirements.df_minimum(), 500.0 / 20000.0 * 100.0);
  // Illuminance is the default quantity.
  const Scene plain = scene_from_json(df_scene(df_target("", "illuminance")), "scene.json", "");
  EXPECT_EQ(plain.targets[0].quantity, Target::Quantity::Illuminance);
}

TEST(DaylightFactorScene, EveryBadInputIsNamed) {
  const std::string ok = df_target(R"({"df_target_percent": 2})");
  const struct {
    std::string text, field;
  } cases[] = {
      {df_scene(df_target("", "lux")), "targets[0].quantity"},
      // No sky; two skies.
      {R"({"format": "lightsolver.scene/1", "materials": {}, "meshes": [], "luminaires": [{"name": "lamp", "type": "point",
          "flux_lm": 1000, "position": [0.5,0.5,2]}], "targets": [)" +
           ok + "]}",
       "targets[0].quantity"},
      {df_scene(ok, R"(, {"name": "sky2", "type": "sky", "model": "uniform",
          "diffuse_horizontal_lx": 5000, "portals": [{"corner": [0,0,3], "edge1": [0,1,0],
          "edge2": [1,0,0]}]})"),
       "targets[0].quantity"},
      // The sky's group shared with a lamp.
      {df_scene(ok, R"(, {"name": "lamp", "type": "point", "flux_lm": 1000,
          "position": [0.5,0.5,2], "group": "daylight"})",
                "daylight"),
       "luminaires[1].group"},
      // DF keys where there is no daylight factor.
      {df_scene(df_target(R"({"df_target_percent": 2})", "illuminance")),
       "targets[0].requirements.df_target_percent"},
      {df_scene(df_target(R"({"en17037": "minimum", "median_diffuse_lx": 15900})", "illuminance")),
       "targets[0].requirements.en17037"},
      // Illuminance requirements and tasks on a DF grid.
      {df_scene(df_target(R"({"em_lux": 500})")), "targets[0].requirements.em_lux"},
      {df_scene(df_target(R"({"u0": 0.6})")), "targets[0].requirements.u0"},
      // Levels, medians and percentages out of range.
      {df_scene(df_target(R"({"en17037": "good", "median_diffuse_lx": 15900})")),
       "targets[0].requirements.en17037"},
      {df_scene(df_target(R"({"en17037": "minimum"})")),
       "targets[0].requirements.median_diffuse_lx"},
      {df_scene(df_target(R"({"median_diffuse_lx": 15900})")),
       "targets[0].requirements.median_diffuse_lx"},
      {df_scene(df_target(R"({"en17037": "minimum", "median_diffuse_lx": 0})")),
       "targets[0].requirements.median_diffuse_lx"},
      {df_scene(df_target(R"({"en17037": "minimum", "median_diffuse_lx": -3})")),
       "targets[0].requirements.median_diffuse_lx"},
      {df_scene(df_target(R"({"df_minimum_percent": 0})")),
       "targets[0].requirements.df_minimum_percent"},
      {df_scene(df_target(R"({"df_target_percent": 101})")),
       "targets[0].requirements.df_target_percent"},
  };
  for (const auto& c : cases) {
    const std::string e = df_error_of(c.text);
    EXPECT_NE(e.find(c.field), std::string::npos) << c.field << " | " << e;
  }
  // The same sky with a lamp in a group of its own is fine.
  EXPECT_EQ(df_error_of(df_scene(ok, kLamp)), "<no error>");
}

TEST(DaylightFactorScene, NanMedianAndTaskAreNamed) {
  Scene s = scene_from_json(df_scene(df_target("")), "scene.json", "");
  s.targets[0].requirements.en17037 = En17037Level::Minimum;
  s.targets[0].requirements.median_diffuse_lx = std::numeric_limits<double>::quiet_NaN();
  try {
    validate(s);
    FAIL() << "a NaN median was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("targets[0].requirements.median_diffuse_lx"),
              std::string::npos)
        << e.what();
  }
  s.targets[0].requirements = {};
  s.targets[0].requirements.task = "1.2.3";
  s.targets[0].requirements.emin_lux = 100.0;
  EXPECT_THROW(
      {
        try {
          validate(s);
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("targets[0].task"), std::string::npos);
          throw;
        }
      },
      InputError);
}

TEST(DaylightFactorStatistics, AreaFractionRanks) {
  EXPECT_EQ(area_fraction_rank(16, 0.5), 8u);
  EXPECT_EQ(area_fraction_rank(16, 0.95), 16u);
  EXPECT_EQ(area_fraction_rank(60, 0.5), 30u);
  EXPECT_EQ(area_fraction_rank(60, 0.95), 57u);
  EXPECT_EQ(area_fraction_rank(1, 0.5), 1u);
  EXPECT_EQ(area_fraction_rank(3, 0.5), 2u);  // 1.5 cells: two cells reach it
}

// Hand-made cells with intervals value +- z sigma: the k-th largest, its lower end from the
// m - k + 1 cells' bounds at two-sided alpha / (m - k + 1), its upper end at alpha / k.
TEST(DaylightFactorStatistics, OrderStatisticIntervalsUseTheirBonferroniLevels) {
  const std::vector<double> values = {5, 1, 4, 2, 3};  // sigma 0.1 each
  GridSampler s;
  s.cells = 5;
  s.cell = [&](std::uint32_t c, double alpha) {
    const double z = z_for_alpha(alpha);
    Estimate e;
    e.mean = values[c];
    e.ci_low = values[c] - 0.1 * z;
    e.ci_high = values[c] + 0.1 * z;
    return e;
  };
  s.grid = [&](double) { return Estimate{}; };
  const OrderStatistic p50 = order_statistic(s, values, area_fraction_rank(5, 0.5), 0.95);
  EXPECT_DOUBLE_EQ(p50.value, 3.0);  // k = 3
  EXPECT_NEAR(p50.low, 3.0 - 0.1 * z_for_alpha(0.05 / 3.0), 1e-12);
  EXPECT_NEAR(p50.high, 3.0 + 0.1 * z_for_alpha(0.05 / 3.0), 1e-12);
  const OrderStatistic min = order_statistic(s, values, 5, 0.95);
  EXPECT_DOUBLE_EQ(min.value, 1.0);  // the Emin rule: one cell below, all five above
  EXPECT_NEAR(min.low, 1.0 - 0.1 * z_for_alpha(0.05), 1e-12);
  EXPECT_NEAR(min.high, 1.0 + 0.1 * z_for_alpha(0.01), 1e-12);
  EXPECT_THROW(order_statistic(s, values, 0, 0.95), std::invalid_argument);
  EXPECT_THROW(order_statistic(s, values, 6, 0.95), std::invalid_argument);
}

// A roof opening over a grey floor (D a few %) lit also by a lamp in its own group.
Scene roof_room(const std::string& requirements) {
  Scene s = scene_from_json(df_scene(df_target(requirements), kLamp), "scene.json", "");
  return s;
}

TEST(DaylightFactorDecide, DecidesAPassAndAFail) {
  // df_target 50 % is far above the grid's D (a few %), df_minimum 0.01 % far below it.
  Scene s = roof_room(R"({"df_target_percent": 50, "df_minimum_percent": 0.01})");
  SolveOptions o;
  o.decide = true;
  o.backend = "embree";
  o.photons = 50'000'000;  // the budget
  const Results r = solve(s, o);
  ASSERT_EQ(r.stop_reason, kStopDecided);
  const TargetResult& t = r.targets[0];
  ASSERT_EQ(t.verdicts.size(), 2u);
  EXPECT_EQ(t.verdicts[0].name, "df_target");
  EXPECT_EQ(t.verdicts[0].verdict, VerdictKind::Fail);
  EXPECT_EQ(t.verdicts[1].name, "df_minimum");
  EXPECT_EQ(t.verdicts[1].verdict, VerdictKind::Pass);
  EXPECT_EQ(r.verdict, VerdictKind::Fail);
  EXPECT_DOUBLE_EQ(t.verdicts[0].value, t.daylight_factor->p50.value);
  EXPECT_DOUBLE_EQ(t.verdicts[1].value, t.daylight_factor->p95.value);
  EXPECT_LT(r.photons, 1'000'000u);  // clear cases decide at once
}

TEST(DaylightFactorDecide, AnUndecidedVerdictSaysWhatDecidingCosts) {
  Scene s = roof_room(R"({"df_target_percent": 1.0})");
  SolveOptions o;
  o.backend = "embree";
  o.photons = 20'000;
  o.seed = 3;
  Results r = solve(s, o);
  const DaylightFactorResult& d = r.targets[0].daylight_factor.value();
  // Put the requirement inside the p50 interval: undecided, with a finite cost.
  s.targets[0].requirements.df_target_percent = 0.5 * (d.p50.value + d.p50.high);
  r = solve(s, o);
  const Verdict& v = r.targets[0].verdicts.at(0);
  EXPECT_EQ(v.verdict, VerdictKind::Undecided);
  ASSERT_TRUE(v.photons_to_decide);
  EXPECT_GT(*v.photons_to_decide, 20'000.0);
  const auto j = nlohmann::json::parse(results_to_json(r));
  EXPECT_TRUE(j["targets"][0]["verdicts"]["df_target"].contains("to_decide"));
}

TEST(DaylightFactorResults, JsonRoundTripAndRescaleKeepTheDaylightFactor) {
  Scene s = roof_room(R"({"en17037": "minimum", "median_diffuse_lx": 15900})");
  SolveOptions o;
  o.backend = "embree";
  o.photons = 200'000;
  o.contributions = true;
  const Results r = solve(s, o);
  const std::string json = results_to_json(r);
  const auto j = nlohmann::json::parse(json);
  const auto& t = j["targets"][0];
  ASSERT_TRUE(t.contains("daylight_factor"));
  EXPECT_EQ(t["daylight_factor"]["sky"], "sky");
  EXPECT_DOUBLE_EQ(t["daylight_factor"]["outside_illuminance_lx"].get<double>(), 10000.0);
  EXPECT_EQ(t["daylight_factor"]["cells"].size(), 4u);
  EXPECT_EQ(t["requirements"]["en17037"], "minimum");
  EXPECT_DOUBLE_EQ(t["requirements"]["df_target_percent"].get<double>(), 300.0 / 159.0);
  EXPECT_EQ(t["requirements"]["source"], "EN 17037:2018, daylight factor method, minimum");
  ASSERT_TRUE(t["verdicts"].contains("df_target"));
  ASSERT_TRUE(t["verdicts"].contains("df_minimum"));
  // Read back and written again: the same text.
  EXPECT_EQ(results_to_json(results_from_json(json, "r.json")), json);
  // Factor 1: bit for bit the traced targets.
  EXPECT_EQ(nlohmann::json::parse(rescale_results_json(json, {}))["targets"], j["targets"]);
  // The sky dimmed (E_in and E_out alike) and the lamp brightened: lux move, D does not.
  const auto dimmed =
      nlohmann::json::parse(rescale_results_json(json, {{"sky", 0.5}, {"lamp", 2}}));
  const auto& u = dimmed["targets"][0];
  EXPECT_EQ(u["daylight_factor"], t["daylight_factor"]);
  EXPECT_EQ(u["verdicts"]["df_target"], t["verdicts"]["df_target"]);
  EXPECT_NE(u["mean_lux"], t["mean_lux"]);
  // The sky off: still the sky's daylight factor (a property of the room and the sky's
  // distribution, not of its level).
  const auto off = nlohmann::json::parse(rescale_results_json(json, {{"sky", 0.0}}));
  EXPECT_EQ(off["targets"][0]["daylight_factor"], t["daylight_factor"]);
}

}  // namespace
}  // namespace lightsolver::test
