// Direct sunlight at points per hour, for ASE (lightsolver/direct_sun.hpp; docs/daylight.md,
// "Direct sun at points (for ASE)"): closed forms in scenes built here — an open site, a box
// with one window (the ray through the window worked by hand), an overhang, glazing against
// the glazing model — and a Chicago year for 300 points against the box's geometry computed in
// the test.
#include "lightsolver/direct_sun.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "daylight/sky_glazing.hpp"
#include "lightsolver/angles.hpp"
#include "lightsolver/error.hpp"
#include "lightsolver/scene.hpp"
#include "lightsolver/sky_patches.hpp"
#include "lightsolver/weather.hpp"
#include "scene_builders.hpp"

namespace lightsolver {
namespace {

const glm::dvec3 kUp(0, 0, 1);

// An axis-aligned rectangle in the plane y = y0: x in [x0, x1], z in [z0, z1].
Mesh wall_y(double y0, double x0, double x1, double z0, double z1, int material = 0) {
  return test::corner_quad({x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}, material);
}

Scene empty_scene() {
  Scene s;
  s.materials = {default_material("wall", Material::Type::Diffuse),
                 default_material("glass", Material::Type::Glass)};
  return s;
}

// A closed 4 × 4 × 3 m box (x, y in [0, 4], z in [0, 3]) with one 2 × 1 m hole in its south
// wall (y = 0): x in [1, 3], z in [1, 2].
Scene box_with_window() {
  Scene s = empty_scene();
  auto& m = s.meshes;
  m.push_back(test::corner_quad({0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}));  // floor
  m.push_back(test::corner_quad({0, 0, 3}, {4, 0, 3}, {4, 4, 3}, {0, 4, 3}));  // ceiling
  m.push_back(test::corner_quad({0, 0, 0}, {0, 4, 0}, {0, 4, 3}, {0, 0, 3}));  // west
  m.push_back(test::corner_quad({4, 0, 0}, {4, 4, 0}, {4, 4, 3}, {4, 0, 3}));  // east
  m.push_back(wall_y(4, 0, 4, 0, 3));                                          // north
  m.push_back(wall_y(0, 0, 4, 0, 1));  // south: below the sill
  m.push_back(wall_y(0, 0, 4, 2, 3));  // above the head
  m.push_back(wall_y(0, 0, 1, 1, 2));  // beside the window
  m.push_back(wall_y(0, 3, 4, 1, 2));
  return s;
}

// The window as a portal: edge1 × edge2 = (0, 2, 0), into the room (+y).
SunOpening window(std::optional<GlazingDefinition> glazing = std::nullopt) {
  return {{1, 0, 1}, {0, 0, 1}, {2, 0, 0}, glazing, false};
}

// Toward the sun at altitude `alt` and azimuth `az` from north toward east (+y north, +x east).
glm::dvec3 sun(double alt_deg, double az_deg) {
  const double a = alt_deg * kDeg, z = az_deg * kDeg;
  return {std::sin(z) * std::cos(a), std::cos(z) * std::cos(a), std::sin(a)};
}

struct Hours {
  std::vector<float> direction, e_n;
  void add(const glm::dvec3& s, double e) {
    direction.insert(direction.end(), {float(s.x), float(s.y), float(s.z)});
    e_n.push_back(float(e));
  }
};

std::vector<float> run(const Scene& scene, const std::vector<SunOpening>& openings,
                       const std::vector<glm::dvec3>& points, const Hours& h,
                       glm::dvec3 normal = kUp) {
  const std::vector<glm::dvec3> normals(points.size(), normal);
  return direct_sun_lx(scene, openings, points, normals, h.direction, h.e_n);
}

TEST(DirectSun, UnobstructedHorizontalPointGetsNormalIlluminanceTimesSinAltitude) {
  Hours h;
  const double alts[] = {5.0, 30.0, 61.5, 89.0};
  for (double a : alts) h.add(sun(a, 137.0), 80000.0);
  const std::vector<float> e = run(empty_scene(), {}, {{0.3, -2.0, 0.8}}, h);
  ASSERT_EQ(e.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    const double exact = 80000.0 * std::sin(alts[i] * kDeg);
    EXPECT_NEAR(e[i], exact, 2e-6 * exact) << alts[i];
  }
  // A vertical point facing the sun's azimuth: E_n cos(altitude); facing away: 0.
  const std::vector<float> v = run(empty_scene(), {}, {{0, 0, 0}}, h, sun(0.0, 137.0));
  EXPECT_NEAR(v[1], 80000.0 * std::cos(30.0 * kDeg), 0.02);
  const std::vector<float> away = run(empty_scene(), {}, {{0, 0, 0}}, h, -sun(0.0, 137.0));
  for (float x : away) EXPECT_EQ(x, 0.0f);
}

TEST(DirectSun, SunDownOrNoDirectLightGivesZero) {
  Hours h;
  h.add(sun(40.0, 180.0), 0.0);      // no direct light
  h.add(sun(-3.0, 180.0), 50000.0);  // below the horizon (E_n given anyway)
  h.add(glm::dvec3(0.0), 0.0);       // SkyMatrix's night: no vector
  h.add(sun(40.0, 180.0), 50000.0);  // the one lit hour
  const std::vector<float> e = run(empty_scene(), {}, {{0, 0, 0}, {5, 5, 1}}, h);
  ASSERT_EQ(e.size(), 8u);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(e[i], 0.0f) << i;
  EXPECT_NEAR(e[6], 50000.0 * std::sin(40.0 * kDeg), 0.05);
  EXPECT_EQ(e[6], e[7]);
}

// The sun due south at 45°: a floor point (x, y, 0) meets the window's plane y = 0 at height y
// (tan 45° = 1) and at the same x, so it is sunlit exactly when x in [1, 3] and y in [1, 2].
TEST(DirectSun, FloorOfABoxIsSunlitWhereTheRayPassesTheWindow) {
  const Scene box = box_with_window();
  Hours h;
  h.add(sun(45.0, 180.0), 60000.0);
  const std::vector<glm::dvec3> pts = {{2, 1.5, 0},   {2, 0.5, 0},   {2, 2.5, 0},
                                       {0.5, 1.5, 0}, {2.9, 1.1, 0}, {3.1, 1.5, 0}};
  const bool lit[] = {true, false, false, false, true, false};
  const double exact = 60000.0 * std::sin(45.0 * kDeg);
  for (const auto& openings : {std::vector<SunOpening>{window()}, std::vector<SunOpening>{}}) {
    const std::vector<float> e = run(box, openings, pts, h);
    for (std::size_t i = 0; i < pts.size(); ++i) {
      EXPECT_NEAR(e[i], lit[i] ? exact : 0.0, 1e-6 * exact) << i << " openings " << openings.size();
    }
  }
  // Oblique: azimuth 150° (south-south-east), altitude 30°: s = (0.4330, −0.75, 0.5). From
  // (x, y, 0) the ray reaches y = 0 after t = y / 0.75, at x + 0.4330 t and height 0.5 t:
  // (1.5, 2) → x 2.6547, z 1.3333 (lit); (2.5, 2) → x 3.6547 (beside the window, dark);
  // (1, 2.8) → x 2.6166, z 1.8667 (lit); (0.5, 2) → x 1.6547 (lit); (1.5, 1) → z 0.6667 (dark).
  const glm::dvec3 s = sun(30.0, 150.0);
  Hours o;
  o.add(s, 60000.0);
  const std::vector<glm::dvec3> q = {
      {1.5, 2, 0}, {2.5, 2, 0}, {1, 2.8, 0}, {0.5, 2, 0}, {1.5, 1, 0}};
  const bool lit_o[] = {true, false, true, true, false};
  const std::vector<float> eo = run(box, {window()}, q, o);
  for (std::size_t i = 0; i < q.size(); ++i) {
    const double t = -q[i].y / s.y;  // the same crossing, computed
    const double x = q[i].x + t * s.x, z = t * s.z;
    const bool in = x >= 1 && x <= 3 && z >= 1 && z <= 2;
    std::printf("[ direct sun ] (%.1f, %.1f): window plane at x %.4f, z %.4f: %s, %.1f lx\n",
                q[i].x, q[i].y, x, z, in ? "lit" : "dark", eo[i]);
    EXPECT_EQ(in, lit_o[i]) << i;
    EXPECT_NEAR(eo[i], lit_o[i] ? 60000.0 * s.z : 0.0, 0.05) << i;
  }
}

TEST(DirectSun, ARayLeavingThroughAWallIsDark) {
  const Scene box = box_with_window();
  Hours h;
  h.add(sun(45.0, 0.0), 60000.0);   // from the north: every ray meets the north wall
  h.add(sun(45.0, 90.0), 60000.0);  // from the east: the east wall
  const std::vector<glm::dvec3> pts = {{2, 1.5, 0.1}, {2, 3.5, 0.1}, {3.9, 2, 2.9}};
  for (const auto& openings : {std::vector<SunOpening>{window()}, std::vector<SunOpening>{}}) {
    for (float e : run(box, openings, pts, h)) EXPECT_EQ(e, 0.0f);
  }
  // An opening that does not face the ray: the portal passes only light entering the room.
  Hours n;
  n.add(sun(45.0, 0.0), 60000.0);
  const std::vector<float> outside = run(empty_scene(), {window()}, {{2, -1.5, 0}}, n);
  EXPECT_EQ(outside[0], 0.0f);
  SunOpening own = window();
  own.two_sided = true;  // the sun's own opening passes it both ways
  EXPECT_NEAR(run(empty_scene(), {own}, {{2, -1.5, 0}}, n)[0], 60000.0 * std::sin(45.0 * kDeg),
              0.05);
  // With openings, a point whose ray crosses none of them is dark even in the open.
  EXPECT_EQ(run(empty_scene(), {window()}, {{2, 5, 0}}, n)[0], 0.0f);
}

// An overhang (a plate at z = 2 over y in [-1, 0]) with the sun due south at 45°: a point
// (x, y, 0) meets z = 2 at y − 2, under the plate for y in [1, 2].
TEST(DirectSun, PointsBehindAnOverhangAreShadowed) {
  Scene s = empty_scene();
  s.meshes.push_back(test::corner_quad({-5, -1, 2}, {5, -1, 2}, {5, 0, 2}, {-5, 0, 2}));
  Hours h;
  h.add(sun(45.0, 180.0), 60000.0);
  const std::vector<float> e = run(s, {}, {{0, 1.5, 0}, {0, 0.5, 0}, {0, 2.5, 0}, {0, 1.02, 0}}, h);
  const double exact = 60000.0 * std::sin(45.0 * kDeg);
  EXPECT_EQ(e[0], 0.0f);
  EXPECT_NEAR(e[1], exact, 0.05);
  EXPECT_NEAR(e[2], exact, 0.05);
  EXPECT_EQ(e[3], 0.0f);
  // An overhang outside the box's window (z = 2.2, y in [-0.6, 0]): the floor point (2, 1.5)
  // leaves the window at z 1.5 and passes z = 2.2 at y = -0.7 (clear); (2, 1.8) at y = -0.4
  // (under the overhang: dark, though the window itself passes it).
  Scene box = box_with_window();
  box.meshes.push_back(test::corner_quad({0, -0.6, 2.2}, {4, -0.6, 2.2}, {4, 0, 2.2}, {0, 0, 2.2}));
  const std::vector<float> b = run(box, {window()}, {{2, 1.5, 0}, {2, 1.8, 0}}, h);
  EXPECT_NEAR(b[0], exact, 0.05);
  EXPECT_EQ(b[1], 0.0f);
  // A partition inside the room between the point and the window blocks too.
  Scene inner = box_with_window();
  inner.meshes.push_back(test::corner_quad({0, 1, 0}, {4, 1, 0}, {4, 1, 0.5}, {0, 1, 0.5}));
  const std::vector<float> p = run(inner, {window()}, {{2, 1.5, 0}}, h);
  EXPECT_EQ(p[0], 0.0f);
}

TEST(DirectSun, GlazingTakesTauAtTheIncidenceTimesFrameAndMaintenance) {
  GlazingDefinition g;
  g.transmittance = 0.7;
  g.panes = 2;
  g.frame_factor = 0.8;
  g.maintenance_factor = 0.9;
  // A glass pane modelled in the hole changes nothing (the opening's glazing stands for it).
  Scene box = box_with_window();
  box.meshes.push_back(wall_y(0.0, 1, 3, 1, 2, 1));
  // Incidence 60° on the window (cos θ = −s.y = cos(alt) cos(az − 180°) = 0.5): altitude
  // acos 0.75 = 41.41°, azimuth 180° − acos(2/3) = 131.81° (0.75 · 2/3 = 0.5).
  const double alt = std::acos(0.75) / kDeg, off = std::acos(2.0 / 3.0) / kDeg;
  const glm::dvec3 s = sun(alt, 180.0 - off);
  ASSERT_NEAR(-s.y, 0.5, 1e-12);
  Hours h;
  h.add(s, 70000.0);
  h.add(sun(30.0, 180.0), 70000.0);
  // Points whose rays cross the window's middle, (2, 0, 1.5): p = (2, 0, 1.5) − t s at z = 0.
  std::vector<glm::dvec3> pts;
  for (const glm::dvec3& d : {s, sun(30.0, 180.0)})
    pts.push_back(glm::dvec3(2, 0, 1.5) - 1.5 / d.z * d);
  const std::vector<float> e = run(box, {window(g)}, pts, h);
  // The glazing model's double glazing: τ(θ)/τv = T(θ)/T(0), stated in docs/daylight.md as
  // 0.8956 at 60° — an independent figure to its 4 digits.
  const double ratio60 = shared::glazing_clear_transmittance<double>(0.5, 4) /
                         shared::glazing_clear_transmittance<double>(1.0, 4);
  EXPECT_NEAR(ratio60, 0.8956, 5e-5);
  const double tau60 = shared::glazing_transmittance<double>(
      0.5, 0.7 / shared::glazing_clear_transmittance<double>(1.0, 4), 2);
  EXPECT_NEAR(tau60, 0.7 * ratio60, 1e-12);
  const double exact0 = 70000.0 * s.z * tau60 * 0.8 * 0.9;
  std::printf("[ direct sun ] double glazing τv 0.7 at 60°: τ %.6f, E %.3f lx (exact %.3f)\n",
              tau60, e[0], exact0);
  EXPECT_NEAR(e[0], exact0, 2e-6 * exact0);
  const double cos1 = std::cos(30.0 * kDeg);  // the second hour: incidence 30° on the window
  const double tau1 = shared::glazing_transmittance<double>(
      cos1, 0.7 / shared::glazing_clear_transmittance<double>(1.0, 4), 2);
  EXPECT_NEAR(e[3], 70000.0 * 0.5 * tau1 * 0.72, 2e-6 * 70000.0);
  // The other two entries (each point at the other hour): whatever the geometry gives.
  for (float x : e) EXPECT_TRUE(std::isfinite(x) && x >= 0.0f);
}

TEST(DirectSun, OpeningsOfTheScene) {
  Scene s = empty_scene();
  EXPECT_TRUE(sun_openings(s).empty());
  Luminaire sky;
  sky.type = Luminaire::Type::Sky;
  sky.sky.portals = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, std::nullopt},
                     {{5, 0, 0}, {0, 0, 1}, {1, 0, 0}, GlazingDefinition{0.6, 2, 0.7, 0.9}}};
  s.luminaires.push_back(sky);
  std::vector<SunOpening> o = sun_openings(s);
  ASSERT_EQ(o.size(), 2u);
  EXPECT_FALSE(o[0].two_sided);
  EXPECT_FALSE(o[0].glazing);
  ASSERT_TRUE(o[1].glazing);
  EXPECT_EQ(o[1].glazing->panes, 2);
  EXPECT_EQ(o[1].corner, glm::dvec3(5, 0, 0));
  // A sun with its own opening comes first (two-sided, its glazing).
  Luminaire sun_l;
  sun_l.type = Luminaire::Type::Sun;
  sun_l.corner = {1, 2, 3};
  sun_l.edge1 = {1, 0, 0};
  sun_l.edge2 = {0, 1, 0};
  sun_l.glazing = GlazingDefinition{0.8, 1, 1.0, 1.0};
  s.luminaires.push_back(sun_l);
  o = sun_openings(s);
  ASSERT_EQ(o.size(), 1u);
  EXPECT_TRUE(o[0].two_sided);
  EXPECT_EQ(o[0].corner, glm::dvec3(1, 2, 3));
  ASSERT_TRUE(o[0].glazing);
  EXPECT_EQ(o[0].glazing->transmittance, 0.8);
  // A sun through portals: those portals, one-sided.
  s.luminaires.back().sky.portals = {{{7, 0, 0}, {1, 0, 0}, {0, 1, 0}, std::nullopt}};
  o = sun_openings(s);
  ASSERT_EQ(o.size(), 1u);
  EXPECT_FALSE(o[0].two_sided);
  EXPECT_EQ(o[0].corner, glm::dvec3(7, 0, 0));
}

