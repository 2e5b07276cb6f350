// Rescaling observer grids (docs/glare.md, "Rescaling an observer grid"): a factor of 1 gives
// the traced results bit for bit, other factors the results of a run traced at the dimmed
// fluxes with the same photons, a group at 0 leaves the other's glare, and results whose
// per-point data are missing or short are refused naming the field.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "lightsolver/rescale.hpp"
#include "lightsolver/simulation.hpp"
#include "lightsolver/solver.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

// A 0.6 m square panel facing down at z = 2.9 m, centred on (x, y).
Luminaire panel(const std::string& name, const std::string& group, double x, double y,
                double flux_lm) {
  Luminaire l;
  l.name = name;
  l.group = group;
  l.type = Luminaire::Type::Area;
  l.corner = {x - 0.3, y - 0.3, 2.9};
  l.edge1 = {0, 0.6, 0};
  l.edge2 = {0.6, 0, 0};  // edge1 x edge2 points down
  l.flux_lm = flux_lm;
  return l;
}

// A grey 6 x 4 x 3 m room, two panels in "left" and one panel and a point lamp (not rated for
// glare) in "right", and seated eyes at two places looking four ways (8 points).
Scene glare_room() {
  Scene s;
  add_material(s, "grey", Material::Type::Diffuse, 0.5);
  s.meshes.push_back(room_mesh("room", 0, dvec3(0), dvec3(6, 4, 3), 2));
  s.luminaires.push_back(panel("l1", "left", 1.5, 1.0, 3000));
  s.luminaires.push_back(panel("l2", "left", 1.5, 3.0, 3000));
  s.luminaires.push_back(panel("r1", "right", 4.5, 2.0, 4000));
  Luminaire lamp = point_light({3.0, 2.0, 2.5}, 1000);
  lamp.name = "r2";
  lamp.group = "right";
  s.luminaires.push_back(lamp);
  Target t;
  t.name = "eyes";
  t.type = Target::Type::ObserverGrid;
  t.positions = {{0.5, 2.0, 1.2}, {3.0, 0.6, 1.2}};
  t.view_step_deg = 90.0;
  t.requirements.ugr_max = 19.0;
  s.targets.push_back(t);
  s.targets.push_back(grid("desk", {0.5, 0.5, 0.75}, {5, 0, 0}, {0, 3, 0}, 2, 2));
  return s;
}

// A run with contributions whose photon shares do not follow the fluxes: dimming a group
// leaves every group's photons, and so every tally, as they were.
Results traced(const Scene& s) {
  Simulation sim(s, {.backend = "embree", .threads = 2});
  sim.fix_photon_shares({1.0, 1.0});
  SolveOptions o;
  o.photons = 200'000;
  o.seed = 11;
  o.contributions = true;
  return sim.run(o);
}

Scene dimmed(Scene s, double left, double right) {
  for (Luminaire& l : s.luminaires) l.flux_lm *= l.group == "left" ? left : right;
  return s;
}

nlohmann::json targets(const std::string& results_json) {
  return nlohmann::json::parse(results_json)["targets"];
}

TEST(ObserverGridRescale, FactorOneGivesTheTracedResultsBitForBit) {
  const Results r = traced(glare_room());
  const TargetResult& g = r.targets.at(0);
  ASSERT_TRUE(g.glare && g.glare->ugr && g.observer_grid);
  ASSERT_EQ(g.contributions.size(), 2u);
  EXPECT_EQ(g.contributions[0].tallies.size(), 8u);  // one per point
  const std::string json = results_to_json(r);
  const auto doc = nlohmann::json::parse(json);
  ASSERT_TRUE(doc["targets"][0]["observer_grid"].contains("glare_terms"));
  EXPECT_EQ(doc["targets"][0]["observer_grid"]["glare_terms"]["not_rated"].size(), 1u);  // r2
  EXPECT_EQ(targets(rescale_results_json(json, {})), doc["targets"]);
  const auto ones =
      nlohmann::json::parse(rescale_results_json(json, {{"left", 1.0}, {"right", 1.0}}));
  EXPECT_EQ(ones["targets"], doc["targets"]);
  EXPECT_EQ(ones["verdict"], doc["verdict"]);
  // Without contributions the grid carries no terms (the results keep their layout).
  Simulation plain(glare_room(), {.backend = "embree", .threads = 2});
  SolveOptions o;
  o.photons = 20'000;
  const auto without = nlohmann::json::parse(results_to_json(plain.run(o)));
  EXPECT_FALSE(without["targets"][0]["observer_grid"].contains("glare_terms"));
}

