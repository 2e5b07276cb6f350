// Quasi-random photons (sampler "sobol", docs/statistics.md "Quasi-random photons"): the Sobol'
// points and their scrambling, the replicates' Student-t interval, the runs that refuse the
// sampler, and unbiasedness against closed forms within the reported interval.
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <set>

#include "lightsolver/process_group.hpp"
#include "lightsolver/simulation.hpp"
#include "model/replicates.hpp"
#include "model/sobol.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

using detail::kSobolDims;

// Every coordinate of the first 2^m points, scrambled or not, puts one point in each of the
// 2^m intervals [k/2^m, (k+1)/2^m): each dimension of Sobol' is a (0, m, 1)-net, and a nested
// scramble permutes the intervals.
void expect_stratified(unsigned m, const std::array<std::uint32_t, kSobolDims>* seeds) {
  for (unsigned d = 0; d < kSobolDims; ++d) {
    std::set<std::uint32_t> cells;
    for (std::uint32_t i = 0; i < (1u << m); ++i) {
      std::uint32_t x = detail::sobol_point(i)[d];
      if (seeds) x = detail::owen_scramble(x, (*seeds)[d]);
      cells.insert(x >> (32 - m));
    }
    EXPECT_EQ(cells.size(), 1u << m) << "dimension " << d;
  }
}

TEST(Sobol, JoeKuoPointsAndNets) {
  // The first points of every Sobol' sequence in natural (not Gray-code) order: 0, 1/2
  // everywhere, then (1/4, 3/4) and (3/4, 1/4) in the first two dimensions (van der Corput's
  // radical inverse first: Joe & Kuo's table read the right way round).
  EXPECT_EQ(detail::sobol_point(0), (std::array<std::uint32_t, kSobolDims>{}));
  for (unsigned d = 0; d < kSobolDims; ++d) EXPECT_EQ(detail::sobol_point(1)[d], 0x80000000u);
  EXPECT_EQ(detail::sobol_point(2)[0], 0x40000000u);
  EXPECT_EQ(detail::sobol_point(2)[1], 0xC0000000u);
  EXPECT_EQ(detail::sobol_point(3)[0], 0xC0000000u);
  EXPECT_EQ(detail::sobol_point(3)[1], 0x40000000u);
  expect_stratified(10, nullptr);
  const detail::SobolScramble scramble(12345, 0);
  expect_stratified(10, &scramble.seeds);
  // Two-dimensional nets of the first dimensions: 2^8 points, one in each of the 16 x 16
  // squares of dimensions 0 and 1 (t = 0 for that pair), scrambled too.
  std::set<std::uint32_t> squares;
  for (std::uint32_t i = 0; i < 256; ++i) {
    const auto p = detail::sobol_point(i);
    const std::uint32_t x = detail::owen_scramble(p[0], scramble.seeds[0]);
    const std::uint32_t y = detail::owen_scramble(p[1], scramble.seeds[1]);
    squares.insert((x >> 28) * 16 + (y >> 28));
  }
  EXPECT_EQ(squares.size(), 256u);
}

TEST(Sobol, ScrambledCoordinatesAreUniform) {
  // Over independent scramble seeds one point's coordinate is uniform: the counts in 16 bins
  // of 16000 seeds pass a chi-square test with a margin of about 5 sigma (15 dof: mean 15,
  // sd 5.5; the bound 45 is exceeded with probability < 1e-4).
  for (const std::uint32_t index : {0u, 1u, 7u, 1000u}) {
    std::array<int, 16> counts{};
    const int n = 16000;
    for (int s = 0; s < n; ++s) {
      const detail::SobolScramble scramble(std::uint64_t(s) * 7919 + 1, 3);
      counts[detail::owen_scramble(detail::sobol_point(index)[5], scramble.seeds[5]) >> 28]++;
    }
    double chi2 = 0.0;
    for (const int c : counts) chi2 += (c - n / 16.0) * (c - n / 16.0) / (n / 16.0);
    EXPECT_LT(chi2, 45.0) << "point " << index;
  }
}