// The traced sun agrees: the black box's window as the portal of a `sun` luminaire (double
// glazing), traced on Embree; 0.4 m floor probes wholly in the beam's patch and wholly outside
// it read, within their 5σ intervals, the direct sun at their centres (sun_openings collects the
// portal).
TEST(DirectSun, AgreesWithTheTracedSunThroughThePortal) {
  Scene box = box_with_window();
  box.materials = {default_material("black", Material::Type::Diffuse)};
  box.materials[0].reflectance = 0.0;
  for (std::size_t i = 0; i < box.meshes.size(); ++i)
    box.meshes[i].name = "wall " + std::to_string(i);
  const glm::dvec3 s = sun(45.0, 180.0);
  Luminaire l;
  l.name = "sun";
  l.type = Luminaire::Type::Sun;
  l.direction = -s;
  l.illuminance_lx = 1e5;
  const SunOpening w = window(GlazingDefinition{0.7, 2, 0.8, 0.9});
  l.sky.portals.push_back({w.corner, w.edge1, w.edge2, w.glazing});
  box.luminaires.push_back(l);
  const std::vector<glm::dvec3> centres = {{2.0, 1.5, 0.01}, {2.0, 2.6, 0.01}};
  for (std::size_t i = 0; i < centres.size(); ++i) {
    box.targets.push_back(test::grid("probe " + std::to_string(i),
                                     centres[i] - glm::dvec3(0.2, 0.2, 0), {0.4, 0, 0}, {0, 0.4, 0},
                                     1, 1));
  }
  const std::vector<SunOpening> openings = sun_openings(box);
  ASSERT_EQ(openings.size(), 1u);
  Hours h;
  h.add(s, 1e5);
  const std::vector<float> e = run(box, openings, centres, h);
  const Results r = test::run_on_backend("embree", box, 400'000, 27);
  std::printf("[ direct sun ] traced %.1f [%.1f, %.1f] lx, direct sun %.1f lx; dark probe %.1f\n",
              r.targets[0].estimate.mean, r.targets[0].estimate.ci_low,
              r.targets[0].estimate.ci_high, e[0], r.targets[1].estimate.mean);
  EXPECT_GT(e[0], 30000.0f);
  test::expect_in_ci(r.targets[0].estimate, e[0], 0.05, "lit probe");
  EXPECT_EQ(e[1], 0.0f);
  EXPECT_EQ(r.targets[1].estimate.hits, 0u);
}

// The field an InputError names.
std::string where_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "direct_sun_lx");
    return e.where();
  }
  return "(no error)";
}