// The rescaled grid against the grid traced at the dimmed fluxes with the same photons: every
// estimate to 1e-12 relative, every UGR to 1e-9, the same maximum, warnings and verdict.
void expect_rescaled_is_traced(const std::string& json, double left, double right) {
  const Results a = rescale_results(json, {{"left", left}, {"right", right}});
  const Results b = traced(dimmed(glare_room(), left, right));
  const std::string at = " at " + std::to_string(left) + ", " + std::to_string(right);
  for (std::size_t t = 0; t < b.targets.size(); ++t) {
    const TargetResult &x = a.targets[t], &y = b.targets[t];
    EXPECT_NEAR(x.estimate.mean, y.estimate.mean, 1e-12 * y.estimate.mean) << y.name << at;
    EXPECT_NEAR(x.estimate.ci_high, y.estimate.ci_high, 1e-12 * y.estimate.ci_high) << at;
  }
  const TargetResult &x = a.targets[0], &y = b.targets[0];
  ASSERT_TRUE(x.glare && y.glare && x.glare->ugr && y.glare->ugr);
  EXPECT_NEAR(*x.glare->ugr, *y.glare->ugr, 1e-9) << at;
  EXPECT_NEAR(*x.glare->ugr_ci_low, *y.glare->ugr_ci_low, 1e-9) << at;
  EXPECT_NEAR(*x.glare->ugr_ci_high, *y.glare->ugr_ci_high, 1e-9) << at;
  EXPECT_EQ(x.observer_grid->max_at, y.observer_grid->max_at) << at;
  ASSERT_EQ(x.observer_grid->points.size(), y.observer_grid->points.size());
  for (std::size_t k = 0; k < y.observer_grid->points.size(); ++k) {
    const ObserverGlare &p = x.observer_grid->points[k], &q = y.observer_grid->points[k];
    EXPECT_NEAR(p.background_luminance_cd_m2, q.background_luminance_cd_m2,
                1e-12 * q.background_luminance_cd_m2)
        << "point " << k << at;
    EXPECT_NEAR(p.luminaire_sum, q.luminaire_sum, 1e-12 * q.luminaire_sum) << "point " << k << at;
    ASSERT_EQ(p.ugr.has_value(), q.ugr.has_value());
    if (q.ugr) EXPECT_NEAR(*p.ugr, *q.ugr, 1e-9) << "point " << k << at;
  }
  EXPECT_EQ(x.glare->warnings, y.glare->warnings) << at;
  ASSERT_EQ(x.verdicts.size(), 1u);
  EXPECT_EQ(x.verdicts[0].verdict, y.verdicts[0].verdict) << at;
}

// Fixed photon shares keep every tally when a group is dimmed, so only rounding can part the
// two (powers of two scale exactly: measured bit for bit; 0.3 and 0.7 round).
TEST(ObserverGridRescale, DimmedEqualsARunTracedAtTheDimmedFluxes) {
  const std::string json = results_to_json(traced(glare_room()));
  expect_rescaled_is_traced(json, 0.5, 4.0);
  expect_rescaled_is_traced(json, 0.3, 0.7);
  // A rescaled result rescales again (it carries the dimmed terms): in two steps as in one.
  const std::string once = rescale_results_json(json, {{"left", 0.5}, {"right", 4.0}});
  const std::string half = rescale_results_json(json, {{"left", 0.5}});
  EXPECT_EQ(targets(rescale_results_json(half, {{"right", 4.0}})), targets(once));
  // The factors moved the glare: not a test that passes by returning the trace.
  const Results same = rescale_results(json, {}), moved = rescale_results(once, {});
  EXPECT_GT(std::abs(*same.targets[0].glare->ugr - *moved.targets[0].glare->ugr), 0.5);
}

