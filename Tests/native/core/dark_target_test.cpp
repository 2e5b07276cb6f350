// Targets that cannot receive light (prepare/target_reach.hpp): said before tracing when no
// surface reflects and the target faces away from every luminaire's emission, per luminaire
// type; never said when something reflects or where a luminaire can reach the target. Each
// claim is checked against a run: a target called dark gets no photon at all.
#include <gtest/gtest.h>

#include "model/prepared_scene.hpp"
#include "prepare/scene_effects.hpp"
#include "prepare/target_reach.hpp"
#include "lightsolver/photometry.hpp"
#include "lightsolver/scene_check.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

const dvec3 kUp(0, 0, 1), kDown(0, 0, -1);

// A black 4 x 4 x 3 m room (nothing reflects) and, at height z, a grid facing up (front +z)
// and one facing down; the luminaire is added by each test.
Scene black_room() {
  Scene s;
  add_material(s, "black", Material::Type::Diffuse, 0.0);
  s.meshes.push_back(room_mesh("room", 0, dvec3(0), dvec3(4, 4, 3)));
  return s;
}

void add_grids_at(Scene& s, double z) {
  // Front = e1 x e2: +z for (x, y), -z for (y, x).
  s.targets.push_back(grid("up " + std::to_string(z), {1, 1, z}, {2, 0, 0}, {0, 2, 0}, 2, 2));
  s.targets.push_back(grid("down " + std::to_string(z), {1, 1, z}, {0, 2, 0}, {2, 0, 0}, 2, 2));
}

std::vector<std::size_t> dark(const Scene& scene) {
  const detail::PreparedScene p = detail::prepare(scene);
  std::vector<std::size_t> out;
  for (const auto& d : detail::dark_targets(scene, p, detail::analyse_effects(p))) {
    out.push_back(d.target);
  }
  return out;
}

