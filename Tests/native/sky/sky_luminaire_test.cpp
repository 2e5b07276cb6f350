// The sky luminaire traced (src/types/luminaire_sky.cpp): unobstructed horizontal illuminance
// under the uniform, overcast and a CIE clear sky without portals; a roof opening in a black room
// against L pi x the configuration factor (portal coplanar with the ceiling's hole); a 1 cm²
// skylight; a side-lit room with and without its portal. Each on every backend (Embree, Vulkan).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "daylight/sky_models.hpp"
#include "lightsolver/angles.hpp"
#include "scene_builders.hpp"
#include "sky_rooms.hpp"

namespace lightsolver::test {
namespace {

Luminaire site_sky(Luminaire l, dvec3 centre, double radius) {
  l.sky.site_centre = centre;
  l.sky.site_radius_m = radius;
  return l;
}

daylight::Sky model_of(const Luminaire& l) {
  daylight::SkySpec spec;
  spec.model = l.sky.model == "uniform"        ? daylight::SkyModel::Uniform
               : l.sky.model == "cie_overcast" ? daylight::SkyModel::CieOvercast
                                               : daylight::SkyModel::CieGeneral;
  spec.cie_type = l.sky.cie_type;
  if (l.sky.sun_direction) {
    const dvec3 s = glm::normalize(*l.sky.sun_direction);
    spec.sun = daylight::Direction{s.x, s.y, s.z};
  }
  spec.normalisation = daylight::SkyNormalisation::ZenithLuminance;
  spec.level = *l.sky.zenith_luminance_cd_m2;
  return daylight::Sky(spec);
}

class SkyTraced : public ::testing::TestWithParam<std::string> {
 protected:
  Results run(Scene s, std::uint64_t photons, std::uint64_t seed = 11) {
    return run_on_backend(GetParam(), std::move(s), photons, seed);
  }
};

// No geometry: a 1 m² grid facing up at the site's centre sees the whole sky above the horizon
// (E = pi L, 7 pi Lz / 9, the CIE clear sky's horizontal integral); the ground's upward light
// crosses it from behind and is not counted.
TEST_P(SkyTraced, UnobstructedHorizontalIlluminanceWithoutPortals) {
  Luminaire clear = sky("cie", 4000.0, 0.2);
  clear.sky.cie_type = 12;
  clear.sky.sun_direction = dvec3(0.3, -0.6, 0.5);
  const std::pair<Luminaire, double> cases[] = {
      {sky("uniform", 1000.0, 0.2), kPi * 1000.0},
      {sky("cie_overcast", 3000.0, 0.2), 7.0 * kPi * 3000.0 / 9.0},
      {clear, model_of(clear).diffuse_horizontal_lx()}};
  for (const auto& [l, exact] : cases) {
    Scene s;
    s.luminaires.push_back(site_sky(l, {0, 0, 0}, 1.0));
    s.targets.push_back(grid("horizontal", {-0.5, -0.5, 0}, {1, 0, 0}, {0, 1, 0}, 1, 1));
    const Results r = run(s, 3'000'000);
    if (l.sky.model == "uniform") {  // pi R^2 x (2 pi L above + 2 pi L_g below), L_g = 0.2 L
      EXPECT_NEAR(r.luminaires[0].emitted_flux_lm, kPi * 2 * kPi * 1200.0,
                  1e-6 * 2.4e3 * kPi * kPi);
    }
    report(r.targets[0].estimate, exact, l.sky.model);
    expect_in_ci(r.targets[0].estimate, exact, 0.03, l.sky.model);
  }
}

// Each of the 15 CIE standard general skies (sun 37° up), traced without portals: a 1 m² grid
// facing up at the site's centre reads the model's horizontal integral L_z ∫ (L/L_z) cos Z dω,
// the quadrature SkyModels.FifteenCieSkiesAgainstAnIndependentQuadrature holds to a midpoint
// rule written in that test within 1e-4 (far inside these intervals: ~2 % at 5e5 photons).
TEST_P(SkyTraced, FifteenCieSkiesUnobstructedHorizontalIlluminance) {
  for (int type = 1; type <= 15; ++type) {
    Luminaire l = sky("cie", 4000.0, 0.2);
    l.sky.cie_type = type;
    l.sky.sun_direction = dvec3(0.3, -0.6, 0.5);
    const double exact = model_of(l).diffuse_horizontal_lx();
    Scene s;
    s.luminaires.push_back(site_sky(l, {0, 0, 0}, 1.0));
    s.targets.push_back(grid("horizontal", {-0.5, -0.5, 0}, {1, 0, 0}, {0, 1, 0}, 1, 1));
    const Results r = run(s, 500'000, 100 + type);
    const std::string name = "CIE sky " + std::to_string(type);
    report(r.targets[0].estimate, exact, name);
    expect_in_ci(r.targets[0].estimate, exact, 0.03, name);
  }
}

// A 1 x 1 m opening in the ceiling (3 m up) of a black 4 x 4 x 3 m room, its portal in the
// ceiling's plane: under the uniform sky a floor probe gets L pi F, F the opening's
// configuration factor (lighting-facts.md), averaged over the probe.
TEST_P(SkyTraced, RoofOpeningInABlackRoomGivesLPiTimesTheConfigurationFactor) {
  Scene s;
  add_material(s, "black", Material::Type::Diffuse, 0.0);
  const Hole h{0.375, 0.625, 0.375, 0.625};  // (1.5, 1.5) to (2.5, 2.5)
  s.meshes.push_back(room_with_hole(0, {0, 0, 0}, {4, 4, 3}, true, h));
  Luminaire l = sky("uniform", 1000.0, 0.0);
  l.sky.portals.push_back({{1.5, 1.5, 3}, {0, 1, 0}, {1, 0, 0}});  // light goes down
  s.luminaires.push_back(l);
  const std::vector<dvec3> probes = {{1.8, 1.8, 0}, {0.4, 0.9, 0}, {3.0, 2.5, 0}};
  for (std::size_t i = 0; i < probes.size(); ++i) {
    s.targets.push_back(grid("p" + std::to_string(i), probes[i], {0.4, 0, 0}, {0, 0.4, 0}, 1, 1));
  }
  const Results r = run(s, 8'000'000);
  EXPECT_NEAR(r.luminaires[0].emitted_flux_lm, kPi * 1000.0, 1e-6 * kPi * 1000.0);
  for (std::size_t i = 0; i < probes.size(); ++i) {
    double sum = 0.0;
    const int n = 60;
    for (int a = 0; a < n; ++a) {
      for (int b = 0; b < n; ++b) {
        const dvec3 p = probes[i] + dvec3(0.4 * (a + 0.5) / n, 0.4 * (b + 0.5) / n, 0);
        sum += parallel_rect_factor(1.5 - p.x, 2.5 - p.x, 1.5 - p.y, 2.5 - p.y, 3.0);
      }
    }
    const double exact = 1000.0 * kPi * sum / (n * n);
    report(r.targets[i].estimate, exact, "roof opening, probe " + std::to_string(i));
    expect_in_ci(r.targets[i].estimate, exact, 0.06, "probe " + std::to_string(i));
  }
}

// A 1 cm² skylight: finite, and the probe below inside its interval (E = L pi F).
TEST_P(SkyTraced, OneSquareCentimetreSkylight) {
  Scene s;
  add_material(s, "black", Material::Type::Diffuse, 0.0);
  s.meshes.push_back(room_with_hole(0, {0, 0, 0}, {4, 4, 3}, true, {0.5, 0.5025, 0.5, 0.5025}));
  Luminaire l = sky("uniform", 1000.0, 0.0);
  l.sky.portals.push_back({{2.0, 2.0, 3}, {0, 0.01, 0}, {0.01, 0, 0}});
  s.luminaires.push_back(l);
  s.targets.push_back(grid("below", {1.5, 1.5, 0}, {1, 0, 0}, {0, 1, 0}, 1, 1));
  const Results r = run(s, 2'000'000);
  double sum = 0.0;
  const int n = 100;
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      const dvec3 p(1.5 + (a + 0.5) / n, 1.5 + (b + 0.5) / n, 0);
      sum += parallel_rect_factor(2.0 - p.x, 2.01 - p.x, 2.0 - p.y, 2.01 - p.y, 3.0);
    }
  }
  const double exact = 1000.0 * kPi * sum / (n * n);
  EXPECT_TRUE(std::isfinite(r.targets[0].estimate.mean));
  report(r.targets[0].estimate, exact, "1 cm2 skylight");
  expect_in_ci(r.targets[0].estimate, exact, 0.02, "1 cm² skylight");
}

// A grey 3 x 3 x 2.5 m room lit by a 1.5 x 1.2 m window in its wall y = 0 under a CIE clear
// sky with ground: through the window's portal and from the site's disc (no portal) the floor
// grid's cells agree within their combined 5 sigma. The room is convex, so no outside surface
// can send light into the window: the portal misses nothing.
TEST_P(SkyTraced, SideLitRoomPortalAndNoPortalAgree) {
  Scene s;
  add_material(s, "grey", Material::Type::Diffuse, 0.5);
  // The wall y = 0 is face(lo, Z, X): s along height, t along x.
  s.meshes.push_back(room_with_hole(0, {0, 0, 0}, {3, 3, 2.5}, false, {0.32, 0.8, 0.25, 0.75}));
  Luminaire l = sky("cie", 5000.0, 0.2);
  l.sky.cie_type = 12;
  l.sky.sun_direction = dvec3(0.2, -0.7, 0.6);  // in front of the window
  s.targets.push_back(grid("floor", {0.25, 0.25, 0.8}, {2.5, 0, 0}, {0, 2.5, 0}, 2, 2));
  Scene with_portal = s, without = s;
  Luminaire through = l;
  through.sky.portals.push_back({{0.75, 0, 0.8}, {0, 0, 1.2}, {1.5, 0, 0}});  // light along +y
  with_portal.luminaires.push_back(through);
  without.luminaires.push_back(site_sky(l, {1.5, 1.5, 1.25}, 2.6));
  const Results a = run(with_portal, 2'000'000);
  const Results b = run(without, 10'000'000, 12);
  report(a.targets[0].estimate, b.targets[0].estimate.mean, "side-lit floor, portal vs disc");
  report(b.targets[0].estimate, a.targets[0].estimate.mean, "side-lit floor, disc vs portal");
  expect_same_within(a.targets[0].estimate, b.targets[0].estimate, "floor");
  for (std::size_t c = 0; c < 4; ++c) {
    expect_same_within(a.targets[0].cells[c], b.targets[0].cells[c], "cell " + std::to_string(c));
  }
  // Both resolved: the comparison means something.
  EXPECT_LT(a.targets[0].estimate.sigma, 0.01 * a.targets[0].estimate.mean);
  EXPECT_LT(b.targets[0].estimate.sigma, 0.05 * b.targets[0].estimate.mean);
}

INSTANTIATE_TEST_SUITE_P(Backends, SkyTraced, ::testing::ValuesIn(backends()));

}  // namespace
}  // namespace lightsolver::test