TEST(DirectSun, BadInputNamesTheField) {
  const Scene s = empty_scene();
  const std::vector<glm::dvec3> pts = {{0, 0, 0}, {1, 0, 0}};
  const std::vector<glm::dvec3> up = {kUp, kUp};
  const std::vector<float> dir = {0, 0, 1, 0, 0.6f, 0.8f};
  const std::vector<float> en = {1000, 2000};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto call = [&](std::vector<glm::dvec3> p, std::vector<glm::dvec3> n, std::vector<float> d,
                  std::vector<float> e, std::vector<SunOpening> o = {}) {
    return [=, &s] { direct_sun_lx(s, o, p, n, d, e); };
  };
  EXPECT_EQ(where_of(call(pts, up, dir, en)), "(no error)");
  EXPECT_EQ(where_of(call(pts, {kUp}, dir, en)), "normals");
  EXPECT_EQ(where_of(call(pts, up, {0, 0, 1}, en)), "sun_direction");
  EXPECT_EQ(where_of(call({{0, 0, 0}, {nan, 0, 0}}, up, dir, en)), "points[1]");
  EXPECT_EQ(where_of(call(pts, {kUp, {0, 0, 0}}, dir, en)), "normals[1]");
  EXPECT_EQ(where_of(call(pts, {{0, 0, 2}, kUp}, dir, en)), "normals[0]");
  EXPECT_EQ(where_of(call(pts, {kUp, {0, nan, 1}}, dir, en)), "normals[1]");
  EXPECT_EQ(where_of(call(pts, up, dir, {1000, -1})), "sun_direct_normal_lx[1]");
  EXPECT_EQ(where_of(call(pts, up, dir, {float(nan), 1})), "sun_direct_normal_lx[0]");
  EXPECT_EQ(where_of(call(pts, up, {0, 0, 1, 0, 0, 0}, en)), "sun_direction[1]");
  EXPECT_EQ(where_of(call(pts, up, {0, 0, 1, 0, 0.6f, 0.9f}, en)), "sun_direction[1]");
  EXPECT_EQ(where_of(call(pts, up, {0, 0, float(nan), 0, 0.6f, 0.8f}, {0, 1})), "sun_direction[0]");
  // No direct light: a zero or any finite direction is fine.
  EXPECT_EQ(where_of(call(pts, up, {0, 0, 0, 0, 0.6f, 0.8f}, {0, 1})), "(no error)");
  SunOpening flat = window();
  flat.edge2 = {0, 0, 2};  // parallel to edge1
  EXPECT_EQ(where_of(call(pts, up, dir, en, {window(), flat})), "openings[1]");
  SunOpening far = window();
  far.corner.x = nan;
  EXPECT_EQ(where_of(call(pts, up, dir, en, {far})), "openings[0]");
  GlazingDefinition g{0.7, 2, 1.0, 1.0};
  g.frame_factor = 0.0;
  EXPECT_EQ(where_of(call(pts, up, dir, en, {window(g)})), "openings[0].glazing.frame_factor");
  g.frame_factor = 1.0;
  g.panes = 3;
  EXPECT_EQ(where_of(call(pts, up, dir, en, {window(g)})), "openings[0].glazing.panes");
  g.panes = 1;
  g.transmittance = 1.5;
  EXPECT_EQ(where_of(call(pts, up, dir, en, {window(g)})), "openings[0].glazing.transmittance");
}

