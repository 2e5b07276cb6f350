// next_event "auto" judges per target whether shadow rays pay (estimate/direct_choice.hpp,
// docs/statistics.md "When shadow rays pay"): a large floor under a lamp goes back to the
// photons, small targets keep their shadow rays, both agree with the closed form and with
// photons alone, and "on" keeps shadow rays everywhere.
#include <gtest/gtest.h>

#include <algorithm>

#include "lightsolver/simulation.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

constexpr double kFlux = 5000.0;
const dvec3 kLamp(0.0, 0.0, 1.0);
const dvec3 kFloor(-5, -5, 0), kFloorE1(10, 0, 0), kFloorE2(0, 10, 0);
const dvec3 kDesk(-1, -1, 0.5), kDeskE1(2, 0, 0), kDeskE2(0, 2, 0);
constexpr unsigned kDeskCells = 4;

// A black 10 x 10 m floor (a surface target) 1 m under a point lamp: about 41 % of the photons
// land on it, while its illuminance peaks under the lamp (the points' values spread over two
// orders of magnitude): its photons' interval is several times narrower than its shadow rays'.
// With `desk`, a 2 x 2 m grid of 4 x 4 cells half-way up (virtual: it casts no shadow), whose
// small cells the shadow rays sample far better than their few photons. With `ground`, a grey
// ground 1 m below the floor: the photons that pass the floor reflect there and leave upwards
// (nothing above), so the scene reflects (effect interreflection) and the closed forms still
// hold (no reflected photon reaches a target's front).
Scene lamp_over_floor(bool desk, bool ground = true) {
  Scene s;
  add_material(s, "black", Material::Type::Diffuse, 0.0);
  add_material(s, "grey", Material::Type::Diffuse, 0.5);
  s.meshes.push_back(quad_mesh("floor", 0, kFloor, kFloorE1, kFloorE2));
  if (ground) s.meshes.push_back(quad_mesh("ground", 1, {-20, -20, -1}, {40, 0, 0}, {0, 40, 0}));
  s.luminaires.push_back(point_light(kLamp, kFlux));
  s.targets.push_back(surface("floor", 0));
  if (desk) s.targets.push_back(grid("desk", kDesk, kDeskE1, kDeskE2, kDeskCells, kDeskCells));
  return s;
}

bool simulated(const Results& r, const std::string& effect) {
  const auto& s = r.effects.simulated;
  return std::find(s.begin(), s.end(), effect) != s.end();
}

// The words the effects list gives next_event_direct: its note when simulated, else its reason.
std::string next_event_words(const Results& r) {
  for (const EffectNote& n : r.effects.notes) {
    if (n.effect == "next_event_direct") return n.note;
  }
  for (const SkippedEffect& e : r.effects.skipped) {
    if (e.effect == "next_event_direct") return e.reason;
  }
  return {};
}

double width(const Estimate& e) { return e.ci_high - e.ci_low; }

void expect_desk_exact(const Results& r, double max_rel_half_width) {
  ASSERT_EQ(r.targets[1].cells.size(), kDeskCells * kDeskCells);
  for (unsigned k = 0; k < kDeskCells * kDeskCells; ++k) {
    const dvec3 c = kDesk + double(k % kDeskCells) / kDeskCells * kDeskE1 +
                    double(k / kDeskCells) / kDeskCells * kDeskE2;
    const double exact = point_source_patch_lux(kLamp, kFlux, c, kDeskE1 / double(kDeskCells),
                                                kDeskE2 / double(kDeskCells));
    expect_in_ci(r.targets[1].cells[k], exact, max_rel_half_width,
                 "desk cell " + std::to_string(k));
  }
}

const double kFloorExact = point_source_patch_lux(kLamp, kFlux, kFloor, kFloorE1, kFloorE2);

class NextEventChoice : public ::testing::TestWithParam<std::string> {};