// Every target called dark gets no photon in a run; every other one here gets some.
void expect_run_agrees(const Scene& scene, const std::vector<std::size_t>& dark_targets) {
  const Results r = run_on_backend("embree", scene, 40'000, 3);
  for (std::size_t i = 0; i < r.targets.size(); ++i) {
    const bool called_dark =
        std::find(dark_targets.begin(), dark_targets.end(), i) != dark_targets.end();
    if (called_dark) {
      EXPECT_EQ(r.targets[i].estimate.hits, 0u) << r.targets[i].name;
    } else {
      EXPECT_GT(r.targets[i].estimate.hits, 0u) << r.targets[i].name;
    }
  }
}

TEST(DarkTargets, PointLightDarkensWhatFacesAwayFromIt) {
  Scene s = black_room();
  s.luminaires.push_back(point_light({2, 2, 1.5}, 1000));
  add_grids_at(s, 2.5);  // above the lamp: "up" faces away, "down" faces it
  add_grids_at(s, 0.8);  // below: "up" faces it, "down" faces away
  validate(s);
  const std::vector<std::size_t> d = dark(s);
  EXPECT_EQ(d, (std::vector<std::size_t>{0, 3}));
  expect_run_agrees(s, d);
}

TEST(DarkTargets, SpotLightsOnlyItsCone) {
  Scene s = black_room();
  s.luminaires.push_back(spot_light({2, 2, 2.0}, kDown, 40, 80, 1000));  // cone 40 deg wide
  add_grids_at(s, 2.5);  // above a downward spot: neither side can be reached
  add_grids_at(s, 0.8);  // below: only the upward face
  validate(s);
  const std::vector<std::size_t> d = dark(s);
  EXPECT_EQ(d, (std::vector<std::size_t>{0, 1, 3}));
  expect_run_agrees(s, d);
}

TEST(DarkTargets, AreaLuminaireEmitsIntoOneHalfSpace) {
  Scene s = black_room();
  Luminaire a;
  a.name = "panel";
  a.type = Luminaire::Type::Area;
  a.corner = {1.5, 1.5, 2.0};
  a.edge1 = {0, 1, 0};  // edge1 x edge2 = -z: emits downward
  a.edge2 = {1, 0, 0};
  a.flux_lm = 1000;
  s.luminaires.push_back(a);
  add_grids_at(s, 2.5);  // above: the whole panel is behind "up"; "down" is not judged dark
  add_grids_at(s, 0.8);
  validate(s);
  const std::vector<std::size_t> d = dark(s);
  // "down 2.5" faces the panel's back side only, but a hemisphere parallel to the target is an
  // edge case (grazing directions): not claimed. "down 0.8" and "up 2.5" are certain.
  EXPECT_EQ(d, (std::vector<std::size_t>{0, 3}));
  const Results r = run_on_backend("embree", s, 40'000, 3);
  EXPECT_EQ(r.targets[0].estimate.hits, 0u);
  EXPECT_EQ(r.targets[3].estimate.hits, 0u);
  EXPECT_GT(r.targets[2].estimate.hits, 0u);
}

TEST(DarkTargets, DirectionalBeamDarkensEveryFaceTurnedWithIt) {
  Scene s = black_room();
  Luminaire sun;
  sun.name = "sun";
  sun.type = Luminaire::Type::Directional;
  sun.corner = {0.5, 0.5, 2.9};
  sun.edge1 = {3, 0, 0};
  sun.edge2 = {0, 3, 0};
  sun.direction = kDown;
  sun.illuminance_lx = 1000;
  s.luminaires.push_back(sun);
  add_grids_at(s, 1.0);
  validate(s);
  const std::vector<std::size_t> d = dark(s);
  EXPECT_EQ(d, (std::vector<std::size_t>{1}));
  expect_run_agrees(s, d);
}

TEST(DarkTargets, SurfaceTargetNeedsEveryTriangleTurnedAway) {
  Scene s = black_room();
  s.luminaires.push_back(point_light({2, 2, 1.0}, 1000));
  s.targets.push_back(surface("room", 0));  // its floor faces the lamp
  // A shelf above the lamp whose only face looks up, away from it.
  s.meshes.push_back(quad_mesh("shelf top", 0, {1, 1, 2}, {1, 0, 0}, {0, 1, 0}));
  s.targets.push_back(surface("shelf top", 1));
  validate(s);
  const std::vector<std::size_t> d = dark(s);
  EXPECT_EQ(d, (std::vector<std::size_t>{1}));
  expect_run_agrees(s, d);
}

// The downlight file has light up to gamma = 77.5 deg (zero from 80 deg): its cone, to the cell
// edge at 80 deg, cannot reach anything that faces down above it, although it sits in front.
TEST(DarkTargets, PhotometricLuminaireLightsItsDistributionOnly) {
  Scene s = black_room();
  Luminaire l;
  l.name = "downlight";
  l.type = Luminaire::Type::Photometric;
  l.position = {2, 2, 2.5};
  l.aim = kDown;
  l.file = "downlight.ies";
  load_photometric(l, std::string(LIGHTSOLVER_SOURCE_DIR) + "/Resources/luminaires/downlight.ies",
                   std::nullopt, "flux_lm");
  s.luminaires.push_back(l);
  add_grids_at(s, 2.8);  // above: "up" is behind the lamp, "down" outside its cone
  add_grids_at(s, 0.8);  // below: "up" is lit, "down" is behind
  // Beside it, facing it: the cone reaches the wall's plane lower down, so not claimed.
  s.targets.push_back(grid("wall", {3.5, 1, 2.3}, {0, 0, 0.4}, {0, 2, 0}, 1, 1));
  validate(s);
  const std::vector<std::size_t> d = dark(s);
  EXPECT_EQ(d, (std::vector<std::size_t>{0, 1, 3}));
  const Results r = run_on_backend("embree", s, 40'000, 3);
  for (std::size_t i : d) EXPECT_EQ(r.targets[i].estimate.hits, 0u) << r.targets[i].name;
  EXPECT_GT(r.targets[2].estimate.hits, 0u);
}

TEST(DarkTargets, ObserversSeeNothingWithoutReflection) {
  Scene s = black_room();
  s.luminaires.push_back(point_light({2, 2, 2.5}, 1000));
  add_grids_at(s, 0.8);
  Target eye;
  eye.name = "eye";
  eye.type = Target::Type::Observer;
  eye.position = {2, 0.5, 1.2};
  eye.view_direction = {0, 1, 0};
  s.targets.push_back(eye);
  validate(s);
  const std::vector<std::size_t> d = dark(s);
  EXPECT_EQ(d, (std::vector<std::size_t>{1, 2}));
  expect_run_agrees(s, d);
}

// An observer grid's eyes are grid rows of their own (PreparedTarget): a grid listed after it
// is judged by its own row, not by an eye's (issue 23: the work plane below a panel was called
// dark because the check counted grid rows by hand and skipped the observer grid's).
Scene panel_over_black_floor() {
  Scene s;
  add_material(s, "black", Material::Type::Diffuse, 0.0);
  s.meshes.push_back(quad_mesh("floor", 0, {0, 0, 0}, {8, 0, 0}, {0, 4, 0}));
  Luminaire panel;
  panel.name = "panel";
  panel.type = Luminaire::Type::Area;
  panel.corner = {3.5, 1.5, 3.0};
  panel.edge1 = {0, 1, 0};  // edge1 x edge2 = -z: faces down
  panel.edge2 = {1, 0, 0};
  panel.flux_lm = 3400;
  s.luminaires.push_back(panel);
  return s;
}

Target one_eye_grid(const std::string& name) {
  Target eyes;
  eyes.name = name;
  eyes.type = Target::Type::ObserverGrid;
  eyes.positions = {{5.5, 2, 1.2}};
  eyes.view_directions = {{1, 0, 0}};
  return eyes;
}

TEST(DarkTargets, ObserverGridBeforeAGridLeavesTheGridItsOwnRow) {
  Scene s = panel_over_black_floor();
  s.targets.push_back(one_eye_grid("eyes"));
  s.targets.push_back(grid("work plane", {1, 0.5, 0.8}, {6, 0, 0}, {0, 3, 0}, 4, 3));
  validate(s);
  const std::vector<std::size_t> d = dark(s);
  EXPECT_EQ(d, (std::vector<std::size_t>{0}));  // the eyes see no reflected light; the plane is lit
  expect_run_agrees(s, d);
  const Results r = run_on_backend("embree", s, 40'000, 3);
  for (const std::string& w : r.warnings) EXPECT_EQ(w.find("work plane"), std::string::npos) << w;
}

// An observer grid alone: its record has grid rows and no mesh (no mesh index -1 to look up),
// on the run's path and on check_scene's.
TEST(DarkTargets, ObserverGridAloneIsJudgedByItsEyes) {
  Scene s = panel_over_black_floor();
  s.targets.push_back(one_eye_grid("eyes"));
  validate(s);
  EXPECT_EQ(dark(s), (std::vector<std::size_t>{0}));
  const SceneCheck check = check_scene(s);
  EXPECT_TRUE(check.errors.empty());
  const auto it = std::find_if(check.warnings.begin(), check.warnings.end(),
                               [](const auto& w) { return w.field == "targets[0]"; });
  ASSERT_NE(it, check.warnings.end());
  EXPECT_NE(it->message.find("counts reflected light only"), std::string::npos) << it->message;
  const Results r = run_on_backend("embree", s, 1000, 1);
  ASSERT_EQ(r.targets.size(), 1u);
  EXPECT_EQ(r.targets[0].estimate.hits, 0u);
}

TEST(DarkTargets, NothingIsClaimedWhenASurfaceReflects) {
  Scene s = black_room();
  s.materials[0].reflectance = 0.3;
  s.luminaires.push_back(point_light({2, 2, 1.5}, 1000));
  add_grids_at(s, 2.5);
  validate(s);
  EXPECT_TRUE(dark(s).empty());
}

TEST(DarkTargets, RunsAndTheCheckWarn) {
  Scene s = black_room();
  s.luminaires.push_back(point_light({2, 2, 1.5}, 1000));
  add_grids_at(s, 2.5);
  validate(s);
  const Results r = run_on_backend("embree", s, 1000, 1);
  const std::string expected =
      "targets[0] (\"up 2.500000\"): faces away from every luminaire and no surface reflects";
  auto has = [&](const std::vector<std::string>& ws) {
    return std::any_of(ws.begin(), ws.end(),
                       [&](const std::string& w) { return w.rfind(expected, 0) == 0; });
  };
  EXPECT_TRUE(has(r.warnings));
  const SceneCheck check = check_scene(s);
  ASSERT_TRUE(check.errors.empty());
  const auto it = std::find_if(check.warnings.begin(), check.warnings.end(),
                               [&](const auto& w) { return w.message.rfind(expected, 0) == 0; });
  ASSERT_NE(it, check.warnings.end());
  EXPECT_EQ(it->field, "targets[0]");
}

}  // namespace
}  // namespace lightsolver::test
