// Groups traced apart (Simulation::trace_group) and combined (Simulation::combine), the
// optimizer's reused traces: combining every group's trace of one seed is the run, bit for bit,
// on every backend; fixed photon shares keep a group's photons when another group's flux
// changes; a combined result scales linearly in a group's flux; bad input is refused clearly.
#include <gtest/gtest.h>

#include "lightsolver/error.hpp"
#include "lightsolver/simulation.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

// grouped_room plus "own": a point without a group key, so three groups in all.
Scene three_groups() {
  Scene s = grouped_room();
  s.luminaires.push_back(named(point_light({3.0, 2.0, 2.5}, 50), "own", ""));
  return s;
}

void expect_same(const Estimate& a, const Estimate& b, const std::string& where) {
  EXPECT_EQ(a.mean, b.mean) << where;
  EXPECT_EQ(a.ci_low, b.ci_low) << where;
  EXPECT_EQ(a.ci_high, b.ci_high) << where;
  EXPECT_EQ(a.sigma, b.sigma) << where;
  EXPECT_EQ(a.hits, b.hits) << where;
}

void expect_same(const Results& a, const Results& b) {
  ASSERT_EQ(a.targets.size(), b.targets.size());
  for (std::size_t t = 0; t < a.targets.size(); ++t) {
    const std::string& name = a.targets[t].name;
    expect_same(a.targets[t].estimate, b.targets[t].estimate, name);
    ASSERT_EQ(a.targets[t].cells.size(), b.targets[t].cells.size());
    for (std::size_t c = 0; c < a.targets[t].cells.size(); ++c) {
      expect_same(a.targets[t].cells[c], b.targets[t].cells[c], name + " cell");
    }
  }
}

// Every group traced alone with the run's seed, then combined at the groups' own fluxes.
Results traced_apart(Simulation& sim, std::uint64_t photons, std::uint64_t seed) {
  std::vector<GroupTrace> traces;
  std::vector<double> flux;
  for (std::size_t g = 0; g < sim.groups().size(); ++g) {
    traces.push_back(sim.trace_group(g, photons, seed));
    flux.push_back(sim.groups()[g].flux_lm);
  }
  std::vector<const GroupTrace*> parts;
  for (const GroupTrace& t : traces) parts.push_back(&t);
  return sim.combine(parts, flux, 0.95);
}

class GroupTraces : public ::testing::TestWithParam<std::string> {};

TEST_P(GroupTraces, EveryGroupTracedApartAndCombinedIsTheRun) {
  Simulation sim(three_groups(), Simulation::Options{GetParam(), 2, {}});
  ASSERT_EQ(sim.groups().size(), 3u);
  EXPECT_EQ(sim.groups()[0].luminaires, (std::vector<std::size_t>{0, 1}));
  SolveOptions o;
  o.photons = 60'000;
  o.seed = 17;
  // Group traces follow the scene's next_event (auto, the default) as the run does: direct
  // parts and photon tallies both. Group traces do not connect reflected light (the optimizer's
  // traces count every reflected crossing), so the run compared bit for bit with them must not
  // either: off here, where auto (the default) would connect.
  o.connect_reflections = "off";
  const Results run = sim.run(o);
  const Results apart = traced_apart(sim, 60'000, 17);
  expect_same(run, apart);
  for (std::size_t g = 0; g < run.groups.size(); ++g) {
    EXPECT_EQ(run.groups[g].photons, apart.groups[g].photons);
  }
  EXPECT_EQ(apart.photons, 60'000u);
  EXPECT_EQ(apart.total_flux_lm, run.total_flux_lm);
}

INSTANTIATE_TEST_SUITE_P(Backends, GroupTraces, ::testing::ValuesIn(backends()));

// With shares fixed, group "right"'s photons (and so its trace) do not depend on the flux of
// "left"; by flux they do. A combined result is linear in a group's flux: "left" traced at 3000
// lm and combined at 1500 lm is, bit for bit, "left" traced and combined at 1500 lm.
TEST(GroupTraces, FixedSharesAndLinearFlux) {
  Simulation sim(three_groups(), Simulation::Options{"embree", 2, {}});
  const std::uint64_t n = 40'000;
  const std::uint64_t by_flux = sim.trace_group(1, n, 3).photons;
  sim.fix_photon_shares({3000, 6000, 50});
  const GroupTrace right = sim.trace_group(1, n, 3);
  EXPECT_NE(right.photons, by_flux);
  const GroupTrace left_full = sim.trace_group(0, n, 3);
  Luminaire dimmer = sim.scene().luminaires[0];
  dimmer.flux_lm /= 2.0;
  Luminaire dimmer2 = sim.scene().luminaires[1];
  dimmer2.flux_lm /= 2.0;
  sim.set_luminaire(0, dimmer);
  sim.set_luminaire(1, dimmer2);
  EXPECT_EQ(sim.trace_group(1, n, 3).bins.size(), right.bins.size());
  EXPECT_EQ(sim.trace_group(1, n, 3).photons, right.photons);  // fixed: unmoved by left's flux
  const GroupTrace left_half = sim.trace_group(0, n, 3);
  EXPECT_EQ(left_half.photons, left_full.photons);
  const GroupTrace own = sim.trace_group(2, n, 3);
  const double left_lm = sim.groups()[0].flux_lm;
  const Results scaled = sim.combine({&left_full, &right, &own}, {left_lm, 3000, 50}, 0.95);
  const Results traced = sim.combine({&left_half, &right, &own}, {left_lm, 3000, 50}, 0.95);
  expect_same(scaled, traced);
  // A dark group (null trace) adds nothing: the rest is the others' combined light.
  const Results dark = sim.combine({nullptr, &right, &own}, {0, 3000, 50}, 0.95);
  EXPECT_LT(dark.targets[1].estimate.mean, traced.targets[1].estimate.mean);
  EXPECT_EQ(dark.groups[0].photons, 0u);
}

TEST(GroupTraceErrors, BadGroupsWeightsAndTracesAreRefused) {
  Scene s = three_groups();
  s.luminaires[2].flux_lm = 0.0;  // group "right" has no flux
  Simulation sim(s, Simulation::Options{"embree", 1, {}});
  EXPECT_THROW(sim.trace_group(3, 1000, 1), InputError);
  try {
    sim.trace_group(1, 1000, 1);
    FAIL() << "a group without flux was traced";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("\"right\" has no flux"), std::string::npos) << e.what();
  }
  EXPECT_THROW(sim.fix_photon_shares({1, 2}), InputError);
  EXPECT_THROW(sim.fix_photon_shares({1, -2, 3}), InputError);
  EXPECT_THROW(sim.fix_photon_shares({1, std::nan(""), 3}), InputError);
  const GroupTrace left = sim.trace_group(0, 1000, 1);
  EXPECT_THROW(sim.combine({&left}, {1}, 0.95), std::invalid_argument);  // too few
  EXPECT_THROW(sim.combine({&left, &left, nullptr}, {1, 1, 0}, 0.95),    // not group 1's
               std::invalid_argument);
  EXPECT_THROW(sim.combine({&left, nullptr, nullptr}, {-1, 0, 0}, 0.95), std::invalid_argument);
  // A group without a trace is dark: a flux for it would be recorded but its light missing.
  EXPECT_THROW(sim.combine({&left, nullptr, nullptr}, {1, 5, 0}, 0.95), std::invalid_argument);
  EXPECT_THROW(sim.combine({&left, nullptr, nullptr}, {1, 0, 0}, 1.0), InputError);
  const Results ok = sim.combine({&left, nullptr, nullptr}, {1, 0, 0}, 0.95);
  EXPECT_GT(ok.targets[1].estimate.mean, 0.0);
}

}  // namespace
}  // namespace lightsolver::test

