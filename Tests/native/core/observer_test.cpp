// Observer targets (docs/glare.md, "UGR in a traced scene"): the traced background luminance
// against a closed form, the UGR interval against compute_ugr at its ends, the ugr_max
// verdict, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "lightsolver/glare.hpp"
#include "lightsolver/scene_io.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

const std::string kData = LIGHTSOLVER_TEST_DATA;
Target observer(const std::string& name, dvec3 eye, dvec3 view, std::optional<double> ugr_max) {
  Target t;
  t.name = name;
  t.type = Target::Type::Observer;
  t.position = eye;
  t.view_direction = view;
  t.requirements.ugr_max = ugr_max;
  return t;
}

class Observer : public ::testing::TestWithParam<std::string> {};

TEST_P(Observer, BackgroundLuminanceOfAGlowingCubeMatchesTheClosedForm) {
  const double rho = 0.75;
  Scene s = glowing_cube(rho);
  s.targets.push_back(observer("eye +y", {0.4, 0.5, 0.5}, {0, 1, 0}, std::nullopt));
  s.targets.push_back(observer("eye diagonal", {0.6, 0.3, 0.6}, {1, 1, 0.2}, std::nullopt));
  const Results r = run_on_backend(GetParam(), s, 600'000, 7);
  const double e_ind = kFluxPerWall_lm * rho / (1.0 - rho);  // Phi/A = 1000 lx, A = 6 m2
  for (const TargetResult& t : r.targets) {
    ASSERT_TRUE(t.is_observer && t.glare);
    expect_in_ci(t.estimate, e_ind, 0.15, t.name);
    const ObserverGlare& g = *t.glare;
    EXPECT_DOUBLE_EQ(g.background_luminance_cd_m2, t.estimate.mean / std::numbers::pi);
    EXPECT_LE(g.background_ci_low_cd_m2, e_ind / std::numbers::pi) << t.name;
    EXPECT_GE(g.background_ci_high_cd_m2, e_ind / std::numbers::pi) << t.name;
  }
}

TEST_P(Observer, CountsOnlyReflectedLight) {
  Scene s = glowing_cube(0.0);  // black walls: everything reaching the eye is direct
  s.targets.push_back(observer("eye", {0.4, 0.5, 0.5}, {0, 1, 0}, 19.0));
  s.targets.push_back(grid("same square", {0.35, 0.5, 0.45}, {0, 0, 0.1}, {0.1, 0, 0}, 1, 1));
  const Results r = run_on_backend(GetParam(), s, 200'000, 3);
  EXPECT_EQ(r.targets[0].estimate.hits, 0u);
  EXPECT_EQ(r.targets[0].estimate.mean, 0.0);
  EXPECT_GT(r.targets[1].estimate.hits, 100u);  // a grid there does see the direct light
  const ObserverGlare& g = *r.targets[0].glare;
  EXPECT_FALSE(g.ugr.has_value());  // L_b = 0: unbounded, never inf
  EXPECT_FALSE(g.ugr_ci_high.has_value());
  ASSERT_EQ(r.targets[0].verdicts.size(), 1u);
  EXPECT_NE(r.targets[0].verdicts[0].verdict, VerdictKind::Pass);  // UGR unbounded above
  const nlohmann::json j = nlohmann::json::parse(results_to_json(r));
  EXPECT_TRUE(j["targets"][0]["ugr"].is_null());
  EXPECT_TRUE(j["targets"][0]["verdicts"]["ugr"]["value"].is_null());
}

TEST_P(Observer, UgrIntervalIsComputeUgrAtTheEndsOfTheBackgroundInterval) {
  const double rho = 0.75;
  Scene s = glowing_cube(rho);
  s.luminaires.push_back(point_light({0.5, 0.9, 0.8}, 10.0));  // no area: excluded
  const dvec3 eye{0.4, 0.5, 0.5}, view{0, 1, 0};
  s.targets.push_back(observer("lenient", eye, view, 40.0));
  s.targets.push_back(observer("strict", eye, view, 1.0));
  s.targets.push_back(observer("borderline", eye, view, std::nullopt));
  Results r = run_on_backend(GetParam(), s, 300'000, 11, 0.95);
  // The same sources built independently: only the wall ahead (y = 1) is in the field.
  std::vector<GlareSource> sources;
  for (const Luminaire& l : s.luminaires) {
    if (l.type != Luminaire::Type::Area) continue;
    const dvec3 n = glm::cross(l.edge1, l.edge2);
    sources.push_back(lambertian_glare_source(l.name, l.corner + 0.5 * (l.edge1 + l.edge2), n,
                                              glm::length(n), l.flux_lm));
  }
  const GlareObserver o{eye, view, {0, 0, 1}};
  const ObserverGlare& g = *r.targets[0].glare;
  ASSERT_TRUE(g.ugr && g.ugr_ci_low && g.ugr_ci_high);
  EXPECT_DOUBLE_EQ(*g.ugr, *compute_ugr(o, sources, g.background_luminance_cd_m2).ugr);
  EXPECT_DOUBLE_EQ(*g.ugr_ci_low, *compute_ugr(o, sources, g.background_ci_high_cd_m2).ugr);
  EXPECT_DOUBLE_EQ(*g.ugr_ci_high, *compute_ugr(o, sources, g.background_ci_low_cd_m2).ugr);
  EXPECT_LE(*g.ugr_ci_low, *g.ugr);
  EXPECT_GE(*g.ugr_ci_high, *g.ugr);
  const double exact = *compute_ugr(o, sources, 3000.0 / std::numbers::pi).ugr;
  EXPECT_LE(*g.ugr_ci_low, exact);
  EXPECT_GE(*g.ugr_ci_high, exact);
  // Contributions in scene order; the point light is named as excluded, with a warning.
  ASSERT_EQ(g.contributions.size(), 7u);
  EXPECT_TRUE(g.contributions[5].counted) << g.contributions[5].why_not;  // the wall ahead
  EXPECT_FALSE(g.contributions[6].counted);
  EXPECT_NE(g.contributions[6].why_not.find("no luminous area"), std::string::npos);
  bool warned = false;
  for (const auto& w : g.warnings) warned = warned || w.find("\"point") != std::string::npos;
  EXPECT_TRUE(warned);
  // Verdicts: pass at 40, fail at 1 (UGR is about 16 here).
  EXPECT_EQ(r.targets[0].verdicts.at(0).verdict, VerdictKind::Pass);
  EXPECT_EQ(r.targets[1].verdicts.at(0).verdict, VerdictKind::Fail);
  EXPECT_EQ(r.targets[0].verdicts[0].name, "ugr");
  EXPECT_STREQ(r.targets[0].verdicts[0].relation, "<=");
  EXPECT_EQ(r.verdict, VerdictKind::Fail);
  const nlohmann::json j = nlohmann::json::parse(results_to_json(r));
  const nlohmann::json& v = j["targets"][1]["verdicts"]["ugr"];
  EXPECT_EQ(v["relation"], "<=");
  EXPECT_EQ(v["verdict"], "fail");
  EXPECT_DOUBLE_EQ(v["ci_high"].get<double>(), *g.ugr_ci_high);
  EXPECT_EQ(j["targets"][0]["type"], "observer");
  EXPECT_EQ(j["targets"][0]["luminaires"].size(), 7u);
  // At a limit inside the interval the verdict is undecided, with an estimate of the cost.
  s.targets[2].requirements.ugr_max = *g.ugr;
  r = run_on_backend(GetParam(), s, 300'000, 11, 0.95);
  const Verdict& u = r.targets[2].verdicts.at(0);
  EXPECT_EQ(u.verdict, VerdictKind::Undecided);
  EXPECT_EQ(u.verdict, judge_at_most(u.ci_low, u.ci_high, u.required));
}

INSTANTIATE_TEST_SUITE_P(Backends, Observer, ::testing::ValuesIn(backends()));

// --- scene file ------------------------------------------------------------------------------

// A one-floor scene file with `target` (JSON) as its second target, and the InputError it
// gives ("<no error>" when it loads): scene_builders.hpp.
std::string scene_with(const std::string& target) { return scene_file_with_target(target); }
std::string error_of(const std::string& target) { return target_error(target, kData); }

TEST(ObserverScene, ReadsAnObserverWithDefaultsAndATaskRow) {
  const Scene s = scene_from_json(
      scene_with(R"({"name": "desk", "type": "observer", "position": [0.5, 0.2, 1.2],
                     "view_direction": [0, 2, 0], "task": "office-writing"})"),
      "scene.json", kData);
  const Target& t = s.targets[1];
  EXPECT_EQ(t.type, Target::Type::Observer);
  EXPECT_EQ(t.view_direction, dvec3(0, 1, 0));  // normalised
  EXPECT_EQ(t.up, dvec3(0, 0, 1));
  ASSERT_TRUE(t.requirements.ugr_max);
  EXPECT_EQ(*t.requirements.ugr_max, 19.0);                  // the row's UGR_L
  EXPECT_FALSE(t.requirements.em_lux || t.requirements.u0);  // illuminance is for grids
  const Scene g = scene_from_json(
      scene_with(R"({"name": "g", "type": "grid", "corner": [0,0,0.8], "edge1": [1,0,0],
                     "edge2": [0,1,0], "cells": [2,2], "task": "office-writing"})"),
      "scene.json", kData);
  EXPECT_FALSE(g.targets[1].requirements.ugr_max);  // a grid does not take the row's UGR
  EXPECT_TRUE(g.targets[1].requirements.em_lux);
}

TEST(ObserverScene, BadInputNamesTheField) {
  const std::string base = R"({"name": "o", "type": "observer", "position": [0.5, 0.2, 1.2])";
  struct Case {
    std::string target, expected;
  };
  const Case cases[] = {
      {base + "}", "targets[1]: missing required key \"view_direction\""},
      {base + R"(, "view_direction": [0, 0, 0]})",
       "targets[1].view_direction: must not be the zero"},
      {base + R"(, "view_direction": [0, 0, 1]})", "targets[1].up: is parallel"},
      {base + R"(, "view_direction": [0, 1, 0], "requirements": {"ugr_max": 0}})",
       "targets[1].requirements.ugr_max: must be > 0"},
      {base + R"(, "view_direction": [0, 1, 0], "requirements": {"ugr_max": 41}})",
       "targets[1].requirements.ugr_max: must be > 0 and at most 40"},
      {base + R"(, "view_direction": [0, 1, 0], "requirements": {"em_lux": 500}})",
       "targets[1].requirements.em_lux: an observer target has only ugr_max"},
      {base + R"(, "view_direction": [0, 1, 0], "cells": [1, 1]})",
       "targets[1].cells: unknown key"},
      {R"({"name": "g", "type": "grid", "corner": [0,0,0.8], "edge1": [1,0,0], "edge2": [0,1,0],
           "cells": [2,2], "requirements": {"ugr_max": 19}})",
       "targets[1].requirements.ugr_max: UGR is judged at an observer"},
  };
  for (const Case& c : cases) {
    const std::string e = error_of(c.target);
    EXPECT_NE(e.find(c.expected), std::string::npos) << c.target << "\n-> " << e;
  }
}

}  // namespace
}  // namespace lightsolver::test
