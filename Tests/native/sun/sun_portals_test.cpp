// The sun through the sky's portals (docs/daylight.md, "The sun through portals"): its flux is
// Σ E·A·(n·d)·τ(θ)·f over the portals facing it, one portal chosen per photon by flux; each
// portal's beam lands where it should with E cos θ' τ f; an outside plate blocks a portal's beam
// (the portals' outside test applies to the sun); scene-file errors name their field. Traced on
// both backends.
#include <gtest/gtest.h>

#include <cmath>

#include "daylight/sky_glazing.hpp"
#include "lightsolver/angles.hpp"
#include "lightsolver/scene_io.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

constexpr double kPortalLux = 100'000.0;

// The beam 30° from the zenith, travelling toward −x; three 1 m² portals: a double-glazed roof
// opening (n = −z), an open window facing the sun (n = −x, n·d = 1/2) and one facing away.
Scene three_portals() {
  Scene s;
  add_material(s, "black", Material::Type::Diffuse, 0.0);
  s.meshes.push_back(quad_mesh("ground", 0, {-50, -50, -5}, {100, 0, 0}, {0, 100, 0}));
  Luminaire l;
  l.name = "sun";
  l.type = Luminaire::Type::Sun;
  l.direction = glm::normalize(dvec3(-std::sin(30 * kDeg), 0, -std::cos(30 * kDeg)));
  l.illuminance_lx = kPortalLux;
  l.sky.portals.push_back({{-1, -1, 3}, {0, 1, 0}, {1, 0, 0}, GlazingDefinition{0.7, 2, 0.8, 0.9}});
  l.sky.portals.push_back({{6, -1, 0.5}, {0, 0, 1}, {0, 1, 0}, std::nullopt});
  l.sky.portals.push_back({{-6, -1, 0.5}, {0, 1, 0}, {0, 0, 1}, std::nullopt});
  s.luminaires.push_back(l);
  // Where each beam lands on the plane z = 0.2: the roof's at x in [−2.62, −1.62], the window's
  // at x in [5.25, 5.83] (both y in [−1, 0]); 0.4 m probes well inside, the disc's blur ~2 cm.
  s.targets.push_back(grid("under the roof", {-2.3, -0.7, 0.2}, {0.4, 0, 0}, {0, 0.4, 0}, 1, 1));
  s.targets.push_back(grid("under the window", {5.35, -0.7, 0.2}, {0.4, 0, 0}, {0, 0.4, 0}, 1, 1));
  return s;
}

double roof_factor() {  // τ(30°) × frame × maintenance of the roof's glazing
  const daylight::Glazing g{0.7, 2, 0.8, 0.9};
  return g.tau(std::cos(30 * kDeg)) * g.factor();
}

class SunPortals : public ::testing::TestWithParam<std::string> {};

TEST_P(SunPortals, FluxAndEachPortalsBeam) {
  const double cos30 = std::cos(30 * kDeg);
  Scene s = three_portals();
  validate(s);
  EXPECT_NEAR(s.luminaires[0].flux_lm, kPortalLux * (cos30 * roof_factor() + 0.5),
              1e-9 * kPortalLux);
  const Results r = run_on_backend(GetParam(), s, 400'000, 11);
  expect_in_ci(r.targets[0].estimate, kPortalLux * cos30 * roof_factor(), 0.04, "under the roof");
  expect_in_ci(r.targets[1].estimate, kPortalLux * cos30, 0.03, "under the window");
  EXPECT_EQ(r.openings.photons, r.photons);
  EXPECT_EQ(r.openings.blocked, 0u);
  std::printf("[ sun      ] roof %.6g (exact %.6g), window %.6g (exact %.6g)\n",
              r.targets[0].estimate.mean, kPortalLux * cos30 * roof_factor(),
              r.targets[1].estimate.mean, kPortalLux * cos30);
}

// A plate outside the window, between it and the sun, blocks the window's beam: its probe reads
// 0 and the blocked photons are the window's share of the flux; the roof's beam is untouched.
TEST_P(SunPortals, AnOutsidePlateBlocksAPortalsBeam) {
  Scene s = three_portals();
  s.meshes.push_back(quad_mesh("awning", 0, {6.05, -2, 1.7}, {2, 0, 0}, {0, 3, 0}));
  const double cos30 = std::cos(30 * kDeg);
  const Results r = run_on_backend(GetParam(), s, 400'000, 12);
  EXPECT_EQ(r.targets[1].estimate.hits, 0u);
  expect_in_ci(r.targets[0].estimate, kPortalLux * cos30 * roof_factor(), 0.04, "under the roof");
  const double share = 0.5 / (cos30 * roof_factor() + 0.5);  // the window's part of the flux
  const double n = double(r.openings.photons), blocked = double(r.openings.blocked);
  EXPECT_NEAR(blocked / n, share, 5.0 * std::sqrt(share * (1 - share) / n));
  EXPECT_EQ(r.openings.glass, 0u);
}

INSTANTIATE_TEST_SUITE_P(Backends, SunPortals, ::testing::ValuesIn(backends()));

std::string portal_scene(const std::string& sun_keys) {
  return R"({"format": "lightsolver.scene/1",
    "materials": {"black": {"type": "diffuse", "reflectance": 0}},
    "meshes": [{"name": "floor", "material": "black",
                "vertices": [[-9,-9,0],[9,-9,0],[9,9,0],[-9,9,0]], "triangles": [[0,1,2],[0,2,3]]}],
    "luminaires": [{"name": "sun", "type": "sun", "illuminance_lx": 100000, )" +
         sun_keys + R"(}],
    "targets": [{"name": "floor", "type": "surface", "mesh": "floor"}]})";
}

std::string portal_error_of(const std::string& keys) {
  try {
    Scene s = scene_from_json(portal_scene(keys), "sun.json", ".");
    validate(s);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SunPortalsScene, ReadsThePortalsAndNamesErrors) {
  const std::string roof = R"({"corner": [0,0,3], "edge1": [0,2,0], "edge2": [1,0,0]})";
  Scene s =
      scene_from_json(portal_scene(R"("direction": [0, 0, -1], "portals": [)" + roof +
                                   R"(, {"corner": [0,0,3], "edge1": [1,0,0], "edge2": [0,1,0]}])"),
                      "sun.json", ".");
  validate(s);
  EXPECT_NEAR(s.luminaires[0].flux_lm, 2e5, 1e-6);  // the second faces away (n = +z)
  EXPECT_NE(
      portal_error_of(R"("direction": [0,0,-1], "corner": [0,0,3], "portals": [)" + roof + "]")
          .find("luminaires[0].corner: a sun through `portals` takes no opening"),
      std::string::npos);
  EXPECT_NE(
      portal_error_of(R"("direction": [0,0,-1], "portals": [])").find("luminaires[0].portals:"),
      std::string::npos);
  EXPECT_NE(
      portal_error_of(
          R"("direction": [0,0,-1], "portals": [{"corner": [0,0,3], "edge1": [0,2,0], "edge2": [1,0,0], "glazing": {"transmittance": 1.5}}])")
          .find("luminaires[0].portals[0].glazing.transmittance"),
      std::string::npos);
  // A disc straddling the portal's plane is traced (sun_straddling_test.cpp), not refused.
  EXPECT_EQ(portal_error_of(R"("direction": [1,0,-0.001], "portals": [)" + roof + "]"),
            "(no error)");
  EXPECT_NE(portal_error_of(
                R"("direction": [0,0,-1], "portals": [{"corner": [0,0,3], "edge1": [0,2,0]}])")
                .find("edge2"),
            std::string::npos);
}

}  // namespace
}  // namespace lightsolver::test