namespace lightsolver::test {
namespace {

std::string sky_scene(const std::string& sky_keys) {
  return R"({"format": "lightsolver.scene/1",
  "materials": {"white": {"type": "diffuse", "reflectance": 0.7}},
  "meshes": [{"name": "floor", "material": "white",
              "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "triangles": [[0,1,2],[0,2,3]]}],
  "luminaires": [{"name": "sky", "type": "sky", )" +
         sky_keys + R"(}],
  "targets": [{"name": "floor", "type": "surface", "mesh": "floor"}]})";
}

std::string load_error(const std::string& keys) {
  try {
    Scene s = scene_from_json(sky_scene(keys), "scene.json", ".");
    validate(s);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SkyScene, ReadsEveryModelFromTheSceneFile) {
  const std::string portal =
      R"("portals": [{"corner": [0,0,3], "edge1": [0,1,0], "edge2": [1,0,0]}])";
  Scene s = scene_from_json(
      sky_scene(R"("model": "cie", "cie_type": 12, "sun_direction": [0.3, -0.5, 0.6],
                 "diffuse_horizontal_lx": 15000, "ground_reflectance": 0.15, )" +
                portal),
      "scene.json", ".");
  validate(s);
  ASSERT_TRUE(s.luminaires[0].sky_emitter);
  EXPECT_EQ(s.luminaires[0].sky.cie_type, 12);
  // A horizontal 1 m² opening passes the sky's diffuse horizontal illuminance.
  EXPECT_NEAR(s.luminaires[0].flux_lm, 15000.0, 1e-5 * 15000.0);
  Scene perez = scene_from_json(sky_scene(R"("model": "perez", "sun_direction": [0, -0.6, 0.8],
                 "perez": {"diffuse_horizontal": 120, "direct_normal": 500, "units": "W/m2",
                           "day_of_year": 80}, "site": {"centre": [0.5, 0.5, 0], "radius_m": 2})"),
                                "scene.json", ".");
  validate(perez);
  EXPECT_GT(perez.luminaires[0].flux_lm, 0.0);
}

TEST(SkyScene, BadInputIsNamed) {
  const std::string portal =
      R"(, "portals": [{"corner": [0,0,3], "edge1": [0,1,0], "edge2": [1,0,0]}])";
  EXPECT_NE(load_error(R"("model": "cloudy", "zenith_luminance_cd_m2": 1)" + portal)
                .find("luminaires[0].model: must be"),
            std::string::npos);
  EXPECT_NE(load_error(R"("model": "uniform")" + portal)
                .find("give exactly one of zenith_luminance_cd_m2 and diffuse_horizontal_lx"),
            std::string::npos);
  EXPECT_NE(load_error(R"("model": "cie", "cie_type": 16, "zenith_luminance_cd_m2": 1)" + portal)
                .find("luminaires[0].cie_type: 16 is not a CIE standard general sky"),
            std::string::npos);
  EXPECT_NE(load_error(R"("model": "cie", "cie_type": 12, "zenith_luminance_cd_m2": 1)" + portal)
                .find("luminaires[0].sun_direction"),
            std::string::npos);
  EXPECT_NE(
      load_error(R"("model": "uniform", "zenith_luminance_cd_m2": 1, "ground_reflectance": 2)" +
                 portal)
          .find("luminaires[0].ground_reflectance"),
      std::string::npos);
  EXPECT_NE(load_error(R"("model": "uniform", "zenith_luminance_cd_m2": 1)")
                .find("luminaires[0].site: without portals"),
            std::string::npos);
  EXPECT_NE(
      load_error(
          R"("model": "uniform", "zenith_luminance_cd_m2": 1, "portals": [{"corner": [0,0,3], "edge1": [0,1,0], "edge2": [0,2,0]}])")
          .find("luminaires[0]"),
      std::string::npos);
  EXPECT_NE(
      load_error(
          R"("model": "perez", "sun_direction": [0,0,1], "perez": {"diffuse_horizontal": -1, "direct_normal": 0, "units": "lx"})" +
          portal)
          .find("luminaires[0].perez.diffuse_horizontal"),
      std::string::npos);
  EXPECT_NE(load_error(R"("model": "uniform", "zenith_luminance_cd_m2": 1, "colour": 3)" + portal)
                .find("colour"),
            std::string::npos);
}

}  // namespace
}  // namespace lightsolver::test
