// The Vulkan backend end to end on lavapipe: it agrees with Embree statistically, traces the same
// paths for the same seed, stays exact when a path touches more bins than the shader keeps in
// registers, fails clearly without a device, and never upsets the validation layer.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "benchmarks/bench_scenes.hpp"
#include "lightsolver/backends.hpp"
#include "lightsolver/scene_io.hpp"
#include "lightsolver/simulation.hpp"
#include "lightsolver/solver.hpp"
#include "vulkan_test_util.hpp"

namespace lightsolver::test {
namespace {

Results run(const Scene& s, const std::string& backend, std::uint64_t photons, std::uint64_t seed) {
  SolveOptions o;
  o.photons = photons;
  o.seed = seed;
  o.backend = backend;
  o.confidence = 0.999;
  // The photon kernels against Embree's, tally for tally: photons alone (next-event estimation
  // on Vulkan has its own tests, next_event_test.cpp).
  o.next_event = "off";
  return solve(s, o);
}

// |a - b| <= z sqrt(sa^2 + sb^2): the two estimates are indistinguishable at that z.
void expect_agree(const Estimate& a, const Estimate& b, double z, const std::string& what) {
  EXPECT_LE(std::abs(a.mean - b.mean), z * std::hypot(a.sigma, b.sigma) + 1e-12)
      << what << ": embree " << a.mean << " ± " << a.sigma << ", vulkan " << b.mean << " ± "
      << b.sigma;
}

// Independent seeds: every target at 99.9 % (z = 3.29); grid cells at 99.9 % jointly (Bonferroni).
void expect_statistical_agreement(const Scene& s, std::uint64_t photons) {
  const Results e = run(s, "embree", photons, 11), v = run(s, "vulkan", photons, 12);
  ASSERT_EQ(v.backend, "vulkan");
  for (std::size_t t = 0; t < e.targets.size(); ++t) {
    const TargetResult &a = e.targets[t], &b = v.targets[t];
    expect_agree(a.estimate, b.estimate, 3.29, a.name);
    if (a.cells.empty()) continue;
    const double z_cells = z_for_confidence(1.0 - 0.001 / double(a.cells.size()));
    for (std::size_t c = 0; c < a.cells.size(); ++c) {
      expect_agree(a.cells[c], b.cells[c], z_cells, a.name + " cell " + std::to_string(c));
    }
  }
}

Scene room_example() { return load_scene(LIGHTSOLVER_EXAMPLES_DIR "/room/room.json"); }

using VulkanBackendTest = VulkanTest;

TEST_F(VulkanBackendTest, AgreesWithEmbreeOnCornellBox) {
  expect_statistical_agreement(bench::cornell_box(), 100'000);
}

TEST_F(VulkanBackendTest, AgreesWithEmbreeOnExampleRoom) {
  expect_statistical_agreement(room_example(), 100'000);
}

// Same seed, same Philox streams, same decisions: the paths coincide except where a last-bit
// difference in sin/cos/sqrt between the GPU and libm tips a decision (rare), so the counts
// agree to far better than their statistical noise.
TEST_F(VulkanBackendTest, SameSeedTracesTheSamePaths) {
  for (const Scene& s : {bench::cornell_box(), room_example()}) {
    const Results e = run(s, "embree", 50'000, 3), v = run(s, "vulkan", 50'000, 3);
    EXPECT_NEAR(double(v.ray_segments), double(e.ray_segments), 1e-3 * double(e.ray_segments));
    for (std::size_t t = 0; t < e.targets.size(); ++t) {
      const double he = double(e.targets[t].estimate.hits);
      EXPECT_NEAR(double(v.targets[t].estimate.hits), he, 1e-3 * he + 2) << e.targets[t].name;
    }
  }
}

// Two parallel mirrors with 40 one-cell grids between them: a path crosses 80 distinct bins many
// times, far beyond the 16 the shader keeps, so the replay passes must restore exact per-path
// counts: S and Q equal Embree's for the same seed.
TEST_F(VulkanBackendTest, PathsTouchingManyBinsKeepExactPerPathCounts) {
  Scene s = mirror_slab_with_grids();
  s.luminaires.push_back(point_light({0.1, 0.2, 2.05}, 1000));
  validate(s);
  const Results e = run(s, "embree", 20'000, 5), v = run(s, "vulkan", 20'000, 5);
  std::uint64_t total = 0;
  for (std::size_t t = 0; t < e.targets.size(); ++t) {
    total += e.targets[t].estimate.hits;
    EXPECT_EQ(v.targets[t].estimate.hits, e.targets[t].estimate.hits) << e.targets[t].name;
    EXPECT_DOUBLE_EQ(v.targets[t].estimate.sigma, e.targets[t].estimate.sigma)
        << e.targets[t].name << ": per-path sums of squares differ";
  }
  // Each crossing deposits on 2 bins (grid and cell): with over 16 crossings per path on average
  // most paths overflow the 16 register slots, so the replay passes really ran.
  EXPECT_GT(total, 20'000u * 16);
}

// Simulation::set_luminaire re-uploads luminaires; a new luminaire type re-specialises the
// pipeline. Same seed on both backends: the same hits after every change.
TEST_F(VulkanBackendTest, LuminaireChangesReachTheDevice) {
  const Scene scene = bench::cornell_box();
  Simulation embree(scene, {.backend = "embree"}), vulkan(scene, {.backend = "vulkan"});
  Luminaire spot;
  spot.name = "spot";
  spot.type = Luminaire::Type::Spot;
  spot.position = {2.75, 2.75, 5.0};
  spot.direction = {0, 0, -1};
  spot.beam_angle_deg = 40;
  spot.field_angle_deg = 70;
  spot.flux_lm = 5000;
  Luminaire moved = scene.luminaires[0];
  moved.corner = {1.0, 1.0, 5.5};
  SolveOptions o;
  o.photons = 20'000;
  o.seed = 9;
  for (const Luminaire& l : {moved, spot}) {
    embree.set_luminaire(0, l);
    vulkan.set_luminaire(0, l);
    const Results e = embree.run(o), v = vulkan.run(o);
    for (std::size_t t = 0; t < e.targets.size(); ++t) {
      const double he = double(e.targets[t].estimate.hits);
      EXPECT_NEAR(double(v.targets[t].estimate.hits), he, 1e-3 * he + 2) << l.name;
    }
  }
}

// Luminaire groups: each group's stream, luminaires and tallies reach the device (push
// constants, luminaires packed group by group). Same seed: each group's part of each target has
// the hits Embree's has; after a luminaire leaves its group the groups (and tallies) grow.
TEST_F(VulkanBackendTest, GroupsTraceTheSameStreamsAsEmbree) {
  Scene s = room_example();
  s.luminaires[0].group = s.luminaires[2].group = "pair";
  Simulation embree(s, {.backend = "embree"}), vulkan(s, {.backend = "vulkan"});
  SolveOptions o;
  o.photons = 40'000;
  o.seed = 5;
  o.contributions = true;
  for (std::size_t groups : {3u, 4u}) {
    const Results e = embree.run(o), v = vulkan.run(o);
    ASSERT_EQ(v.groups.size(), groups);
    for (std::size_t t = 0; t < e.targets.size(); ++t) {
      for (std::size_t g = 0; g < groups; ++g) {
        const double he = double(e.targets[t].contributions[g].estimate.hits);
        EXPECT_NEAR(double(v.targets[t].contributions[g].estimate.hits), he, 1e-3 * he + 2)
            << e.targets[t].name << ", group " << e.groups[g].name;
      }
    }
    Luminaire alone = s.luminaires[2];
    alone.group.clear();
    embree.set_luminaire(2, alone);
    vulkan.set_luminaire(2, alone);
  }
}

TEST_F(VulkanBackendTest, CountsCappedPathsLikeEmbree) {
  Scene s;
  add_material(s, "white", Material::Type::Diffuse, 1.0);
  s.meshes.push_back(room_mesh("box", 0, glm::dvec3(0), glm::dvec3(2), 1));
  s.targets.push_back(surface("box", 0));
  s.luminaires.push_back(point_light({1, 1, 1}, 100));
  s.settings.max_bounces = 5;
  validate(s);
  const Results v = run(s, "vulkan", 2000, 1);
  EXPECT_EQ(v.capped_paths, 2000u);  // nothing is absorbed: every path hits the cap
  EXPECT_EQ(v.targets[0].estimate.hits, 2000u * 6);
  EXPECT_EQ(v.ray_segments, 2000u * 6);
}

// Not a VulkanTest: the one validation error here is deliberate.
TEST(VulkanValidation, LayerIsActiveAndReports) {
  if (!vkw::ContextOptions::validation_requested()) {
    GTEST_SKIP() << "run with LIGHTSOLVER_VULKAN_VALIDATION=1 (ctest sets it)";
  }
  const vkw::Context ctx;
  const std::size_t before = detail::vulkan_validation_message_count();
  VkBufferCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  info.size = 64;
  info.usage = 0;  // invalid on purpose: usage must not be 0
  VkBuffer buffer = VK_NULL_HANDLE;
  if (vkCreateBuffer(ctx.device(), &info, nullptr, &buffer) == VK_SUCCESS) {
    vkDestroyBuffer(ctx.device(), buffer, nullptr);
  }
  EXPECT_GT(detail::vulkan_validation_message_count(), before)
      << "the validation layer is not reporting, so 'no messages' would prove nothing";
  std::fprintf(stderr, "(the validation error above was provoked on purpose)\n");
}

TEST_F(VulkanBackendTest, UnknownBackendNamesTheChoices) {
  try {
    run(bench::cornell_box(), "cuda", 10, 1);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("vulkan"), std::string::npos) << e.what();
  }
}

// The registry finds lavapipe (a CPU device) for "vulkan", while "auto" keeps to Embree unless a
// real GPU is present.
TEST_F(VulkanBackendTest, RegistrySeesTheDeviceAndAutoWantsARealGpu) {
  bool listed = false;
  for (const BackendInfo& b : available_backends()) {
    if (b.name != "vulkan") continue;
    listed = true;
    EXPECT_TRUE(b.gpu);
    EXPECT_TRUE(b.available.value_or(false)) << "no Vulkan device found";
  }
  EXPECT_TRUE(listed);
  EXPECT_EQ(run(bench::cornell_box(), "auto", 1000, 1).backend,
            detail::vulkan_gpu_available() ? "vulkan" : "embree");
}

// Run by ctest with VK_ICD_FILENAMES pointing at a file that does not exist.
TEST(NoDevice, VulkanFailsClearlyAndAutoFallsBackToEmbree) {
  const char* icd = std::getenv("VK_ICD_FILENAMES");
  if (!icd || std::string(icd).find("nonexistent") == std::string::npos) {
    GTEST_SKIP() << "needs VK_ICD_FILENAMES=<nonexistent file> (ctest test vulkan.no_device)";
  }
  EXPECT_FALSE(detail::vulkan_gpu_available());
  for (const BackendInfo& b : available_backends()) {
    EXPECT_EQ(b.available.value_or(true), b.name != "vulkan") << b.name;
  }
  const Scene s = bench::cornell_box();
  try {
    run(s, "vulkan", 10, 1);
    FAIL() << "no error without a Vulkan driver";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("Vulkan"), std::string::npos) << e.what();
  }
  EXPECT_EQ(run(s, "auto", 1000, 1).backend, "embree");
}

}  // namespace
}  // namespace lightsolver::test
