// The `sun` luminaire (docs/scene-format.md): the beam through its opening with the solar
// disc's 0.53°, on both backends, against closed forms. A cap of angular radius α of uniform
// radiance L gives E_n = L π sin²α across the beam and L π sin²α cos θ on a plane at θ to it
// (while the cap stays on one side of the plane), so every plane below reads E_n cos θ exactly;
// a plane containing the beam's axis sees half the cap: E_n (α − sin α cos α) / (π sin²α).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "lightsolver/angles.hpp"
#include "lightsolver/rng.hpp"
#include "lightsolver/scene_io.hpp"
#include "model/prepared_scene.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

constexpr double kLux = 100'000.0;
const double kAlpha = 0.265 * kDeg;  // the disc's angular radius

Luminaire sun_beam(dvec3 direction, dvec3 corner, dvec3 e1, dvec3 e2) {
  Luminaire l;
  l.name = "sun";
  l.type = Luminaire::Type::Sun;
  l.direction = direction;
  l.corner = corner;
  l.edge1 = e1;
  l.edge2 = e2;
  l.illuminance_lx = kLux;
  return l;
}

// A black floor far below, so nothing returns light.
Scene black_scene() {
  Scene s;
  add_material(s, "black", Material::Type::Diffuse, 0.0);
  s.meshes.push_back(quad_mesh("ground", 0, {-50, -50, -5}, {100, 0, 0}, {0, 100, 0}));
  return s;
}

// expect_in_ci, printing the estimate, its interval and the exact value for docs/daylight.md.
void check(const Estimate& e, double exact, double max_rel_half_width, const std::string& what) {
  std::printf("%-28s exact %.6g  estimate %.6g  interval [%.6g, %.6g]  half-width %.2f %%\n",
              what.c_str(), exact, e.mean, e.ci_low, e.ci_high,
              50.0 * (e.ci_high - e.ci_low) / exact);
  expect_in_ci(e, exact, max_rel_half_width, what);
}

class SunLuminaire : public ::testing::TestWithParam<std::string> {
 protected:
  Results run(Scene s, std::uint64_t photons) {
    return run_on_backend(GetParam(), std::move(s), photons, 11);
  }
};

// A beam 30° from the zenith through a horizontal opening: E_n on a square across the beam,
// E_n cos 30° on a horizontal one. Both lie inside the beam, its 0.265° blur included.
TEST_P(SunLuminaire, NormalAndTiltedPlanes) {
  Scene s = black_scene();
  const dvec3 d = glm::normalize(dvec3(-std::sin(30 * kDeg), 0, -std::cos(30 * kDeg)));
  s.luminaires.push_back(sun_beam(d, {-2, -2, 3}, {0, 4, 0}, {6, 0, 0}));  // front −z: faces d
  // Across the beam: a 0.4 m square facing the sun (front = −d), centred near (0, 0, 1).
  const dvec3 a = glm::normalize(glm::cross(d, dvec3(0, 1, 0))), b(0, 1, 0);
  const dvec3 centre(0, 0, 1);
  s.targets.push_back(grid("across", centre - 0.2 * a - 0.2 * b, 0.4 * a, 0.4 * b, 1, 1));
  ASSERT_GT(glm::dot(glm::cross(a, b), -d), 0.0);  // the grid faces the sun
  s.targets.push_back(grid("floor", {-0.5, -0.5, 0.2}, {1, 0, 0}, {0, 1, 0}, 1, 1));
  const Results r = run(s, 2'000'000);
  check(r.targets[0].estimate, kLux, 0.1, "across the beam");
  check(r.targets[1].estimate, kLux * std::cos(30 * kDeg), 0.05, "horizontal");
}

// The sun 0.5° above the horizon through a window (a vertical opening facing it): a horizontal
// plane gets E_n sin 0.5°, finite and inside its interval though the beam grazes it.
TEST_P(SunLuminaire, SunHalfADegreeAboveTheHorizon) {
  Scene s = black_scene();
  const double e = 0.5 * kDeg;
  const dvec3 d(-std::cos(e), 0, -std::sin(e));
  // Opening in the plane x = 5, y in [−2, 2], z in [0.2, 0.6]; front e1 × e2 = −x.
  s.luminaires.push_back(sun_beam(d, {5, -2, 0.2}, {0, 0, 0.4}, {0, 4, 0}));
  // Rays from z ≥ 0.4 cross z = 0.4 within 0.2 / tan(0.765°) = 15 m of the opening, whatever
  // their direction in the disc: x in [−5, 0] is lit by the whole disc.
  s.targets.push_back(grid("floor", {-5, -0.5, 0.4}, {5, 0, 0}, {0, 1, 0}, 1, 1));
  const Results r = run(s, 2'000'000);
  const Estimate& est = r.targets[0].estimate;
  EXPECT_TRUE(std::isfinite(est.mean) && std::isfinite(est.ci_low) && std::isfinite(est.ci_high));
  check(est, kLux * std::sin(e), 0.05, "grazing floor");
}

