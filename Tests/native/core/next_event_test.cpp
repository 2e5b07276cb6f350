// Next-event estimation of direct light at targets (estimate/next_event.hpp): closed forms, the
// same answer as photons alone, honest intervals over 200 seeds, and the setting's errors.
#include <gtest/gtest.h>

#include "lightsolver/photometry.hpp"
#include "lightsolver/simulation.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

class NextEvent : public ::testing::TestWithParam<std::string> {};

// Direct light only (no surface): the cells' exact means lie in narrow intervals; the photons
// carry nothing here (nothing reflects: the direct part is the whole estimate).
TEST_P(NextEvent, PointSourceOverPlaneExactFromShadowRays) {
  Scene s;
  const dvec3 src(0.3, -0.2, 2.0), c(-2, -2, 0), e1(4, 0, 0), e2(0, 4, 0);
  s.luminaires.push_back(point_light(src, 5000.0));
  s.targets.push_back(grid("floor", c, e1, e2, 8, 8));
  const Results r = run_next_event(GetParam(), s, 200'000, 3, "on");
  for (unsigned k = 0; k < 64; ++k) {
    const dvec3 cc = c + double(k % 8) / 8.0 * e1 + double(k / 8) / 8.0 * e2;
    const double exact = point_source_patch_lux(src, 5000.0, cc, e1 / 8.0, e2 / 8.0);
    expect_in_ci(r.targets[0].cells[k], exact, 0.01, "cell " + std::to_string(k));
  }
}

// A tilted surface target under a point source: the area-weighted mean of its triangles.
TEST_P(NextEvent, SurfaceTargetFromShadowRays) {
  Scene s;
  const dvec3 src(0.0, 0.0, 2.0), pc(-0.5, -0.4, 0.2), pe1(1.0, 0, 0), pe2(0, 0.5, 0.3);
  s.luminaires.push_back(point_light(src, 5000.0));
  add_material(s, "black", Material::Type::Diffuse, 0.0);
  s.meshes.push_back(quad_mesh("tilted", 0, pc, pe1, pe2));
  s.targets.push_back(surface("tilted", 0));
  const Results r = run_next_event(GetParam(), s, 200'000, 5, "on");
  expect_in_ci(r.targets[0].estimate, point_source_patch_lux(src, 5000.0, pc, pe1, pe2), 0.01,
               "tilted patch");
}

// The box room with a table: every cell with next-event estimation agrees with photons alone
// within five combined sigma, and the intervals are narrower.
TEST_P(NextEvent, AgreesWithPhotonsAloneInABoxRoomWithShadows) {
  const Scene s = box_room(8, true);
  const Results on = run_next_event(GetParam(), s, 400'000, 11, "on", 0.95);
  const Results off = run_next_event(GetParam(), s, 400'000, 12, "off", 0.95);
  ASSERT_EQ(on.targets[0].cells.size(), 64u);
  const auto [width_on, width_off] = expect_cells_agree(on, off);
  EXPECT_LT(width_on, width_off);
}

// Coverage of the 95 % intervals over 200 seeds, in four cells (one under the table's shadow
// edge), against a reference 64 times longer: the miss rate within binomial limits (4 sigma).
// On Embree: the Vulkan backend's shadow rays and tallies equal Embree's (vulkan_tests), so its
// coverage is this one; lavapipe would take a minute over it.
TEST_P(NextEvent, PerCellCoverageOver200Seeds) {
  if (GetParam() != "embree") GTEST_SKIP() << "coverage is measured on Embree";
  const Scene s = box_room(8, true);
  Simulation::Options so;
  so.backend = GetParam();
  Simulation sim(s, so);
  SolveOptions ref;
  ref.photons = 12'800'000;
  ref.seed = 999;
  ref.next_event = "on";
  ref.confidence = 0.95;
  const Results reference = sim.run(ref);
  const std::size_t cells[] = {0, 27, 28, 45};  // a corner, under the table, its edge, open
  int inside = 0, trials = 0;
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    SolveOptions o = ref;
    o.photons = 200'000;
    o.seed = seed;
    const Results r = sim.run(o);
    for (const std::size_t c : cells) {
      const Estimate& e = r.targets[0].cells[c];
      const double truth = reference.targets[0].cells[c].mean;
      inside += e.ci_low <= truth && truth <= e.ci_high;
      ++trials;
    }
  }
  const double p = 0.95, sd = std::sqrt(p * (1 - p) / trials);
  EXPECT_GE(double(inside) / trials, p - 4 * sd) << inside << " of " << trials;
}

// The run's effects say what next-event estimation did, and a refine() continues a run bit for
// bit (the direct parts are the same for the same seed).
TEST_P(NextEvent, EffectsAndRefine) {
  const Scene s = box_room(4);
  Simulation::Options so;
  so.backend = GetParam();
  Simulation sim(s, so);
  SolveOptions o;
  o.photons = 20'000;
  o.seed = 4;
  o.next_event = "auto";
  const Results first = sim.run(o);
  const auto& simulated = first.effects.simulated;
  EXPECT_NE(std::find(simulated.begin(), simulated.end(), "next_event_direct"), simulated.end());
  o.photons = 40'000;
  const Results refined = sim.refine(o);
  const Results whole = sim.run(o);
  for (std::size_t k = 0; k < 16; ++k) {
    EXPECT_EQ(refined.targets[0].cells[k].mean, whole.targets[0].cells[k].mean);
    EXPECT_EQ(refined.targets[0].cells[k].ci_high, whole.targets[0].cells[k].ci_high);
  }
  o.next_event = "off";
  const Results off = sim.run(o);
  bool skipped = false;
  for (const auto& e : off.effects.skipped) {
    if (e.effect == "next_event_direct") skipped = e.reason.find("setting") != std::string::npos;
  }
  EXPECT_TRUE(skipped);
}

// Every sample luminaire file near the floor of a grey room, aimed and rotated: its shadow-ray
// direct light (the file's candela scaled to the traced flux, from points of its luminous
// opening) equals its photons' within five combined sigma in every cell, close up where the
// opening's size matters.
TEST_P(NextEvent, PhotometricFilesAgreeWithTheirPhotons) {
  // Every file on Embree; on Vulkan (lavapipe: slow) a disc and a cylinder opening.
  std::vector<std::string> files = {"downlight.ies",  "downlight.ldt",     "wallwasher.ies",
                                    "wallwasher.ldt", "batwing_panel.ies", "linear_tube.ldt"};
  if (GetParam() != "embree") files = {"downlight.ies", "linear_tube.ldt"};
  for (const std::string& file : files) {
    Scene s;
    Luminaire l;
    l.name = file;
    l.type = Luminaire::Type::Photometric;
    l.position = {1.0, 1.2, 1.0};
    l.aim = glm::normalize(dvec3(0.3, 0.1, -1.0));
    l.rotation_deg = 25.0;
    l.file = file;
    load_photometric(l, std::string(LIGHTSOLVER_SOURCE_DIR) + "/Resources/luminaires/" + file,
                     std::nullopt, "flux_lm");
    s.luminaires.push_back(l);
    s.targets.push_back(grid("floor", {0, 0, 0}, {3, 0, 0}, {0, 3, 0}, 6, 6));
    const Results on = run_next_event(GetParam(), s, 2'000'000, 21, "on");
    const Results off = run_next_event(GetParam(), s, 2'000'000, 22, "off");
    for (std::size_t k = 0; k < 36; ++k) {
      expect_same_within(on.targets[0].cells[k], off.targets[0].cells[k],
                         file + " cell " + std::to_string(k));
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, NextEvent, ::testing::ValuesIn(shadow_backends()));
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(NextEvent);

TEST(NextEventSetting, BadValuesNameTheField) {
  Scene s = box_room(2);
  SolveOptions o;
  o.photons = 100;
  o.next_event = "maybe";
  try {
    solve(s, o);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("next_event"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("auto, on, off"), std::string::npos) << e.what();
  }
  s.settings.next_event = "sometimes";
  EXPECT_THROW(validate(s), InputError);
}

TEST(NextEventSetting, OnWithoutAnyTargetIsRefused) {
  Scene s;
  s.luminaires.push_back(point_light({0, 0, 1}, 100));
  add_material(s, "grey", Material::Type::Diffuse, 0.5);
  s.meshes.push_back(quad_mesh("floor", 0, {-1, -1, 0}, {2, 0, 0}, {0, 2, 0}));
  SolveOptions o;
  o.photons = 100;
  o.next_event = "on";
  o.backend = "embree";
  s.targets.push_back(surface("floor", 0));
  EXPECT_NO_THROW(solve(s, o));
  s.targets.clear();
  s.targets.push_back(grid("g", {-1, -1, 0.5}, {2, 0, 0}, {0, 2, 0}, 1, 1));
  s.targets.back().reflected_only = true;  // counts reflected light only: nothing to sample
  try {
    solve(s, o);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no grid or surface target"), std::string::npos)
        << e.what();
  }
  o.next_event = "auto";
  EXPECT_NO_THROW(solve(s, o));
}

// Sobol' runs with next-event estimation: qmc_next_event_test.cpp.

}  // namespace
}  // namespace lightsolver::test
