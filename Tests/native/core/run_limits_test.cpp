// Which limit ends a run: the photon count, an accuracy goal (with a large budget when no
// photon count was given), a time limit, or a cancel; and the forecast of a long run.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>

#include "lightsolver/scene_io.hpp"
#include "lightsolver/solver.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

// A white room with a desk grid: every target is lit, so any accuracy goal can be reached.
Scene lit_room(std::uint64_t default_photons) {
  Scene s;
  add_material(s, "white", Material::Type::Diffuse, 0.6);
  s.meshes.push_back(room_mesh("room", 0, dvec3(0), dvec3(4, 3, 3), 2));
  s.targets.push_back(surface("room", 0));
  s.targets.push_back(grid("desk", {1, 1, 0.8}, {1, 0, 0}, {0, 0.6, 0}, 1, 1));
  s.luminaires.push_back(point_light({2, 1.5, 2.5}, 2000.0));
  s.settings.photons = default_photons;
  validate(s);
  return s;
}

bool has_warning(const Results& r, const std::string& text) {
  for (const auto& w : r.warnings) {
    if (w.find(text) != std::string::npos) return true;
  }
  return false;
}

TEST(RunLimits, AccuracyWithoutAPhotonCountIsNotCappedByTheSceneDefault) {
  const Scene s = lit_room(10'000);  // far too few photons for +-2 %
  SolveOptions o;
  o.target_accuracy = 0.02;
  const Results r = solve(s, o);
  EXPECT_EQ(r.stop_reason, kStopAccuracy);
  EXPECT_TRUE(r.accuracy_met);
  EXPECT_FALSE(r.partial);
  // More than the scene's 10^4 (not capped by it); the connected reflected light (auto, the
  // default) reaches the goal with fewer photons than the photons alone (about 10^5).
  EXPECT_GT(r.photons, 10'000u);
  EXPECT_EQ(r.photons_requested, kAccuracyPhotonBudget);
  ASSERT_TRUE(r.max_seconds.has_value());
  EXPECT_EQ(*r.max_seconds, kDefaultAccuracySeconds);
  for (const auto& t : r.targets) {
    EXPECT_LE(0.5 * (t.estimate.ci_high - t.estimate.ci_low), 0.02 * t.estimate.mean) << t.name;
  }
  EXPECT_FALSE(has_warning(r, "accuracy")) << r.warnings.size();
  EXPECT_EQ(solve(s, o).photons, r.photons);  // still deterministic for a seed
}

TEST(RunLimits, AnExplicitPhotonCountStaysTheBudget) {
  const Scene s = lit_room(10'000);
  SolveOptions o;
  o.target_accuracy = 0.02;
  o.photons = 20'000;
  const Results r = solve(s, o);
  EXPECT_EQ(r.stop_reason, kStopPhotons);
  EXPECT_EQ(r.photons, 20'000u);
  EXPECT_FALSE(r.accuracy_met);
  EXPECT_FALSE(r.max_seconds.has_value());  // no default time limit for an explicit count
  EXPECT_TRUE(has_warning(r, "photon budget ran out"));
  const Results plain = solve(s, SolveOptions{});  // no goal: the scene's count, no limit
  EXPECT_EQ(plain.stop_reason, kStopPhotons);
  EXPECT_EQ(plain.photons, 10'000u);
  EXPECT_FALSE(plain.max_seconds.has_value());
}

TEST(RunLimits, TheScenesTimeLimitIsADefaultLikeItsPhotonCount) {
  // A limit so short that any run of more than one batch (2^14 photons) would be cut by it.
  Scene s = lit_room(1'000'000);
  s.settings.max_seconds = 1e-6;
  const Results from_scene = solve(s, SolveOptions{});
  EXPECT_EQ(from_scene.stop_reason, kStopTime);
  EXPECT_EQ(from_scene.photons, 1u << 14);  // at least one batch, then the limit
  // An explicit count (an optimizer evaluation, --photons) is traced to the end...
  SolveOptions o;
  o.photons = 200'000;
  const Results explicit_count = solve(s, o);
  EXPECT_EQ(explicit_count.stop_reason, kStopPhotons);
  EXPECT_EQ(explicit_count.photons, 200'000u);
  EXPECT_FALSE(explicit_count.max_seconds.has_value());
  // ...unless an explicit time limit comes with it.
  o.max_seconds = 1e-6;
  EXPECT_EQ(solve(s, o).photons, 1u << 14);
}

TEST(RunLimits, ATimeLimitEndsAHugeRunWithAForecast) {
  const Scene s = lit_room(10'000);
  SolveOptions o;
  o.photons = 10'000'000'000'000ull;  // days on any machine
  o.max_seconds = 0.8;
  int forecasts = 0;
  RunForecast seen;
  o.forecast = [&](const RunForecast& f) {
    ++forecasts;
    seen = f;
  };
  const Results r = solve(s, o);
  EXPECT_EQ(r.stop_reason, kStopTime);
  EXPECT_FALSE(r.partial);  // not a cancel: exit code 0, results complete for what was traced
  EXPECT_GT(r.photons, 0u);
  EXPECT_LT(r.photons, *o.photons);
  EXPECT_LT(r.seconds, 10.0);
  EXPECT_TRUE(has_warning(r, "time limit (0.8 s) ended the run"));
  EXPECT_TRUE(has_warning(r, "machine's speed"));
  EXPECT_GT(r.targets[0].estimate.mean, 0.0);
  ASSERT_EQ(forecasts, 1);
  EXPECT_EQ(seen.photons, *o.photons);
  EXPECT_FALSE(seen.accuracy_goal);
  EXPECT_GT(seen.photons_per_second, 0.0);
  EXPECT_NEAR(seen.seconds, double(seen.photons) / seen.photons_per_second, 1e-6 * seen.seconds);
  EXPECT_GT(seen.seconds, 60.0);
  ASSERT_TRUE(seen.max_seconds.has_value());
  EXPECT_EQ(*seen.max_seconds, 0.8);
}

TEST(RunLimits, ATimeLimitBeforeTheGoalIsReportedAsSuch) {
  Scene s = lit_room(10'000);
  s.settings.max_seconds = 0.6;  // the scene's limit applies to accuracy runs too
  SolveOptions o;
  o.target_accuracy = 1e-5;  // out of reach
  int forecasts = 0;
  o.forecast = [&](const RunForecast& f) {
    ++forecasts;
    EXPECT_TRUE(f.accuracy_goal);
    EXPECT_GT(f.photons, 1'000'000'000u);  // (1e-2 / 1e-5)^2 x what a fraction of a second gives
    EXPECT_LE(f.photons, kAccuracyPhotonBudget);
  };
  const Results r = solve(s, o);
  EXPECT_EQ(r.stop_reason, kStopTime);
  EXPECT_FALSE(r.accuracy_met);
  EXPECT_EQ(*r.max_seconds, 0.6);
  EXPECT_TRUE(has_warning(r, "before every target reached the requested accuracy"));
  EXPECT_FALSE(has_warning(r, "photon budget ran out"));
  EXPECT_EQ(forecasts, 1);
}

TEST(RunLimits, CancelIsTheStopReasonOfAPartialRun) {
  const Scene s = lit_room(200'000);
  std::atomic<bool> cancel{true};
  SolveOptions o;
  o.cancel = &cancel;
  const Results r = solve(s, o);
  EXPECT_EQ(r.stop_reason, kStopCancelled);
  EXPECT_TRUE(r.partial);
  // A progress callback that says stop after the last batch cancels nothing.
  const Results all = solve(s, SolveOptions{},
                            [](std::uint64_t done, std::uint64_t total) { return done < total; });
  EXPECT_EQ(all.stop_reason, kStopPhotons);
  EXPECT_FALSE(all.partial);
}

TEST(RunLimits, TimeLimitsMustBeFinitePositiveSeconds) {
  const Scene s = lit_room(10'000);
  for (const double bad : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    SolveOptions o;
    o.max_seconds = bad;
    EXPECT_THROW(solve(s, o), InputError) << bad;
  }
  const std::string head =
      R"({"format": "lightsolver.scene/1", "materials": {"w": {"type": "diffuse"}},
          "meshes": [{"name": "m", "material": "w", "vertices": [[0,0,0], [1,0,0], [0,1,0]],
                      "triangles": [[0, 1, 2]]}],
          "luminaires": [{"name": "l", "type": "point", "flux_lm": 1, "position": [0, 0, 1]}],
          "targets": [{"name": "t", "type": "surface", "mesh": "m"}],
          "settings": {"max_seconds": )";
  for (const char* bad : {"0", "-5", "\"60\""}) {
    try {
      scene_from_json(head + bad + "}}", "t.json", ".");
      ADD_FAILURE() << bad << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("settings.max_seconds"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(scene_from_json(head + "90}}", "t.json", ".").settings.max_seconds, 90.0);
}

}  // namespace
}  // namespace lightsolver::test
