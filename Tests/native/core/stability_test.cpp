// Hard cases that break naive tracers: grazing light, georeferenced coordinates with many
// bounces, 1 mm glass, lossless rooms, a grid lying on a surface, tiny triangles.
#include <gtest/gtest.h>

#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

class Stability : public ::testing::TestWithParam<std::string> {
 protected:
  Results run(Scene s, std::uint64_t photons, double confidence = kCheckConfidence) {
    return run_on_backend(GetParam(), std::move(s), photons, 11, confidence);
  }
};

TEST_P(Stability, GrazingSunlightFollowsCosine) {
  // 88 degrees from the normal: E = E_normal cos(88 deg), 3.5 % of the normal value.
  const double t = glm::radians(88.0);
  Scene s;
  Luminaire sun;
  sun.name = "sun";
  sun.type = Luminaire::Type::Directional;
  sun.direction = {std::sin(t), 0, -std::cos(t)};
  sun.corner = {-10, -1, 0.5};
  sun.edge1 = {0, 2, 0};
  sun.edge2 = {0, 0, 0.6};  // a vertical window-like source facing the beam
  sun.illuminance_lx = 100'000.0;
  s.luminaires.push_back(sun);
  // The beam descends 0.6 m over 17 m: it lands on x in [3.7, 17.2] at z = 0.
  s.targets.push_back(grid("floor", {6, -0.5, 0}, {6, 0, 0}, {0, 1, 0}, 1, 1));
  const Results r = run(s, 1'000'000);
  expect_in_ci(r.targets[0].estimate, 100'000.0 * std::cos(t), 0.02, "grazing");
}

TEST_P(Stability, ReflectiveCubeFarFromOriginMatchesCie171) {
  for (const double rho : {0.9, 0.99}) {
    Scene s;
    add_material(s, "white", Material::Type::Diffuse, rho);
    const dvec3 o(5.2e6, 1.7e6, 420.0);  // georeferenced: float spacing here is 0.5 m
    // 43 200 triangles: their hit records fill more than one 2 MiB huge page.
    s.meshes.push_back(room_mesh("cube", 0, o, o + dvec3(4), 60));
    s.targets.push_back(surface("cube", 0));
    s.luminaires.push_back(point_light(o + dvec3(2), 10'000.0));
    s.settings.max_bounces = 100'000;  // 0.99^1000 = 4e-5 of paths would still be alive at 1000
    const Results r = run(s, rho > 0.95 ? 40'000 : 200'000);
    expect_in_ci(r.targets[0].estimate, 10'000.0 / (96.0 * (1.0 - rho)), 0.03,
                 "rho " + std::to_string(rho));
    EXPECT_EQ(r.capped_paths, 0u);
  }
}

TEST_P(Stability, MillimetreGlassKeepsFresnelTransmittance) {
  Scene s;
  Material glass;
  glass.name = "glass";
  glass.type = Material::Type::Glass;
  glass.ior = 1.52;
  s.materials.push_back(glass);
  s.meshes.push_back(solid_box_mesh("slab", 0, {-1, -1, 1}, {1, 1, 1.001}));
  Luminaire sun;
  sun.name = "beam";
  sun.type = Luminaire::Type::Directional;
  sun.direction = {0.3, 0.1, -1};
  sun.corner = {-0.3, -0.3, 2};
  sun.edge1 = {0.6, 0, 0};
  sun.edge2 = {0, 0.6, 0};
  sun.illuminance_lx = 1000.0;
  s.luminaires.push_back(sun);
  const dvec3 d = glm::normalize(sun.direction);
  // Footprint at z = 0.5 is the source square shifted by 1.5 d_xy / |d_z|; probe its middle.
  const dvec3 centre = dvec3(0, 0, 2) + (1.5 / -d.z) * d;
  s.targets.push_back(grid("below", centre - dvec3(0.1, 0.1, 0), {0.2, 0, 0}, {0, 0.2, 0}, 1, 1));
  const double cos_i = -d.z, n = 1.52;
  const double sin_t = std::sqrt(1 - cos_i * cos_i) / n, cos_t = std::sqrt(1 - sin_t * sin_t);
  const double rs = std::pow((cos_i - n * cos_t) / (cos_i + n * cos_t), 2);
  const double rp = std::pow((n * cos_i - cos_t) / (n * cos_i + cos_t), 2);
  const double T = 0.5 * ((1 - rs) / (1 + rs) + (1 - rp) / (1 + rp));
  const Results r = run(s, 1'000'000);
  expect_in_ci(r.targets[0].estimate, 1000.0 * cos_i * T, 0.02, "1 mm slab");
}

TEST_P(Stability, LosslessMirrorBoxTerminatesWithABiasWarning) {
  Scene s;
  add_material(s, "mirror", Material::Type::Mirror, 1.0);
  s.meshes.push_back(room_mesh("box", 0, dvec3(0), dvec3(1), 1));
  s.targets.push_back(surface("box", 0));
  s.luminaires.push_back(point_light({0.31, 0.52, 0.43}, 100.0));
  s.settings.max_bounces = 200;
  const Results r = run(s, 2'000);
  EXPECT_EQ(r.capped_paths, 2'000u);  // no photon is ever absorbed: every one hits the cap
  EXPECT_EQ(r.targets[0].estimate.hits, 2'000u * 201u);
  bool warned = false;
  for (const auto& w : r.warnings) warned |= w.find("max_bounces") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST_P(Stability, GridOnAFloorCountsWhatTheFloorReceives) {
  Scene s;
  add_material(s, "black", Material::Type::Diffuse, 0.0);
  s.meshes.push_back(quad_mesh("floor", 0, {-2, -2, 0}, {4, 0, 0}, {0, 4, 0}));
  s.targets.push_back(surface("floor", 0));
  s.targets.push_back(grid("grid on floor", {-2, -2, 0}, {4, 0, 0}, {0, 4, 0}, 1, 1));
  s.luminaires.push_back(point_light({0.3, 0.1, 1.5}, 1000.0));
  const Results r = run(s, 1'000'000);
  const auto floor_hits = r.targets[0].estimate.hits, grid_hits = r.targets[1].estimate.hits;
  // Only a photon landing within float error of the floor's edge could be counted by one and
  // not the other.
  EXPECT_NEAR(double(grid_hits), double(floor_hits), 1e-4 * double(floor_hits));
}

TEST_P(Stability, FloorOfTinyTrianglesIsWatertight) {
  Scene s;
  add_material(s, "black", Material::Type::Diffuse, 0.0);
  Mesh room = room_mesh("room", 0, dvec3(0), dvec3(0.05, 0.05, 0.05), 40);  // 1.25 mm quads
  s.meshes.push_back(room);
  s.targets.push_back(surface("room", 0));
  s.luminaires.push_back(point_light({0.0251, 0.0249, 0.013}, 1.0));
  const Results r = run(s, 300'000);
  EXPECT_EQ(r.targets[0].estimate.hits, r.photons);
}

INSTANTIATE_TEST_SUITE_P(Backends, Stability, ::testing::ValuesIn(backends()));

}  // namespace
}  // namespace lightsolver::test
