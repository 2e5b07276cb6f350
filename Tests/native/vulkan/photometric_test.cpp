// Photometric luminaires on the Vulkan backend: the GLSL sampler consumes the Philox stream in
// the CPU's order (origin, cell, rejection tries), so the same seed gives the same photons.
#include <string>

#include "lightsolver/photometry.hpp"
#include "lightsolver/simulation.hpp"
#include "lightsolver/solver.hpp"
#include "native/core/scene_builders.hpp"
#include "vulkan/gpu_scene.hpp"
#include "vulkan_test_util.hpp"

namespace lightsolver::test {
namespace {

const std::string kLuminaires = std::string(LIGHTSOLVER_SOURCE_DIR) + "/Resources/luminaires/";

Luminaire photometric(const std::string& file, dvec3 position, dvec3 aim, double rotation_deg) {
  Luminaire l;
  l.name = file;
  l.type = Luminaire::Type::Photometric;
  l.position = position;
  l.aim = aim;
  l.rotation_deg = rotation_deg;
  l.file = file;
  load_photometric(l, kLuminaires + file, std::nullopt, "flux_lm");
  return l;
}

// A grey room lit by every sample file at once (round and rectangular openings, types and
// symmetries of all kinds, tilted aims), with a floor grid and the walls as targets.
Scene photometric_room() {
  Scene s;
  add_material(s, "grey", Material::Type::Diffuse, 0.5);
  s.meshes.push_back(room_mesh("room", 0, dvec3(0), dvec3(6, 4, 3), 2));
  s.luminaires.push_back(photometric("downlight.ies", {1.5, 1.0, 2.95}, {0, 0, -1}, 0));
  s.luminaires.push_back(photometric("wallwasher.ldt", {4.5, 1.0, 2.95}, {0.3, 0.2, -1}, 30));
  s.luminaires.push_back(photometric("batwing_panel.ies", {1.5, 3.0, 2.95}, {0, 0, -1}, 90));
  s.luminaires.push_back(photometric("linear_tube.ldt", {4.5, 3.0, 2.5}, {0, 0.5, -1}, 10));
  s.targets.push_back(grid("floor", {0.2, 0.2, 0.01}, {5.6, 0, 0}, {0, 3.6, 0}, 6, 4));
  s.targets.push_back(surface("room", 0));
  validate(s);
  return s;
}

Results run(const Scene& s, const std::string& backend, std::uint64_t photons) {
  SolveOptions o;
  o.photons = photons;
  o.seed = 21;
  o.backend = backend;
  return solve(s, o);
}

void expect_same_hits(const Results& e, const Results& v, const std::string& what) {
  ASSERT_EQ(v.backend, "vulkan");
  EXPECT_NEAR(double(v.ray_segments), double(e.ray_segments), 1e-3 * double(e.ray_segments))
      << what;
  for (std::size_t t = 0; t < e.targets.size(); ++t) {
    const double he = double(e.targets[t].estimate.hits);
    EXPECT_NEAR(double(v.targets[t].estimate.hits), he, 1e-3 * he + 2)
        << what << ": " << e.targets[t].name;
    for (std::size_t c = 0; c < e.targets[t].cells.size(); ++c) {
      const double ce = double(e.targets[t].cells[c].hits);
      EXPECT_NEAR(double(v.targets[t].cells[c].hits), ce, 2e-3 * ce + 2)
          << what << ": " << e.targets[t].name << " cell " << c;
    }
  }
}

using VulkanPhotometricTest = VulkanTest;

// The cell pick on integers equals the CPU's `uniform_double() * total < cdf[c]` on both sides
// of every threshold, for every cell of every sample file.
TEST(PhotometricThresholds, CellPickEqualsTheCpuCompare) {
  for (const char* file :
       {"downlight.ies", "downlight.ldt", "wallwasher.ies", "wallwasher.ldt", "batwing_panel.ies",
        "batwing_panel.ldt", "linear_tube.ies", "linear_tube.ldt"}) {
    const Luminaire l = photometric(file, dvec3(0), {0, 0, -1}, 0);
    const std::vector<double>& cdf = l.sampler->tables().cell_cdf;
    const double total = cdf.back();
    auto below = [&](std::uint64_t k, double c) { return double(k) * 0x1p-53 * total < c; };
    for (double c : cdf) {
      const std::uint64_t t = detail::scaled_cdf_threshold(c, total);
      if (t > 0) EXPECT_TRUE(below(t - 1, c)) << file;
      EXPECT_FALSE(below(t, c)) << file;
    }
  }
}

TEST_F(VulkanPhotometricTest, SameSeedTracesTheSamePhotonsAsEmbree) {
  const Scene s = photometric_room();
  expect_same_hits(run(s, "embree", 40'000), run(s, "vulkan", 40'000), "four files");
}

// Simulation::set_luminaire: a point light becomes photometric (tables uploaded, pipeline
// re-specialised), then another file (tables of another size).
TEST_F(VulkanPhotometricTest, LuminaireChangesUploadTheTables) {
  Scene scene = photometric_room();
  scene.luminaires.resize(1);
  scene.luminaires[0] = point_light({3, 2, 2.5}, 1000);
  Simulation embree(scene, {.backend = "embree"}), vulkan(scene, {.backend = "vulkan"});
  SolveOptions o;
  o.photons = 20'000;
  o.seed = 4;
  for (const Luminaire& l : {photometric("downlight.ldt", {3, 2, 2.9}, {0, 0, -1}, 0),
                             photometric("wallwasher.ies", {3, 2, 2.9}, {1, 0, -1}, 45)}) {
    embree.set_luminaire(0, l);
    vulkan.set_luminaire(0, l);
    expect_same_hits(embree.run(o), vulkan.run(o), l.name);
  }
}

}  // namespace
}  // namespace lightsolver::test
