// Quasi-random photons together with next-event estimation (docs/statistics.md, "Quasi-random
// photons"): the replicates carry the photon part (light after a scattering), one direct part per
// group is shared by them and added with its own variance. The interval's arithmetic on hand-made
// tallies, the direct part alone where nothing reflects, groups, agreement with photons alone in
// the box room, and the effects. Coverage over 256 seeds: qmc_coverage_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "lightsolver/simulation.hpp"
#include "model/groups.hpp"
#include "model/replicates.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

// Two groups, four replicates, one bin: group 0 with a direct part, group 1 without.
struct HandTallies {
  std::vector<Tally> bins;
  std::vector<detail::DirectPart> direct{{10.0, 4.0, 32}, {99.0, 99.0, 5}};
  std::array<double, 4> a{90, 110, 100, 104}, b{40, 30, 36, 50};  // deposits per replicate
  detail::GroupedTallies t;

  HandTallies() {
    for (std::size_t r = 0; r < 4; ++r) {
      bins.push_back({std::uint64_t(a[r]), std::uint64_t(a[r])});  // group 0
      bins.push_back({std::uint64_t(b[r]), std::uint64_t(b[r])});  // group 1
    }
    t.bins = &bins;
    t.bin_count = 1;
    t.photons = {400, 400};  // 100 per replicate
    t.flux_lm = {100.0, 50.0};
    t.direct = &direct;
    // As grouped_tallies lays them out: a factor for every group, and `next_event` says which
    // group has a direct part (group 1 has none: its row, 99 lx, must never be read).
    t.direct_scale = {1.0, 1.0};
    t.next_event = {1, 0};
    t.replicates = 4;
  }
};

// The photon part is the replicates' Student-t interval of their summed groups; the direct part
// adds its lux to the mean and z·√Var to each end's distance, in quadrature.
TEST(QuasiRandomNextEvent, DirectPartAddsToTheReplicateInterval) {
  HandTallies h;
  const double z = z_for_confidence(0.95);
  std::array<double, 4> both{}, only1{};
  for (std::size_t r = 0; r < 4; ++r) {
    both[r] = h.a[r] + 0.5 * h.b[r];  // Φ_g / A · S / (N_g / R), area 1 m²
    only1[r] = 0.5 * h.b[r];
  }
  const Estimate photons = detail::replicate_interval(both, z, 560);
  const Estimate e = h.t.estimate_z(0, 1.0, z);
  // The direct part's half-width: z·σ plus its mean's rounding allowance, (lit + 16)·eps·lux
  // (with_direct_part, model/groups.cpp), lit = 32 points and 10 lx here.
  const double half = z * 2.0 + 48.0 * std::numeric_limits<double>::epsilon() * 10.0;
  EXPECT_DOUBLE_EQ(e.mean, photons.mean + 10.0);
  EXPECT_DOUBLE_EQ(e.ci_high - e.mean, std::hypot(photons.ci_high - photons.mean, half));
  EXPECT_DOUBLE_EQ(e.mean - e.ci_low, std::hypot(photons.mean - photons.ci_low, half));
  EXPECT_DOUBLE_EQ(e.sigma, std::hypot(photons.sigma, 2.0));
  EXPECT_EQ(e.hits, 560u + 32u);
  // Group 1 alone has no direct part: exactly the replicates' interval.
  const Estimate g1 = h.t.group_estimate_z(1, 0, 1.0, z);
  const Estimate p1 = detail::replicate_interval(only1, z, 156);
  EXPECT_EQ(g1.mean, p1.mean);
  EXPECT_EQ(g1.ci_low, p1.ci_low);
  EXPECT_EQ(g1.ci_high, p1.ci_high);
  // Where nothing reflects, group 0's photons carry nothing: its direct part is all of it,
  // the point 10 ± half with the lit points as hits.
  h.t.photons_reflect = false;
  const Estimate g0 = h.t.group_estimate_z(0, 0, 1.0, z);
  EXPECT_DOUBLE_EQ(g0.mean, 10.0);
  EXPECT_DOUBLE_EQ(g0.ci_high, 10.0 + half);
  EXPECT_DOUBLE_EQ(g0.ci_low, 10.0 - half);
  EXPECT_EQ(g0.hits, 32u);
  const Estimate sum = h.t.estimate_z(0, 1.0, z);
  EXPECT_DOUBLE_EQ(sum.mean, p1.mean + 10.0);
  EXPECT_DOUBLE_EQ(sum.ci_high - sum.mean, std::hypot(p1.ci_high - p1.mean, half));
}