TEST(Sobol, PathRngDrawsThePointThenPhilox) {
  const detail::SobolScramble scramble(99, 1);
  PathRng rng = scramble.path_rng(99, 5, 1);
  const auto p = detail::sobol_point(5);
  for (unsigned d = 0; d < kSobolDims; ++d) {
    EXPECT_EQ(rng.next_u32(), detail::owen_scramble(p[d], scramble.seeds[d])) << d;
  }
  PathRng philox(99, 5, 1);  // then the path's own Philox stream from its start
  for (int i = 0; i < 8; ++i) EXPECT_EQ(rng.next_u32(), philox.next_u32());
}

TEST(Replicates, StudentTInterval) {
  const std::array<double, 4> v{1.0, 2.0, 3.0, 4.0};
  const Estimate e = detail::replicate_interval(v, z_for_confidence(0.95), 10);
  EXPECT_DOUBLE_EQ(e.mean, 2.5);
  const double sigma = std::sqrt(5.0 / 3.0 / 4.0);
  EXPECT_NEAR(e.sigma, sigma, 1e-12);
  EXPECT_NEAR(e.ci_high - e.mean, 3.182446305 * sigma, 1e-8);  // t(0.975, 3)
  EXPECT_NEAR(e.mean - e.ci_low, 3.182446305 * sigma, 1e-8);
  EXPECT_EQ(e.hits, 10u);
  EXPECT_NEAR(detail::student_t_for_z(z_for_confidence(0.95), 7), 2.364624252, 1e-8);
  EXPECT_EQ(detail::student_t_for_z(0.0, 7), 0.0);
  EXPECT_TRUE(std::isfinite(detail::student_t_for_z(40.0, 7)));  // a tail below any double
  EXPECT_GT(detail::student_t_for_z(40.0, 7), detail::student_t_for_z(8.0, 7));
  const std::array<double, 3> spread{0.1, 0.0, 5.0};  // clamped at 0, holds its mean
  const Estimate c = detail::replicate_interval(spread, 1.96, 3);
  EXPECT_EQ(c.ci_low, 0.0);
  EXPECT_GE(c.ci_high, c.mean);
  const std::array<double, 1> one{1.0};
  EXPECT_THROW(detail::replicate_interval(one, 1.96, 0), std::invalid_argument);
}

Scene point_over_plane() {
  Scene s;
  s.luminaires.push_back(point_light({0.3, -0.2, 2.0}, 5000.0));
  s.targets.push_back(grid("floor", {-2, -2, 0}, {4, 0, 0}, {0, 4, 0}, 4, 4));
  return s;
}

Scene with_requirement(Scene s) {
  s.targets[0].requirements.emin_lux = 50;  // something for a decide run to decide
  return s;
}

// Photons alone (qmc_next_event_test.cpp: with next-event estimation).
SolveOptions sobol(std::uint64_t photons, std::uint64_t seed, std::uint32_t replicates = 8) {
  return sobol_options(photons, seed, "off", replicates);
}

// InputError whose message names `field` and the sampler.
template <class F>
void expect_refused(F&& f, const std::string& field) {
  try {
    f();
    ADD_FAILURE() << "not refused: " << field;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(field), std::string::npos) << what;
    EXPECT_NE(what.find("sobol"), std::string::npos) << what;
  }
}

// Two processes, as MPI would give them (rank 0 of 2; nothing is ever summed: it is refused).
class TwoRanks final : public ProcessGroup {
 public:
  int rank() const override { return 0; }
  int size() const override { return 2; }
  void sum(std::span<std::uint64_t>) override {}
  void broadcast(std::span<std::uint64_t>) override {}
};