const WeatherFile& chicago() {
  static const WeatherFile w =
      read_epw(std::filesystem::path(LIGHTSOLVER_SOURCE_DIR) / "Tests/native/sun/data" /
               "USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw");
  return w;
}

// A year in Chicago for 300 points 0.8 m above the box's floor, through the double-glazed
// south window: every value against the box's geometry worked here (the ray meets the plane
// y = 0 inside the window: lit, else dark; the box is convex and has no other hole), points
// whose crossing lies within 10⁻⁴ m of the window's edge left out (float rays); the same result
// on one thread; the time printed.
TEST(DirectSun, ChicagoYearFor300PointsMatchesTheWindowGeometry) {
  const SkyMatrix sky = sky_matrix(chicago(), {});
  const Scene box = box_with_window();
  const GlazingDefinition g{0.7, 2, 0.8, 0.9};
  std::vector<glm::dvec3> pts, normals;
  for (int i = 0; i < 15; ++i) {
    for (int j = 0; j < 20; ++j) pts.push_back({0.1 + i * 3.8 / 14, 0.1 + j * 3.8 / 19, 0.8});
  }
  normals.assign(pts.size(), kUp);
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<float> e = direct_sun_lx(box, {window(g)}, pts, normals, sky);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(e.size(), std::size_t(sky.hours) * pts.size());
  const daylight::Glazing glazing{0.7, 2, 0.8, 0.9};
  std::size_t lit = 0, over_1000 = 0, checked = 0, sun_hours = 0;
  for (int h = 0; h < sky.hours; ++h) {
    const glm::dvec3 s = glm::normalize(glm::dvec3(
        sky.sun_direction[3 * h], sky.sun_direction[3 * h + 1], sky.sun_direction[3 * h + 2]));
    const double en = sky.sun_direct_normal_lx[h];
    const bool up = en > 0.0 && s.z > 0.0;
    sun_hours += up;
    for (std::size_t p = 0; p < pts.size(); ++p) {
      const float got = e[h * pts.size() + p];
      ASSERT_TRUE(std::isfinite(got) && got >= 0.0f);
      double exact = 0.0;
      if (up && s.y < 0.0) {
        const double t = -pts[p].y / s.y;
        const double x = pts[p].x + t * s.x, z = pts[p].z + t * s.z;
        const double margin =
            std::min({std::abs(x - 1), std::abs(x - 3), std::abs(z - 1), std::abs(z - 2)});
        if (margin < 1e-4) continue;
        if (x > 1 && x < 3 && z > 1 && z < 2) {
          exact = en * s.z * glazing.tau(-s.y) * glazing.factor();
        }
      }
      ++checked;
      ASSERT_NEAR(got, exact, 1e-5 * en + 1e-3) << "hour " << h << " point " << p;
      lit += got > 0.0f;
      over_1000 += got > 1000.0f;
    }
  }
  std::printf(
      "[ direct sun ] Chicago year, 300 points, box with a south window: %.3f s (%d hours, %zu "
      "with the sun up), %zu cell-hours sunlit, %zu above 1000 lx, %zu of %zu checked\n",
      seconds, sky.hours, sun_hours, lit, over_1000, checked, e.size());
  EXPECT_GT(lit, 10000u);  // the geometry lets the sun in, so the check has teeth
  EXPECT_GT(checked, e.size() - e.size() / 10000);  // few crossings that near an edge
  EXPECT_LT(seconds, 2.0);
  // One thread: the same floats.
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  EXPECT_EQ(direct_sun_lx(box, {window(g)}, pts, normals, sky), e);
}

}  // namespace
}  // namespace lightsolver