// "right" at 0: its panel is dark toward every eye and the grid is the grid traced with that
// group at 0 lm (the same photons: its tallies count, its flux is 0), point by point.
TEST(ObserverGridRescale, AGroupAtZeroIsTheGroupTracedDark) {
  const Results off = rescale_results(results_to_json(traced(glare_room())), {{"right", 0.0}});
  const Results dark = traced(dimmed(glare_room(), 1.0, 0.0));
  const TargetResult &g = off.targets.at(0), &h = dark.targets.at(0);
  ASSERT_TRUE(g.glare && g.observer_grid && h.glare && h.observer_grid);
  EXPECT_EQ(g.observer_grid->terms.status, h.observer_grid->terms.status);
  for (std::size_t k = 0; k < 8; ++k) {
    const std::string& status = g.observer_grid->terms.status[k];
    EXPECT_NE(status[2], 'c') << "point " << k;  // r1, dimmed to 0
    EXPECT_EQ(status[3], 'x');                   // r2, a point lamp: never rated
    const ObserverGlare &p = g.observer_grid->points[k], &q = h.observer_grid->points[k];
    EXPECT_EQ(p.background_luminance_cd_m2, q.background_luminance_cd_m2) << "point " << k;
    EXPECT_EQ(p.luminaire_sum, q.luminaire_sum) << "point " << k;
    EXPECT_EQ(p.ugr, q.ugr) << "point " << k;
  }
  EXPECT_EQ(g.glare->ugr_ci_low, h.glare->ugr_ci_low);
  EXPECT_EQ(g.glare->warnings, h.glare->warnings);
  ASSERT_EQ(g.glare->contributions.size(), 4u);
  EXPECT_FALSE(g.glare->contributions[2].counted);
  EXPECT_EQ(off.rescaled[1], (std::pair<std::string, double>{"right", 0.0}));
}

// A plain observer says the same of a group dimmed to 0 as a run traced with it at 0 lm: its
// panel is dark toward the eye (not counted with a luminance of 0), and the UGR agrees.
TEST(ObserverGridRescale, APlainObserverSeesAGroupAtZeroAsTracedDark) {
  Scene s = glare_room();
  Target eye;
  eye.name = "eye";
  eye.type = Target::Type::Observer;
  eye.position = {0.5, 2.0, 1.2};
  eye.view_direction = {1, 0, 0};
  s.targets.push_back(eye);
  const Results off = rescale_results(results_to_json(traced(s)), {{"right", 0.0}});
  const Results dark = traced(dimmed(s, 1.0, 0.0));
  const ObserverGlare &g = *off.targets.at(2).glare, &h = *dark.targets.at(2).glare;
  ASSERT_EQ(g.contributions.size(), h.contributions.size());
  for (std::size_t i = 0; i < g.contributions.size(); ++i) {
    EXPECT_EQ(g.contributions[i].counted, h.contributions[i].counted) << i;
    EXPECT_EQ(g.contributions[i].why_not, h.contributions[i].why_not) << i;
  }
  EXPECT_FALSE(g.contributions[2].counted);  // r1, dimmed to 0
  ASSERT_TRUE(g.ugr.has_value() && h.ugr.has_value());
  EXPECT_NEAR(*g.ugr, *h.ugr, 1e-9);
}

// Results whose grid lacks its per-point data, or has it short, are refused naming the field.
TEST(ObserverGridRescale, MissingOrShortPerPointDataNamesTheField) {
  const auto doc = nlohmann::json::parse(results_to_json(traced(glare_room())));
  auto message = [](const nlohmann::json& d) {
    return input_error_of([&] { rescale_results(d.dump(), {{"left", 0.5}}, "r.json"); });
  };
  auto without = [&](auto edit) {
    nlohmann::json d = doc;
    edit(d["targets"][0]);
    return message(d);
  };
  const std::string none = without([](auto& t) { t["observer_grid"].erase("glare_terms"); });
  EXPECT_NE(none.find("observer_grid"), std::string::npos) << none;
  EXPECT_NE(none.find("--contributions"), std::string::npos) << none;
  const std::string status =
      without([](auto& t) { t["observer_grid"]["glare_terms"]["status"].erase(7); });
  EXPECT_NE(status.find("glare_terms.status"), std::string::npos) << status;
  EXPECT_NE(status.find("one per point (8)"), std::string::npos) << status;
  const std::string chars =
      without([](auto& t) { t["observer_grid"]["glare_terms"]["status"][0] = "cc"; });
  EXPECT_NE(chars.find("status[0]"), std::string::npos) << chars;
  const std::string terms =
      without([](auto& t) { t["observer_grid"]["glare_terms"]["terms"][0].erase(0); });
  EXPECT_NE(terms.find("terms[0]"), std::string::npos) << terms;
  const std::string negative =
      without([](auto& t) { t["observer_grid"]["glare_terms"]["terms"][0][0] = -1.0; });
  EXPECT_NE(negative.find("must be > 0"), std::string::npos) << negative;
  const std::string points =
      without([](auto& t) { t["contributions"]["left"]["points"].erase(0); });
  EXPECT_NE(points.find("contributions.left.points"), std::string::npos) << points;
}

}  // namespace
}  // namespace lightsolver::test