// A point source over a grid and nothing else: the direct part is the whole estimate, and it is
// the random sampler's to the bit (the same seed draws the same points), inside the exact value.
TEST(QuasiRandomNextEvent, NothingReflectsDirectPartAlone) {
  Scene s;
  const dvec3 src(0.3, -0.2, 2.0), c(-2, -2, 0), e1(4, 0, 0), e2(0, 4, 0);
  s.luminaires.push_back(point_light(src, 5000.0));
  s.targets.push_back(grid("floor", c, e1, e2, 4, 4));
  Simulation sim(s, {"embree"});
  const Results q = sim.run(sobol_options(8 * 4096, 7, "on"));
  SolveOptions random = sobol_options(8 * 4096, 7, "on");
  random.sampler = "random";
  const Results r = sim.run(random);
  EXPECT_EQ(q.sampler, "sobol");
  for (unsigned k = 0; k < 16; ++k) {
    const Estimate &a = q.targets[0].cells[k], &b = r.targets[0].cells[k];
    EXPECT_EQ(a.mean, b.mean) << k;
    EXPECT_EQ(a.ci_low, b.ci_low) << k;
    EXPECT_EQ(a.ci_high, b.ci_high) << k;
    const dvec3 cc = c + double(k % 4) / 4.0 * e1 + double(k / 4) / 4.0 * e2;
    expect_in_ci(a, point_source_patch_lux(src, 5000.0, cc, e1 / 4.0, e2 / 4.0), 0.01,
                 "cell " + std::to_string(k));
  }
}

// The box room (every surface rho 0.5, the 100 cd source at (2, 2, 2.9)) with a black
// table casting shadow edges: the sobol + next-event cells against photons alone (random,
// independent), each within 4.5 sigma of the difference Bonferroni-free (16 cells, fixed seeds).
TEST(QuasiRandomNextEvent, BoxRoomAgreesWithPhotonsAlone) {
  Simulation sim(box_room(4, true), {"embree"});
  const Results q = sim.run(sobol_options(8 * 32'768, 3, "on"));
  SolveOptions alone = sobol_options(2'000'000, 4, "off");
  alone.sampler = "random";
  const Results p = sim.run(alone);
  const double t = detail::student_t_for_z(4.5, 7);  // the sobol part's sigma is from 8 values
  for (unsigned k = 0; k < 16; ++k) {
    const Estimate &a = q.targets[0].cells[k], &b = p.targets[0].cells[k];
    EXPECT_LE(std::abs(a.mean - b.mean), t * std::hypot(a.sigma, b.sigma)) << "cell " << k;
    EXPECT_LT(a.sigma, 0.02 * a.mean) << "cell " << k;
  }
}

// Two groups, each with its direct part: the sum of both in every cell, within the interval.
TEST(QuasiRandomNextEvent, GroupsAddTheirDirectParts) {
  Scene s;
  const dvec3 a(-0.5, 0.2, 1.5), b(0.8, -0.4, 2.5), c(-1, -1, 0), e1(2, 0, 0), e2(0, 2, 0);
  s.luminaires.push_back(named(point_light(a, 4000.0), "a", "left"));
  s.luminaires.push_back(named(point_light(b, 1000.0), "b", "right"));
  s.targets.push_back(grid("floor", c, e1, e2, 2, 2));
  const Results r = Simulation(s, {"embree"}).run(sobol_options(8 * 4096, 21, "on"));
  ASSERT_EQ(r.groups.size(), 2u);
  for (unsigned k = 0; k < 4; ++k) {
    const dvec3 cc = c + double(k % 2) * 0.5 * e1 + double(k / 2) * 0.5 * e2;
    const double exact = point_source_patch_lux(a, 4000.0, cc, 0.5 * e1, 0.5 * e2) +
                         point_source_patch_lux(b, 1000.0, cc, 0.5 * e1, 0.5 * e2);
    expect_in_ci(r.targets[0].cells[k], exact, 0.01, "cell " + std::to_string(k));
  }
}

// "on" and "auto" both trace direct light by shadow rays in a sobol run and say so; "off" says
// the setting turned it off.
TEST(QuasiRandomNextEvent, EffectsSayWhatRan) {
  Simulation sim(box_room(4, true), {"embree"});
  for (const std::string mode : {"on", "auto", "off"}) {
    const Results r = sim.run(sobol_options(8 * 1024, 2, mode));
    const auto& done = r.effects.simulated;
    const bool simulated = std::find(done.begin(), done.end(), "next_event_direct") != done.end();
    EXPECT_EQ(simulated, mode != "off") << mode;
    EXPECT_EQ(r.sampler, "sobol") << mode;
  }
}

}  // namespace
}  // namespace lightsolver::test
