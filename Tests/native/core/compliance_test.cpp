// Verdicts on hand-made intervals (every outcome of every requirement kind, both sides of the
// bound, equality at it), the grid intervals' arithmetic, and requirements in scene files.
#include "lightsolver/compliance.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "estimate/decide.hpp"
#include "lightsolver/scene_io.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver {
namespace {

TEST(Judge, PassFailUndecidedAndTheBoundItself) {
  EXPECT_EQ(judge(510, 530, 500), VerdictKind::Pass);       // wholly above
  EXPECT_EQ(judge(470, 490, 500), VerdictKind::Fail);       // wholly below
  EXPECT_EQ(judge(490, 510, 500), VerdictKind::Undecided);  // straddles
  // Equality: the allowed set of ">= 500" is [500, inf) with its end, so [500, 510] lies in
  // it (pass), and [490, 500] touches it at 500 (not wholly outside: undecided).
  EXPECT_EQ(judge(500, 510, 500), VerdictKind::Pass);
  EXPECT_EQ(judge(490, 500, 500), VerdictKind::Undecided);
  EXPECT_EQ(judge(500, 500, 500), VerdictKind::Pass);  // a point interval on the bound
  EXPECT_EQ(judge(0, 0, 1e-300), VerdictKind::Fail);
}

TEST(Judge, OverallIsFailThenUndecidedThenPass) {
  using V = VerdictKind;
  EXPECT_EQ(overall({}), V::Pass);
  EXPECT_EQ(overall({V::Pass, V::Pass}), V::Pass);
  EXPECT_EQ(overall({V::Pass, V::Undecided}), V::Undecided);
  EXPECT_EQ(overall({V::Undecided, V::Fail, V::Pass}), V::Fail);
}

// A grid result whose four statistics all have the interval [low, high] around `value`, in
// the units of the kind under test (lux or a ratio).
TargetResult grid_result(const std::string& kind, double value, double low, double high) {
  TargetResult t;
  t.name = "g";
  t.is_grid = true;
  t.estimate = {1.0, 0.0, 1.0, 1.0, 1, false};
  t.min_lux = t.max_lux = t.uniformity = 1.0;
  t.intervals = GridIntervals{1, 1, 1, 1, 1, 1, 1, 1, 1};
  GridIntervals& g = *t.intervals;
  if (kind == "em") t.estimate = {value, 0.0, low, high, 1, false};
  if (kind == "u0") std::tie(t.uniformity, g.u0_low, g.u0_high) = std::tuple{value, low, high};
  if (kind == "emin") std::tie(t.min_lux, g.min_low, g.min_high) = std::tuple{value, low, high};
  if (kind == "ud") std::tie(g.ud, g.ud_low, g.ud_high) = std::tuple{value, low, high};
  return t;
}

void require(Requirements& q, const std::string& kind, double r) {
  if (kind == "em") q.em_lux = r;
  if (kind == "u0") q.u0 = r;
  if (kind == "emin") q.emin_lux = r;
  if (kind == "ud") q.ud = r;
}

struct Case {
  double value, low, high, required;
  VerdictKind expected;
  bool to_decide_known;  // undecided: an estimate exists (value off the bound)
};

TEST(Verdicts, EveryOutcomeOfEveryRequirementKindBothSidesAndAtTheBound) {
  using V = VerdictKind;
  const Case cases[] = {
      {0.55, 0.52, 0.58, 0.50, V::Pass, false},       // above
      {0.45, 0.42, 0.48, 0.50, V::Fail, false},       // below
      {0.52, 0.47, 0.57, 0.50, V::Undecided, true},   // straddles, value above the bound
      {0.48, 0.43, 0.53, 0.50, V::Undecided, true},   // straddles, value below the bound
      {0.52, 0.50, 0.54, 0.50, V::Pass, false},       // low end exactly on the bound
      {0.48, 0.46, 0.50, 0.50, V::Undecided, true},   // high end exactly on the bound
      {0.50, 0.47, 0.53, 0.50, V::Undecided, false},  // value on the bound: no estimate
  };
  for (const char* kind : {"em", "u0", "emin", "ud"}) {
    for (const Case& c : cases) {
      Results r;
      r.photons = 10'000;
      r.targets.push_back(grid_result(kind, c.value, c.low, c.high));
      require(r.targets[0].requirements, kind, c.required);
      detail::add_verdicts(r);
      detail::add_to_decide(r, 1e6);
      const TargetResult& t = r.targets[0];
      ASSERT_EQ(t.verdicts.size(), 1u) << kind;
      const Verdict& v = t.verdicts[0];
      SCOPED_TRACE(std::string(kind) + " [" + std::to_string(c.low) + ", " +
                   std::to_string(c.high) + "] >= " + std::to_string(c.required));
      EXPECT_EQ(v.name, kind);
      EXPECT_EQ(v.verdict, c.expected);
      EXPECT_EQ(t.verdict, c.expected);
      EXPECT_EQ(r.verdict, c.expected);
      EXPECT_EQ(v.value, c.value);
      EXPECT_EQ(v.ci_low, c.low);
      EXPECT_EQ(v.ci_high, c.high);
      EXPECT_EQ(v.required, c.required);
      EXPECT_EQ(v.photons_to_decide.has_value(), c.to_decide_known);
      EXPECT_EQ(v.seconds_to_decide.has_value(), c.to_decide_known);
      if (c.to_decide_known) {
        // Half-width on the side facing the bound over the distance to it, squared.
        const double w = c.value >= c.required ? c.value - c.low : c.high - c.value;
        const double ratio = w / std::abs(c.value - c.required);
        EXPECT_NEAR(*v.photons_to_decide, 10'000 * ratio * ratio, 1e-6);
        EXPECT_NEAR(*v.seconds_to_decide, *v.photons_to_decide / 1e6, 1e-12);
      }
    }
  }
}

TEST(Verdicts, OverallOfTargetsAndOnlyTheRequiredOnes) {
  Results r;
  r.targets.push_back(grid_result("em", 600, 590, 610));
  r.targets[0].requirements.em_lux = 500;  // pass
  r.targets.push_back(grid_result("u0", 0.5, 0.45, 0.55));
  r.targets[1].requirements.u0 = 0.6;                     // fail
  r.targets[1].requirements.ud = 0.4;                     // ud is 1 in grid_result: pass
  r.targets.push_back(grid_result("em", 600, 590, 610));  // no requirements: not judged
  detail::add_verdicts(r);
  EXPECT_EQ(r.targets[0].verdict, VerdictKind::Pass);
  ASSERT_EQ(r.targets[1].verdicts.size(), 2u);
  EXPECT_EQ(r.targets[1].verdicts[0].name, "u0");
  EXPECT_EQ(r.targets[1].verdicts[1].name, "ud");
  EXPECT_EQ(r.targets[1].verdict, VerdictKind::Fail);
  EXPECT_TRUE(r.targets[2].verdicts.empty());
  EXPECT_EQ(r.verdict, VerdictKind::Fail);
}

// Cells with fixed mean and sigma (normal intervals): the bounds are z(alpha / m) sigma away.
GridSampler fixed_cells(std::vector<double> means, double sigma, double grid_mean,
                        double grid_sigma) {
  GridSampler s;
  s.cells = static_cast<std::uint32_t>(means.size());
  s.cell = [means, sigma](std::uint32_t c, double alpha) {
    const double z = z_for_alpha(alpha);
    return Estimate{means[c], sigma, means[c] - z * sigma, means[c] + z * sigma, 100, false};
  };
  s.grid = [grid_mean, grid_sigma](double alpha) {
    const double z = z_for_alpha(alpha);
    return Estimate{grid_mean, grid_sigma, grid_mean - z * grid_sigma, grid_mean + z * grid_sigma,
                    100,       false};
  };
  return s;
}

TEST(GridIntervals, OneCellForTheNearEndsBonferroniForTheFarEndsAlphaSplitForRatios) {
  const std::vector<double> means{100, 120, 140, 160};
  const GridIntervals g = grid_intervals(fixed_cells(means, 5, 130, 2), 0.95, 100, 160, 130);
  // Two-sided levels (each end one-sided half of it): 0.05 for one cell's end, 0.05 / 4 for
  // the union over 4 cells; the ratios use half of those, and Em at two-sided 0.025.
  const double z1 = z_for_alpha(0.05), zm = z_for_alpha(0.05 / 4), zq1 = z_for_alpha(0.025),
               zqm = z_for_alpha(0.025 / 4), zem = z_for_alpha(0.025);
  EXPECT_NEAR(z1, 1.95996, 1e-5);
  EXPECT_NEAR(zm, 2.49771, 1e-5);
  EXPECT_DOUBLE_EQ(g.min_low, 100 - z1 * 5);  // the darkest cell's own interval
  EXPECT_DOUBLE_EQ(g.min_high, 100 + zm * 5);
  EXPECT_DOUBLE_EQ(g.max_low, 160 - zm * 5);
  EXPECT_DOUBLE_EQ(g.max_high, 160 + z1 * 5);
  EXPECT_DOUBLE_EQ(g.ud, 100.0 / 160.0);
  EXPECT_DOUBLE_EQ(g.ud_low, (100 - zq1 * 5) / (160 + zq1 * 5));
  EXPECT_DOUBLE_EQ(g.ud_high, (100 + zqm * 5) / (160 - zqm * 5));
  EXPECT_DOUBLE_EQ(g.u0_low, (100 - zq1 * 5) / (130 + zem * 2));
  EXPECT_DOUBLE_EQ(g.u0_high, (100 + zqm * 5) / (130 - zem * 2));
}

TEST(GridIntervals, RatiosStayInZeroOneAndHoldTheirEstimates) {
  // Nearly equal cells: the upper ratio bounds would pass 1, which no true U0 or Ud can.
  GridIntervals g = grid_intervals(fixed_cells({100, 101}, 10, 100.5, 5), 0.95, 100, 101, 100.5);
  EXPECT_EQ(g.u0_high, 1.0);
  EXPECT_EQ(g.ud_high, 1.0);
  EXPECT_LE(g.u0_low, 100 / 100.5);
  // Every cell at zero (no light yet): Ud and U0 are 0 with the uninformative [0, 1].
  g = grid_intervals(fixed_cells({0, 0}, 0, 0, 0), 0.95, 0, 0, 0);
  EXPECT_EQ(g.ud, 0.0);
  EXPECT_EQ(g.ud_low, 0.0);
  EXPECT_EQ(g.ud_high, 1.0);
  EXPECT_EQ(g.u0_low, 0.0);
  EXPECT_EQ(g.u0_high, 1.0);
}

// --- requirements in scene files ---------------------------------------------------------

std::string scene_text(const std::string& target_extra, const std::string& settings = "{}",
                       const std::string& luminaire_extra = "") {
  return R"({"format": "lightsolver.scene/1", "materials": {"m": {"type": "diffuse"}},
   "meshes": [{"name": "desk", "material": "m", "vertices": [[0,0,1],[1,0,1],[0,1,1]],
               "triangles": [[0,1,2]]}],
   "luminaires": [{"name": "p", "type": "point", "position": [0,0,3], "flux_lm": 1000)" +
         luminaire_extra + R"(}],
   "targets": [{"name": "g", "type": "grid", "corner": [0,0,0], "edge1": [2,0,0],
                "edge2": [0,2,0], "cells": [2,2])" +
         target_extra + R"(}], "settings": )" + settings + "}";
}

std::string error_of(const std::string& text) {
  try {
    scene_from_json(text, "s.json", ".");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneRequirements, ReadsAnySubsetAndTaskRowsWithOverrides) {
  Scene s = scene_from_json(scene_text(R"(, "requirements": {"em_lux": 300, "ud": 0.25})"),
                            "s.json", ".");
  const Requirements& q = s.targets[0].requirements;
  EXPECT_EQ(q.em_lux, 300.0);
  EXPECT_EQ(q.ud, 0.25);
  EXPECT_FALSE(q.u0 || q.emin_lux);
  EXPECT_TRUE(q.task.empty());

  // The shipped table (found through the compiled-in source path): office writing 500 / 0.60.
  s = scene_from_json(scene_text(R"(, "task": "office-writing")"), "s.json", ".");
  EXPECT_EQ(s.targets[0].requirements.em_lux, 500.0);
  EXPECT_EQ(s.targets[0].requirements.u0, 0.6);
  EXPECT_EQ(s.targets[0].requirements.task, "office-writing");
  EXPECT_NE(s.targets[0].requirements.source.find("EN 12464-1:2021"), std::string::npos);
  // The scene's own values replace the row's.
  s = scene_from_json(scene_text(R"(, "task": "office-writing", "requirements": {"u0": 0.7})"),
                      "s.json", ".");
  EXPECT_EQ(s.targets[0].requirements.em_lux, 500.0);
  EXPECT_EQ(s.targets[0].requirements.u0, 0.7);
}

TEST(SceneRequirements, UnknownTaskListsTheClosestIds) {
  const std::string e = error_of(scene_text(R"(, "task": "office-writting")"));
  EXPECT_NE(e.find("targets[0].task"), std::string::npos) << e;
  EXPECT_NE(e.find("unknown task \"office-writting\""), std::string::npos) << e;
  EXPECT_NE(e.find("closest: office-writing"), std::string::npos) << e;
}

TEST(SceneRequirements, TheEnvironmentNamesAnotherTable) {
  const auto dir = std::filesystem::temp_directory_path() / "lightsolver_requirements_test";
  std::filesystem::create_directories(dir);
  const auto file = dir / "mine.json";
  std::ofstream(file) << R"({"source": "house rules", "tasks": [{"id": "lab", "em_lux": 1000}]})";
  setenv("LIGHTSOLVER_REQUIREMENTS", file.c_str(), 1);
  const Scene s = scene_from_json(scene_text(R"(, "task": "lab")"), "s.json", ".");
  unsetenv("LIGHTSOLVER_REQUIREMENTS");
  EXPECT_EQ(s.targets[0].requirements.em_lux, 1000.0);
  EXPECT_FALSE(s.targets[0].requirements.u0);
  EXPECT_EQ(s.targets[0].requirements.source, "house rules: lab");
  std::filesystem::remove_all(dir);
}

TEST(SceneRequirements, RangesAndKeysAreCheckedWithFieldNames) {
  const std::pair<const char*, const char*> bad[] = {
      {R"(, "requirements": {"em_lux": 0})", "targets[0].requirements.em_lux: must be > 0"},
      {R"(, "requirements": {"emin_lux": 2e7})", "targets[0].requirements.emin_lux: must be > 0"},
      {R"(, "requirements": {"u0": 1.5})", "targets[0].requirements.u0: must lie in (0, 1]"},
      {R"(, "requirements": {"ud": -0.1})", "targets[0].requirements.ud: must lie in (0, 1]"},
      {R"(, "requirements": {"em": 500})", "targets[0].requirements.em: unknown key"},
      {R"(, "requirements": {"u0": "0.6"})", "targets[0].requirements.u0: expected a number"},
      {R"(, "task": 5)", "targets[0].task: expected a string"},
  };
  for (const auto& [extra, message] : bad) {
    EXPECT_NE(error_of(scene_text(extra)).find(message), std::string::npos)
        << extra << " -> " << error_of(scene_text(extra));
  }
}

TEST(SceneRequirements, SurfaceTargetsTakeEmOnly) {
  auto surface = [](const std::string& extra) {
    std::string text = scene_text("");
    const std::string grid = text.substr(text.find("{\"name\": \"g\""));
    text.replace(text.find("{\"name\": \"g\""), grid.find('}') + 1,
                 R"({"name": "d", "type": "surface", "mesh": "desk")" + extra + "}");
    return text;
  };
  EXPECT_EQ(scene_from_json(surface(R"(, "requirements": {"em_lux": 200})"), "s.json", ".")
                .targets[0]
                .requirements.em_lux,
            200.0);
  const std::string e = error_of(surface(R"(, "requirements": {"u0": 0.6})"));
  EXPECT_NE(e.find("targets[0].requirements.u0: a surface target has no cells"), std::string::npos)
      << e;
  // A task's U0 applies to grids: on a surface only its Em is taken.
  const Scene s = scene_from_json(surface(R"(, "task": "office-writing")"), "s.json", ".");
  EXPECT_EQ(s.targets[0].requirements.em_lux, 500.0);
  EXPECT_FALSE(s.targets[0].requirements.u0);
}

TEST(SceneRequirements, PowerOnEveryLuminaireTypeAndDecideSetting) {
  Scene s =
      scene_from_json(scene_text("", R"({"decide": true})", R"(, "power_w": 36.5)"), "s.json", ".");
  EXPECT_EQ(s.luminaires[0].power_w, 36.5);
  EXPECT_TRUE(s.settings.decide);
  EXPECT_FALSE(scene_from_json(scene_text(""), "s.json", ".").luminaires[0].power_w);
  EXPECT_NE(error_of(scene_text("", "{}", R"(, "power_w": -1)"))
                .find("luminaires[0].power_w: must be a finite value in 0..10^9 W"),
            std::string::npos);
  EXPECT_NE(error_of(scene_text("", "{}", R"(, "power_w": "9")"))
                .find("luminaires[0].power_w: expected a number"),
            std::string::npos);
  // Other keys are still the type's own: a typo is named.
  EXPECT_NE(error_of(scene_text("", "{}", R"(, "power_w": 9, "flux": 1)"))
                .find("luminaires[0].flux: unknown key"),
            std::string::npos);
}

TEST(SceneRequirements, DecideNeedsRequirementsAndNoAccuracyGoal) {
  Scene s = scene_from_json(scene_text(""), "s.json", ".");
  SolveOptions o;
  o.photons = 1000;
  o.decide = true;
  EXPECT_THROW(solve(s, o), InputError);
  s.targets[0].requirements.em_lux = 10;
  o.target_accuracy = 0.1;
  EXPECT_THROW(solve(s, o), InputError);
  o.target_accuracy.reset();
  EXPECT_NO_THROW(solve(s, o));
}

}  // namespace
}  // namespace lightsolver
