// Coverage of the quasi-random runs' intervals (docs/statistics.md, "Quasi-random photons"):
// over 256 fixed seeds, the share of 95 % per-cell intervals (Student-t over 8 replicates, with
// next-event estimation's direct part added where it is on) that hold the exact value (or a
// long reference's) is 95 % within binomial limits at k = 4.5 sigma. Cells of one run
// share its replicates, so their misses may be correlated: the limit uses the larger of the
// binomial variance and the variance the per-seed miss counts show (a design effect), so a
// correlation cannot pass off as coverage.
#include <gtest/gtest.h>

#include <cmath>

#include "lightsolver/simulation.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

constexpr int kSeeds = 256;
constexpr double kConfidence = 0.95, kSigmas = 4.5;

SolveOptions sobol_run(std::uint64_t photons, std::uint64_t seed,
                       const std::string& next_event = "off") {
  SolveOptions o = sobol_options(photons, seed, next_event);
  o.confidence = kConfidence;
  return o;
}

// Misses of each seed's intervals out of `per_seed` trials each: within the limits.
void expect_coverage(const std::vector<int>& misses, int per_seed, const std::string& what) {
  const double n = double(misses.size()) * per_seed, p = 1.0 - kConfidence;
  double total = 0.0, squares = 0.0;
  for (const int m : misses) total += m;
  const double mean = total / double(misses.size());
  for (const int m : misses) squares += (m - mean) * (m - mean);
  const double binomial = n * p * (1.0 - p);
  const double observed = squares / double(misses.size() - 1) * double(misses.size());
  const double sd = std::sqrt(std::max(binomial, observed));
  std::cout << what << ": " << total << " misses of " << n << " (expected " << n * p
            << ", binomial sd " << std::sqrt(binomial) << ", observed sd " << std::sqrt(observed)
            << ")\n";
  EXPECT_LE(std::abs(total - n * p), kSigmas * sd) << what;
}

TEST(QuasiRandomCoverage, PerCellDirectLight) {
  // Inverse-square law per cell: a point source over a 4 x 4 grid (direct light only).
  Scene s;
  const dvec3 src(0.3, -0.2, 2.0), c(-2, -2, 0), e1(4, 0, 0), e2(0, 4, 0);
  s.luminaires.push_back(point_light(src, 5000.0));
  s.targets.push_back(grid("floor", c, e1, e2, 4, 4));
  std::vector<double> exact;
  for (unsigned iv = 0; iv < 4; ++iv) {
    for (unsigned iu = 0; iu < 4; ++iu) {
      const dvec3 cc = c + (iu / 4.0) * e1 + (iv / 4.0) * e2;
      exact.push_back(point_source_patch_lux(src, 5000.0, cc, e1 / 4.0, e2 / 4.0));
    }
  }
  Simulation sim(s, {"embree"});
  std::vector<int> misses;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    const Results r = sim.run(sobol_run(8 * 4096, 1000 + seed));
    int m = 0;
    for (std::size_t k = 0; k < exact.size(); ++k) {
      const Estimate& e = r.targets[0].cells[k];
      if (!(e.ci_low <= exact[k] && exact[k] <= e.ci_high)) ++m;
    }
    misses.push_back(m);
  }
  expect_coverage(misses, int(exact.size()), "direct, 16 cells");
}

// With next-event estimation ("on") the replicates carry the light after a scattering and one
// stratified direct part is added with its own variance: both settings are measured.
class QuasiRandomCoverageNee : public ::testing::TestWithParam<std::string> {};

TEST_P(QuasiRandomCoverageNee, IntegratingSphereWithBounces) {
  // Interreflection through the quasi-random first bounces: the mean illuminance of a closed
  // diffuse box is Φ / (A (1 - ρ)), and the four walls' means share it by symmetry only in
  // sum, so the whole box is the one exact value per run.
  Scene s;
  add_material(s, "grey", Material::Type::Diffuse, 0.6);
  s.meshes.push_back(room_mesh("box", 0, dvec3(0), dvec3(4, 4, 3), 1));
  s.targets.push_back(surface("box", 0));
  s.luminaires.push_back(point_light({1.2, 2.5, 2.6}, 10'000.0));
  const double exact = 10'000.0 / (80.0 * (1.0 - 0.6));
  Simulation sim(s, {"embree"});
  std::vector<int> misses;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    const Estimate e = sim.run(sobol_run(8 * 2048, 5000 + seed, GetParam())).targets[0].estimate;
    misses.push_back(e.ci_low <= exact && exact <= e.ci_high ? 0 : 1);
  }
  expect_coverage(misses, 1, "integrating box, whole surface, next_event " + GetParam());
}

// The box room (4 x 4 x 3 m, every surface rho 0.5, the 100 cd source at (2, 2, 2.9))
// with a black table whose shadow edges cross cells, an 8 x 8 work plane: every cell of 256
// sobol + next-event runs against a random next-event reference of 64 times the photons (its
// variance about 1/64 of a run's: it moves the expected misses by about 0.2 points). Photons
// alone with sobol are measured above (direct light, the integrating box).
TEST(QuasiRandomCoverage, BoxRoomPerCellWithNextEvent) {
  const Scene s = box_room(8, true);
  Simulation sim(s, {"embree"});
  constexpr std::uint64_t kPhotons = 8 * 4096;
  SolveOptions ref = sobol_run(64 * kPhotons, 999, "on");
  ref.sampler = "random";
  const Results reference = sim.run(ref);
  std::vector<int> misses;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    const Results r = sim.run(sobol_run(kPhotons, 7000 + seed, "on"));
    int m = 0;
    for (std::size_t k = 0; k < r.targets[0].cells.size(); ++k) {
      const Estimate& e = r.targets[0].cells[k];
      const double truth = reference.targets[0].cells[k].mean;
      if (!(e.ci_low <= truth && truth <= e.ci_high)) ++m;
    }
    misses.push_back(m);
  }
  expect_coverage(misses, 64, "box room, 64 cells, next_event on");
}

INSTANTIATE_TEST_SUITE_P(NextEvent, QuasiRandomCoverageNee, ::testing::Values("off", "on"));

}  // namespace
}  // namespace lightsolver::test