// The beam's axis exactly in a wall's plane (y = 0): each side of the wall sees half the disc,
// E_n (α − sin α cos α) / (π sin²α) ≈ 0.001 E_n; the floor beside it the full E_n cos 30°.
TEST_P(SunLuminaire, SunInAWallsPlane) {
  Scene s = black_scene();
  const dvec3 d(-0.5, 0, -std::sqrt(0.75));
  s.luminaires.push_back(sun_beam(d, {-2, -0.3, 3}, {0, 1.6, 0}, {6, 0, 0}));
  s.meshes.push_back(quad_mesh("wall", 0, {-1, 0, 0}, {0, 0, 2.5}, {2, 0, 0}));  // front +y
  s.targets.push_back(surface("wall", 1));
  s.targets.push_back(grid("floor beside", {-1, 0.05, 0.01}, {2, 0, 0}, {0, 0.25, 0}, 1, 1));
  const Results r = run(s, 4'000'000);
  const double half_disc = kLux * (kAlpha - std::sin(kAlpha) * std::cos(kAlpha)) /
                           (std::numbers::pi * std::pow(std::sin(kAlpha), 2));
  const Estimate& wall = r.targets[0].estimate;
  EXPECT_TRUE(std::isfinite(wall.mean) && std::isfinite(wall.ci_high));
  check(wall, half_disc, 0.12, "wall in the beam's plane");
  check(r.targets[1].estimate, kLux * std::sqrt(0.75), 0.05, "floor beside the wall");
}

INSTANTIATE_TEST_SUITE_P(Backends, SunLuminaire, ::testing::ValuesIn(backends()));

// Emission statistics, CPU: every direction within the disc, and the density ∝ |n·ω| (as many
// photons per direction as the opening's area across it). Through an opening at θ = 80° from the
// beam, n·ω = cos θ − sin θ·s, s the offset along e1 = (cos θ, 0, sin θ) (⊥ d, away from n), so
// the offsets' mean is −tan θ·E[s²] = −(α²/4)·tan θ, 8 σ from the 0 of uniform sampling.
TEST(SunEmission, DirectionsFillTheDiscWeightedByTheOpening) {
  Scene s = black_scene();
  const double theta = 80 * kDeg;
  const dvec3 d(std::sin(theta), 0, -std::cos(theta));
  s.luminaires.push_back(sun_beam(d, {0, 0, 3}, {0, 1, 0}, {1, 0, 0}));  // n = −z
  s.targets.push_back(surface("ground", 0));
  validate(s);
  const detail::PreparedScene p = detail::prepare(s);
  const detail::PreparedLuminaire& l = p.luminaires[0];
  const dvec3 e1(std::cos(theta), 0, std::sin(theta));
  const int n = 4'000'000;
  double max_angle = 0.0, sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    PathRng rng(5, i);
    const dvec3 w = glm::normalize(dvec3(l.emit(l, rng).direction));
    max_angle = std::max(max_angle, std::acos(std::min(1.0, glm::dot(w, d))));
    const double off = glm::dot(w - d, e1);
    sum += off;
    sum2 += off * off;
  }
  EXPECT_LE(max_angle, kAlpha * 1.001);
  EXPECT_GE(max_angle, kAlpha * 0.98);
  const double mean = sum / n, sigma = std::sqrt((sum2 / n - mean * mean) / n);
  const double expected = -0.25 * kAlpha * kAlpha * std::tan(theta);
  ASSERT_GT(std::abs(expected), 6 * sigma);  // the test tells the two samplings apart
  EXPECT_NEAR(mean, expected, 4 * sigma);
}

