// Quasi-random photons (sampler "sobol") on the Vulkan backend: Shaders/sobol.glsl gives each
// path the CPU's scrambled Sobol' point, so for one seed the two backends trace the same paths,
// replicate by replicate, as they do with Philox alone (backend_test.cpp).
#include <string>

#include "benchmarks/bench_scenes.hpp"
#include "lightsolver/scene_io.hpp"
#include "lightsolver/solver.hpp"
#include "vulkan_test_util.hpp"

namespace lightsolver::test {
namespace {

Results run(const Scene& s, const std::string& backend, const std::string& sampler,
            std::uint64_t photons, const std::string& next_event = "off") {
  SolveOptions o;
  o.photons = photons;
  o.seed = 7;
  o.backend = backend;
  o.sampler = sampler;
  o.replicates = 8;
  o.next_event = next_event;
  return solve(s, o);
}

// Same seed: the same points, scrambles and Philox tails, so the counts agree to far better
// than their noise (a last-bit difference in sin/cos/sqrt between the GPU and libm may tip a
// rare decision). Random photons of the same seed trace other paths: their counts differ by
// their noise, which the tolerance is far below (so a backend ignoring the sampler fails).
TEST_F(VulkanTest, SobolTracesTheSamePathsAsEmbree) {
  for (const Scene& s :
       {bench::cornell_box(), load_scene(LIGHTSOLVER_EXAMPLES_DIR "/room/room.json")}) {
    const Results e = run(s, "embree", "sobol", 8 * 1024), v = run(s, "vulkan", "sobol", 8 * 1024);
    const Results random = run(s, "embree", "random", 8 * 1024);
    ASSERT_EQ(v.backend, "vulkan");
    EXPECT_NEAR(double(v.ray_segments), double(e.ray_segments), 1e-3 * double(e.ray_segments));
    std::size_t differ_from_random = 0;
    for (std::size_t t = 0; t < e.targets.size(); ++t) {
      const double he = double(e.targets[t].estimate.hits);
      EXPECT_NEAR(double(v.targets[t].estimate.hits), he, 1e-3 * he + 2) << e.targets[t].name;
      EXPECT_NEAR(v.targets[t].estimate.mean, e.targets[t].estimate.mean,
                  1e-3 * e.targets[t].estimate.mean + 1e-9)
          << e.targets[t].name;
      const double hr = double(random.targets[t].estimate.hits);
      differ_from_random += std::abs(hr - he) > 1e-3 * he + 2 ? 1 : 0;
    }
    EXPECT_GT(differ_from_random, 0u) << "sobol and random traced the same paths";
  }
}

// Specular paths crossing 80 bins (beyond the shader's 16 register slots: replayed): each
// replicate's tallies reach its own block, so the replicates' spread (sigma) is Embree's too,
// up to a path a last bit tips (one path of one replicate moves a sigma by about 2 %).
TEST_F(VulkanTest, SobolReplicatesKeepTheirTalliesOnMirrors) {
  Scene s = mirror_slab_with_grids();
  s.luminaires.push_back(point_light({0.1, 0.2, 2.05}, 1000));
  validate(s);
  const Results e = run(s, "embree", "sobol", 8 * 1024), v = run(s, "vulkan", "sobol", 8 * 1024);
  for (std::size_t t = 0; t < e.targets.size(); ++t) {
    const Estimate &a = e.targets[t].estimate, &b = v.targets[t].estimate;
    EXPECT_NEAR(double(b.hits), double(a.hits), 1e-3 * double(a.hits) + 2) << e.targets[t].name;
    EXPECT_NEAR(b.sigma, a.sigma, 0.05 * a.sigma) << e.targets[t].name;
  }
}

// With next-event estimation the replicates share a direct part traced by the backend's shadow
// rays: the two backends' estimates agree as closely as their paths do.
TEST_F(VulkanTest, SobolWithNextEventAgreesWithEmbree) {
  const Scene s = load_scene(LIGHTSOLVER_EXAMPLES_DIR "/room/room.json");
  const Results e = run(s, "embree", "sobol", 8 * 1024, "on");
  const Results v = run(s, "vulkan", "sobol", 8 * 1024, "on");
  for (std::size_t t = 0; t < e.targets.size(); ++t) {
    const Estimate &a = e.targets[t].estimate, &b = v.targets[t].estimate;
    EXPECT_NEAR(b.mean, a.mean, 2e-3 * a.mean + 1e-9) << e.targets[t].name;
    EXPECT_NEAR(b.sigma, a.sigma, 0.05 * a.sigma + 1e-9) << e.targets[t].name;
  }
}

}  // namespace
}  // namespace lightsolver::test