// The floor alone: auto gives it back to the photons, so the run is the photons-only run bit
// for bit (the same photons deposit the same bounces), its interval no wider, and the effects
// list says why; "on" traces its shadow rays, several times wider.
TEST_P(NextEventChoice, LargeFloorGoesBackToThePhotons) {
  const Scene s = lamp_over_floor(false);
  const Results automatic = run_next_event(GetParam(), s, 50'000, 3, "auto");
  const Results off = run_next_event(GetParam(), s, 50'000, 3, "off");
  const Results on = run_next_event(GetParam(), s, 50'000, 3, "on");
  EXPECT_FALSE(simulated(automatic, "next_event_direct"));
  const std::string why = next_event_words(automatic);
  EXPECT_NE(why.find("auto"), std::string::npos) << why;
  EXPECT_NE(why.find("floor ("), std::string::npos) << why;
  const Estimate &a = automatic.targets[0].estimate, &p = off.targets[0].estimate;
  EXPECT_EQ(a.mean, p.mean);
  EXPECT_EQ(a.ci_low, p.ci_low);
  EXPECT_EQ(a.ci_high, p.ci_high);
  expect_in_ci(a, kFloorExact, 0.05, "floor (auto)");
  EXPECT_TRUE(simulated(on, "next_event_direct"));
  EXPECT_TRUE(on.effects.notes.empty());
  expect_in_ci(on.targets[0].estimate, kFloorExact, 0.2, "floor (on)");
  EXPECT_GT(width(on.targets[0].estimate), width(a));  // what the choice avoided
}

// Small targets keep their shadow rays, as before the choice: a small tilted patch and the box
// room's work plane.
TEST_P(NextEventChoice, SmallTargetsKeepShadowRays) {
  Scene s;
  const dvec3 src(0.0, 0.0, 2.0), pc(-0.5, -0.4, 0.2), pe1(1.0, 0, 0), pe2(0, 0.5, 0.3);
  s.luminaires.push_back(point_light(src, kFlux));
  add_material(s, "black", Material::Type::Diffuse, 0.0);
  s.meshes.push_back(quad_mesh("tilted", 0, pc, pe1, pe2));
  s.targets.push_back(surface("tilted", 0));
  const Results patch = run_next_event(GetParam(), s, 50'000, 5, "auto");
  EXPECT_TRUE(simulated(patch, "next_event_direct"));
  EXPECT_TRUE(patch.effects.notes.empty()) << next_event_words(patch);
  expect_in_ci(patch.targets[0].estimate, point_source_patch_lux(src, kFlux, pc, pe1, pe2), 0.01,
               "tilted patch");
  const Results room = run_next_event(GetParam(), box_room(4), 20'000, 6, "auto");
  EXPECT_TRUE(simulated(room, "next_event_direct"));
  EXPECT_TRUE(room.effects.notes.empty()) << next_event_words(room);
}

// One target each way: the floor by photons, the desk's cells by shadow rays. Both agree with
// their closed forms and with photons alone (another seed, within five combined sigma); the
// note names each. "on" keeps the floor's shadow rays: its interval is wider than auto's.
TEST_P(NextEventChoice, MixedSceneAgreesWithClosedFormAndPhotons) {
  const Scene s = lamp_over_floor(true);
  const Results automatic = run_next_event(GetParam(), s, 50'000, 7, "auto");
  ASSERT_TRUE(simulated(automatic, "next_event_direct"));
  const std::string note = next_event_words(automatic);
  EXPECT_NE(note.find("photons where shadow rays would be wider: floor ("), std::string::npos)
      << note;
  EXPECT_NE(note.find("shadow rays: desk"), std::string::npos) << note;
  expect_in_ci(automatic.targets[0].estimate, kFloorExact, 0.05, "floor (auto)");
  // The desk's photons, reflected light only, have no hit: their zero-hit bound (about
  // z^2 / N of flux / cell area, 5 lx) is most of a corner cell's interval.
  expect_desk_exact(automatic, 0.05);
  const Results off = run_next_event(GetParam(), s, 50'000, 8, "off");
  expect_same_within(automatic.targets[0].estimate, off.targets[0].estimate, "floor");
  for (std::size_t k = 0; k < kDeskCells * kDeskCells; ++k) {
    expect_same_within(automatic.targets[1].cells[k], off.targets[1].cells[k],
                       "desk cell " + std::to_string(k));
    EXPECT_LT(width(automatic.targets[1].cells[k]), width(off.targets[1].cells[k]));
  }
  const Results on = run_next_event(GetParam(), s, 50'000, 7, "on");
  EXPECT_TRUE(on.effects.notes.empty()) << next_event_words(on);
  expect_in_ci(on.targets[0].estimate, kFloorExact, 0.2, "floor (on)");
  expect_desk_exact(on, 0.05);
  EXPECT_GT(width(on.targets[0].estimate), width(automatic.targets[0].estimate));
}

// Where nothing reflects, the photons deposit nothing at targets with shadow rays (exactly
// zero): one target by photons would give every other their zero-hit bound, so a mixed choice
// keeps shadow rays everywhere and says why; the desk's intervals stay as narrow as "on"'s.
TEST_P(NextEventChoice, NothingReflectsKeepsShadowRaysEverywhere) {
  const Scene s = lamp_over_floor(true, false);
  const Results automatic = run_next_event(GetParam(), s, 50'000, 7, "auto");
  ASSERT_TRUE(simulated(automatic, "next_event_direct"));
  const std::string note = next_event_words(automatic);
  EXPECT_NE(note.find("nothing reflects"), std::string::npos) << note;
  EXPECT_NE(note.find("floor ("), std::string::npos) << note;
  expect_desk_exact(automatic, 0.01);
  const Results on = run_next_event(GetParam(), s, 50'000, 7, "on");
  EXPECT_EQ(automatic.targets[0].estimate.ci_high, on.targets[0].estimate.ci_high);
}

INSTANTIATE_TEST_SUITE_P(Backends, NextEventChoice, ::testing::ValuesIn(shadow_backends()));
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(NextEventChoice);

// The choice is made once per run and every replicate of a sobol run shares it (their direct
// parts and deposits alike); an accuracy goal judges against the photons it predicts.
TEST(NextEventChoiceRuns, SobolReplicatesAndAccuracyGoalsShareOneChoice) {
  const Scene s = lamp_over_floor(true);
  Results sobol = solve(s, sobol_options(50'000, 9, "auto"));
  EXPECT_NE(next_event_words(sobol).find("floor ("), std::string::npos) << next_event_words(sobol);
  expect_in_ci(sobol.targets[0].estimate, kFloorExact, 0.05, "floor (sobol)");
  expect_desk_exact(sobol, 0.02);
  SolveOptions goal;
  goal.backend = "embree";
  goal.seed = 10;
  goal.next_event = "auto";
  goal.target_accuracy = 0.02;
  goal.confidence = 0.95;
  const Results g = solve(s, goal);
  EXPECT_EQ(g.stop_reason, kStopAccuracy);
  EXPECT_NE(next_event_words(g).find("floor ("), std::string::npos) << next_event_words(g);
  EXPECT_NE(next_event_words(g).find("shadow rays: desk"), std::string::npos);
}

// A refine() continues only tallies traced with the same choice: the floor's photons deposit
// bounce 0 in both runs, and the continued run equals the whole run bit for bit.
TEST(NextEventChoiceRuns, RefineContinuesTheSameChoice) {
  Simulation::Options so;
  so.backend = "embree";
  Simulation sim(lamp_over_floor(true), so);
  SolveOptions o;
  o.photons = 20'000;
  o.seed = 11;
  o.next_event = "auto";
  sim.run(o);
  o.photons = 40'000;
  const Results refined = sim.refine(o);
  const Results whole = sim.run(o);
  EXPECT_EQ(refined.targets[0].estimate.mean, whole.targets[0].estimate.mean);
  EXPECT_EQ(refined.targets[0].estimate.ci_high, whole.targets[0].estimate.ci_high);
  EXPECT_EQ(refined.targets[1].cells[5].mean, whole.targets[1].cells[5].mean);
  EXPECT_EQ(next_event_words(refined), next_event_words(whole));
}

}  // namespace
}  // namespace lightsolver::test