// Scene files: a sun from a site and a time, and the errors that name their key.
std::string sun_scene(const std::string& keys) {
  return R"({"format": "lightsolver.scene/1",
    "materials": {"black": {"type": "diffuse", "reflectance": 0}},
    "meshes": [{"name": "floor", "material": "black",
                "vertices": [[-9,-9,0],[9,-9,0],[9,9,0],[-9,9,0]], "triangles": [[0,1,2],[0,2,3]]}],
    "luminaires": [{"name": "sun", "type": "sun", "illuminance_lx": 100000,
                    "corner": [-3,-3,3], "edge1": [0,6,0], "edge2": [6,0,0])" +
         (keys.empty() ? "" : ", " + keys) + R"(}],
    "targets": [{"name": "floor", "type": "surface", "mesh": "floor"}]})";
}

std::string sun_error_of(const std::string& keys) {
  try {
    Scene s = scene_from_json(sun_scene(keys), "sun.json", ".");
    validate(s);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SunScene, DirectionFromSiteAndTime) {
  Scene s = scene_from_json(sun_scene(R"("site": {"latitude_deg": 39.742476,
      "longitude_deg": -105.1786, "elevation_m": 1830.14}, "time": "2003-10-17T12:30:30-07:00",
      "north_deg": 90)"),
                            "sun.json", ".");
  validate(s);
  const Luminaire& l = s.luminaires[0];
  ASSERT_TRUE(l.sun.has_value());
  EXPECT_NEAR(l.sun->azimuth_deg, 194.34, 0.01);
  // The beam travels away from the sun: down, and (north along −x, east along +y) toward the
  // north-north-east since the sun stands south-south-west.
  const dvec3 toward = sun_direction(*l.sun, 90.0);
  EXPECT_NEAR(glm::length(l.direction + toward), 0.0, 1e-12);
  EXPECT_LT(l.direction.z, 0.0);
  EXPECT_LT(l.direction.x, 0.0);  // toward north (−x)
  EXPECT_NEAR(l.flux_lm, 100000 * 36 * -l.direction.z, 1e-6 * l.flux_lm);
}

TEST(SunScene, BelowTheHorizonIsSwitchedOff) {
  Scene s = scene_from_json(sun_scene(R"("site": {"latitude_deg": 50, "longitude_deg": 0},
      "time": "2026-12-21T00:00Z")"),
                            "sun.json", ".");
  validate(s);
  EXPECT_EQ(s.luminaires[0].flux_lm, 0.0);
  EXPECT_LT(s.luminaires[0].sun->elevation_deg, 0.0);
}

TEST(SunScene, ErrorsNameTheKey) {
  EXPECT_NE(sun_error_of(R"("direction": [0,0,-1], "time": "2026-01-01T12:00Z")")
                .find("luminaires[0]: a sun gives either"),
            std::string::npos);
  EXPECT_NE(sun_error_of("").find("a sun gives either"), std::string::npos);
  EXPECT_NE(sun_error_of(
                R"("site": {"latitude_deg": 95, "longitude_deg": 0}, "time": "2026-06-01T12:00Z")")
                .find("luminaires[0].site.latitude_deg: must be a number from -90 to 90"),
            std::string::npos);
  EXPECT_NE(sun_error_of(
                R"("site": {"latitude_deg": 45, "longitude_deg": 0}, "time": "2026-13-01T12:00Z")")
                .find("luminaires[0].time: '2026-13-01T12:00Z' is not an ISO 8601"),
            std::string::npos);
  EXPECT_NE(sun_error_of(
                R"("site": {"latitude_deg": 45, "longitude_deg": 0}, "time": "2026-06-01T12:00")")
                .find("luminaires[0].time:"),
            std::string::npos);
  EXPECT_NE(sun_error_of(R"("site": {"latitude_deg": 45}, "time": "2026-06-01T12:00Z")")
                .find("longitude_deg"),
            std::string::npos);
  EXPECT_NE(
      sun_error_of(
          R"("site": {"latitude_deg": 45, "longitude_deg": 0, "height": 3}, "time": "2026-06-01T12:00Z")")
          .find("height"),
      std::string::npos);
  // A beam within the disc's radius of its opening's plane is traced (sun_straddling_test.cpp).
  EXPECT_EQ(sun_error_of(R"("direction": [1, 0, -0.001])"), "(no error)");
  EXPECT_EQ(sun_error_of(R"("direction": [1, 0, -0.01])"), "(no error)");
}

}  // namespace
}  // namespace lightsolver::test