namespace lightsolver::test {
namespace {

// An observer rates each luminaire's luminance, which follows its group's flux: a panel
// combined at half its traced flux glares as the panel traced at half flux (same tallies).
TEST(GroupTraces, CombinedGlareFollowsTheCombinedFlux) {
  Scene s = grouped_room();
  Luminaire panel;
  panel.type = Luminaire::Type::Area;
  panel.flux_lm = 4000;
  panel.corner = {1.5, 1.7, 2.9};
  panel.edge1 = {0, 0.6, 0};
  panel.edge2 = {0.6, 0, 0};
  s.luminaires.push_back(named(panel, "panel", "panel"));
  Target eye;
  eye.name = "eye";
  eye.type = Target::Type::Observer;
  eye.position = {5.0, 2.0, 1.2};
  eye.view_direction = {-1, 0, 0};
  s.targets.push_back(eye);
  Simulation sim(s, Simulation::Options{"embree", 2, {}});
  sim.fix_photon_shares({3000, 3000, 4000});
  auto all = [&](std::uint64_t seed) {
    std::vector<GroupTrace> t;
    for (std::size_t g = 0; g < 3; ++g) t.push_back(sim.trace_group(g, 60'000, seed));
    return t;
  };
  const std::vector<GroupTrace> full = all(5);
  const Results bright = sim.combine({&full[0], &full[1], &full[2]}, {3000, 3000, 4000}, 0.95);
  const Results dimmed = sim.combine({&full[0], &full[1], &full[2]}, {3000, 3000, 2000}, 0.95);
  Luminaire half = sim.scene().luminaires[3];
  half.flux_lm = 2000;
  sim.set_luminaire(3, half);
  const std::vector<GroupTrace> traced = all(5);
  const Results at_half =
      sim.combine({&traced[0], &traced[1], &traced[2]}, {3000, 3000, 2000}, 0.95);
  const ObserverGlare& g = *dimmed.targets[2].glare;
  ASSERT_TRUE(g.ugr.has_value() && bright.targets[2].glare->ugr.has_value());
  EXPECT_LT(*g.ugr, *bright.targets[2].glare->ugr - 1.0);  // half the luminance: about 2 less
  EXPECT_NEAR(*g.ugr, *at_half.targets[2].glare->ugr, 1e-9);
  EXPECT_NEAR(g.luminaire_sum, at_half.targets[2].glare->luminaire_sum, 1e-12 * g.luminaire_sum);
}

}  // namespace
}  // namespace lightsolver::test