TEST(QuasiRandomRun, RefusesWhatItCannotDo) {
  Simulation sim(point_over_plane(), {"embree"});
  SolveOptions o = sobol(80'000, 1);
  o.target_accuracy = 0.05;
  expect_refused([&] { sim.run(o); }, "target_accuracy");
  o = sobol(80'000, 1);
  o.decide = true;
  Simulation judged(with_requirement(point_over_plane()), {"embree"});
  expect_refused([&] { judged.run(o); }, "decide");
  o = sobol(80'000, 1);
  o.max_seconds = 10.0;
  expect_refused([&] { sim.run(o); }, "max_seconds");
  o = sobol(80'000, 1);
  o.contributions = true;
  expect_refused([&] { sim.run(o); }, "contributions");
  o = sobol(80'000, 1);
  o.checkpoints = {10'000};
  expect_refused([&] { sim.run(o); }, "sampler");
  expect_refused([&] { sim.run(sobol(80'001, 1)); }, "photons");
  expect_refused([&] { sim.run(sobol(4, 1)); }, "photons");
  expect_refused([&] { sim.refine(sobol(80'000, 1)); }, "sampler");
  o = sobol(80'000, 1);
  o.processes = std::make_shared<TwoRanks>();
  expect_refused([&] { sim.run(o); }, "sampler");
  o = sobol(80'000, 1);
  o.sampler = "halton";
  EXPECT_THROW(sim.run(o), InputError);
  EXPECT_THROW(sim.run(sobol(80'000, 1, 1)), InputError);  // replicates in [2, 1024]
  // Every backend built traces quasi-random photons (Vulkan: Shaders/sobol.glsl, compared
  // path for path with Embree in Tests/native/vulkan/quasi_random_test.cpp).
  for (const BackendInfo& b : lightsolver::backends()) {
    if (b.name == "embree" || b.name == "auto") continue;
    try {
      Simulation other(point_over_plane(), {b.name});
      EXPECT_EQ(other.run(sobol(80'000, 1)).sampler, "sobol") << b.name;
    } catch (const std::exception& e) {  // a backend built but not usable here
      std::cout << b.name << ": " << e.what() << "\n";
    }
  }
  // A refused run leaves the simulation usable, random and sobol alike.
  EXPECT_EQ(sim.run(sobol(80'000, 1)).photons, 80'000u);
  SolveOptions random;
  random.photons = 80'000;
  EXPECT_EQ(sim.run(random).sampler, "random");
}

TEST(QuasiRandomRun, DeterministicAndEvenlySplit) {
  Simulation sim(point_over_plane(), {"embree"});
  const Results a = sim.run(sobol(160'000, 5)), b = sim.run(sobol(160'000, 5));
  const Results c = sim.run(sobol(160'000, 6));
  EXPECT_EQ(a.sampler, "sobol");
  EXPECT_EQ(a.replicates, 8u);
  EXPECT_EQ(a.photons, 160'000u);
  ASSERT_EQ(a.groups.size(), 1u);
  EXPECT_EQ(a.groups[0].photons, 160'000u);
  for (std::size_t k = 0; k < a.targets[0].cells.size(); ++k) {
    EXPECT_EQ(a.targets[0].cells[k].mean, b.targets[0].cells[k].mean);
    EXPECT_EQ(a.targets[0].cells[k].ci_high, b.targets[0].cells[k].ci_high);
  }
  EXPECT_NE(a.targets[0].cells[5].mean, c.targets[0].cells[5].mean);  // another seed
}

// |mean - exact| within the t interval at a Bonferroni-corrected confidence over `cells`
// estimates (each a fixed seed: a failure is a bias, not bad luck at 1e-4 overall).
void expect_unbiased(const Estimate& e, double exact, std::uint32_t replicates, int cells,
                     double max_rel_sigma, const std::string& what) {
  const double t = detail::student_t_for_z(z_for_alpha(1e-4 / cells), replicates - 1);
  EXPECT_LE(std::abs(e.mean - exact), t * e.sigma) << what << ": " << e.mean << " vs " << exact;
  EXPECT_LT(e.sigma, max_rel_sigma * exact) << what << ": too noisy";
  EXPECT_LE(e.ci_low, e.mean);
  EXPECT_GE(e.ci_high, e.mean);
}

TEST(QuasiRandomRun, InverseSquareLawOverAPlane) {
  // σ below 0.4 % of each cell: independent photons give 0.7 % (the brightest cell) and more at
  // this count (binomial, from the cells' solid angles), so the test
  // also fails a sampler that is not quasi-random.
  const Scene s = point_over_plane();
  const Results r = Simulation(s, {"embree"}).run(sobol(16 * 65'536, 11, 16));
  const dvec3 src(0.3, -0.2, 2.0), c(-2, -2, 0), e1(4, 0, 0), e2(0, 4, 0);
  for (unsigned iv = 0; iv < 4; ++iv) {
    for (unsigned iu = 0; iu < 4; ++iu) {
      const dvec3 cc = c + (iu / 4.0) * e1 + (iv / 4.0) * e2;
      const double exact = point_source_patch_lux(src, 5000.0, cc, e1 / 4.0, e2 / 4.0);
      expect_unbiased(r.targets[0].cells[iv * 4 + iu], exact, 16, 16, 4e-3,
                      "cell " + std::to_string(iu) + "," + std::to_string(iv));
    }
  }
}

TEST(QuasiRandomRun, IntegratingSphere) {
  // A closed diffuse box with a point source inside: the mean illuminance of its surfaces is
  // Φ / (A (1 - ρ)) whatever the source's place (every photon's expected deposits 1/(1 - ρ)).
  for (const double rho : {0.5, 0.8}) {
    Scene s;
    add_material(s, "grey", Material::Type::Diffuse, rho);
    s.meshes.push_back(room_mesh("box", 0, dvec3(0), dvec3(4, 4, 3), 2));
    s.targets.push_back(surface("box", 0));
    s.luminaires.push_back(point_light({2, 2, 2.9}, 10'000.0));
    const Results r = Simulation(s, {"embree"}).run(sobol(8 * 32'768, 3));
    const double area = 2 * (16.0 + 12.0 + 12.0);
    expect_unbiased(r.targets[0].estimate, 10'000.0 / (area * (1.0 - rho)), 8, 2, 0.01,
                    "rho " + std::to_string(rho));
  }
}

TEST(QuasiRandomRun, GroupsAddWithinEachReplicate) {
  // Two groups (a point source each, 4:1 in flux): each replicate's estimate sums its groups,
  // every group's photons are a multiple of the replicates, and the sum is unbiased.
  Scene s;
  const dvec3 a(-0.5, 0.2, 1.5), b(0.8, -0.4, 2.5), c(-1, -1, 0), e1(2, 0, 0), e2(0, 2, 0);
  s.luminaires.push_back(named(point_light(a, 4000.0), "a", "left"));
  s.luminaires.push_back(named(point_light(b, 1000.0), "b", "right"));
  s.targets.push_back(grid("floor", c, e1, e2, 2, 2));
  // A grid facing away from both sources: no photon reaches it.
  s.targets.push_back(grid("dark", {-1, -1, 0.5}, {0, 2, 0}, {2, 0, 0}, 1, 1));
  const Results r = Simulation(s, {"embree"}).run(sobol(8 * 65'536, 21));
  ASSERT_EQ(r.groups.size(), 2u);
  EXPECT_EQ(r.groups[0].photons + r.groups[1].photons, 8u * 65'536u);
  EXPECT_EQ(r.groups[0].photons % 8, 0u);
  for (unsigned k = 0; k < 4; ++k) {
    const dvec3 cc = c + double(k % 2) * 0.5 * e1 + double(k / 2) * 0.5 * e2;
    const double exact = point_source_patch_lux(a, 4000.0, cc, 0.5 * e1, 0.5 * e2) +
                         point_source_patch_lux(b, 1000.0, cc, 0.5 * e1, 0.5 * e2);
    expect_unbiased(r.targets[0].cells[k], exact, 8, 4, 0.01, "cell " + std::to_string(k));
  }
  // Zero hits in every replicate: mean 0, and an upper end above 0 (the pooled zero-hit
  // Wilson bound), not the point [0, 0].
  const Estimate& dark = r.targets[1].estimate;
  EXPECT_EQ(dark.hits, 0u);
  EXPECT_EQ(dark.mean, 0.0);
  EXPECT_GT(dark.ci_high, 0.0);
}

}  // namespace
}  // namespace lightsolver::test
