// Bad input must produce a clear InputError naming the file and the field (or line), never a
// crash, hang or silent nonsense; recoverable problems produce warnings.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "lightsolver/scene_io.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver::test {
namespace {

const std::string kData = LIGHTSOLVER_TEST_DATA;

// A valid scene; each test breaks one thing in it.
std::string valid_scene(const std::string& patch = "") {
  std::string s = R"({"format": "lightsolver.scene/1",
  "materials": {"white": {"type": "diffuse", "reflectance": 0.7}},
  "meshes": [{"name": "floor", "material": "white",
              "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "triangles": [[0,1,2],[0,2,3]]}],
  "luminaires": [{"name": "lamp", "type": "point", "flux_lm": 1000, "position": [0.5,0.5,2]}],
  "targets": [{"name": "floor", "type": "surface", "mesh": "floor"}],
  "settings": {"photons": 1000})";
  return s + patch + "}";
}

std::string error_of(const std::string& json) {
  try {
    scene_from_json(json, "scene.json", kData);
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no error>";
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const auto pos = s.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  return s.replace(pos, from.size(), to);
}

TEST(SceneErrors, ValidSceneLoads) {
  const Scene s = scene_from_json(valid_scene(), "scene.json", kData);
  EXPECT_EQ(s.meshes.size(), 1u);
  EXPECT_TRUE(s.warnings.empty());
}

TEST(SceneErrors, MalformedJsonNamesLineAndColumn) {
  const std::string e =
      error_of("{\n  \"format\": \"lightsolver.scene/1\",\n  \"materials\": {,}\n}");
  EXPECT_NE(e.find("scene.json: line 3"), std::string::npos) << e;
  EXPECT_NE(e.find("malformed JSON"), std::string::npos) << e;
}

TEST(SceneErrors, UnknownKeysAreErrors) {
  EXPECT_NE(error_of(valid_scene(R"(, "colour": 1)")).find("scene.json: colour: unknown key"),
            std::string::npos);
  const std::string e =
      error_of(replaced(valid_scene(), R"("flux_lm": 1000)", R"("flux_lm": 1000, "lumens": 5)"));
  EXPECT_NE(e.find("luminaires[0].lumens: unknown key"), std::string::npos) << e;
  EXPECT_NE(error_of(replaced(valid_scene(), R"("reflectance": 0.7)",
                              R"("reflectance": 0.7, "ior": 1.5)"))
                .find("materials.white.ior: unknown key"),
            std::string::npos);
}

TEST(SceneErrors, WrongTypesAndUnknownTypeNames) {
  EXPECT_NE(error_of(replaced(valid_scene(), R"("flux_lm": 1000)", R"("flux_lm": "bright")"))
                .find("luminaires[0].flux_lm: expected a number, got a string"),
            std::string::npos);
  EXPECT_NE(error_of(replaced(valid_scene(), R"("type": "point")", R"("type": "laser")"))
                .find("luminaires[0].type: unknown luminaire type \"laser\""),
            std::string::npos);
  EXPECT_NE(error_of(replaced(valid_scene(), R"("type": "diffuse")", R"("type": "velvet")"))
                .find("materials.white.type: unknown material type"),
            std::string::npos);
  EXPECT_NE(error_of(replaced(valid_scene(), R"("type": "surface")", R"("type": "volume")"))
                .find("targets[0].type: unknown target type"),
            std::string::npos);
  EXPECT_NE(error_of(replaced(valid_scene(), "lightsolver.scene/1", "lightsolver.scene/9"))
                .find("format: unsupported format"),
            std::string::npos);
  EXPECT_NE(
      error_of(replaced(valid_scene(), R"("position": [0.5,0.5,2])", R"("position": [0.5,0.5])"))
          .find("luminaires[0].position: expected [x, y, z]"),
      std::string::npos);
}

TEST(SceneErrors, MissingRequiredKey) {
  EXPECT_NE(error_of(replaced(valid_scene(), R"("flux_lm": 1000, )", ""))
                .find("luminaires[0]: missing required key \"flux_lm\""),
            std::string::npos);
}

TEST(SceneErrors, ValuesOutOfRange) {
  EXPECT_NE(error_of(replaced(valid_scene(), R"("flux_lm": 1000)", R"("flux_lm": -5)"))
                .find("luminaires[0].flux_lm: must be a finite value >= 0"),
            std::string::npos);
  EXPECT_NE(error_of(replaced(valid_scene(), R"("reflectance": 0.7)", R"("reflectance": 1.2)"))
                .find("materials.white.reflectance: must lie in 0..1"),
            std::string::npos);
  EXPECT_NE(error_of(replaced(valid_scene(), R"("photons": 1000)", R"("photons": 0)"))
                .find("settings.photons: must be at least 1"),
            std::string::npos);
  EXPECT_NE(error_of(replaced(valid_scene(), R"("photons": 1000)",
                              R"("photons": 1000, "confidence": 1.0)"))
                .find("settings.confidence"),
            std::string::npos);
  EXPECT_NE(error_of(replaced(valid_scene(), R"("photons": 1000)", R"("photons": -3)"))
                .find("settings.photons: must be >= 0"),
            std::string::npos);
}

TEST(SceneErrors, NonFiniteCoordinates) {
  // JSON has no NaN literal; 1e999 overflows to infinity and must be caught, not traced.
  const std::string overflow = error_of(replaced(valid_scene(), "[1,0,0]", "[1e999,0,0]"));
  EXPECT_NE(overflow.find("scene.json"), std::string::npos) << overflow;
  EXPECT_NE(overflow.find("number overflow"), std::string::npos) << overflow;
  Scene s = scene_from_json(valid_scene(), "scene.json", kData);
  s.meshes[0].vertices[2].y = std::nan("");
  try {
    validate(s);
    FAIL() << "NaN vertex accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("meshes[0].vertices[2]"), std::string::npos);
  }
}

TEST(SceneErrors, UnknownNamesReferenced) {
  EXPECT_NE(error_of(replaced(valid_scene(), R"("material": "white")", R"("material": "red")"))
                .find("meshes[0].material: unknown material \"red\""),
            std::string::npos);
  EXPECT_NE(error_of(replaced(valid_scene(), R"("mesh": "floor")", R"("mesh": "desk")"))
                .find("targets[0].mesh: unknown mesh \"desk\""),
            std::string::npos);
  EXPECT_NE(error_of(replaced(valid_scene(), "[0,2,3]", "[0,2,9]"))
                .find("meshes[0].triangles[1][2]: vertex index 9 out of range"),
            std::string::npos);
}

TEST(SceneErrors, DegenerateTrianglesDroppedWithWarning) {
  const Scene s = scene_from_json(
      replaced(valid_scene(), "[[0,1,2],[0,2,3]]", "[[0,1,2],[0,2,3],[0,0,1],[0,1,1]]"),
      "scene.json", kData);
  EXPECT_EQ(s.meshes[0].triangles.size(), 2u);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("dropped 2 degenerate"), std::string::npos) << s.warnings[0];
}

TEST(SceneErrors, ZeroAreaTargets) {
  EXPECT_NE(error_of(replaced(valid_scene(), "[[0,1,2],[0,2,3]]", "[[0,0,1]]"))
                .find("targets[0].mesh: mesh \"floor\" has zero area"),
            std::string::npos);
  const std::string grid = R"({"name": "g", "type": "grid", "corner": [0,0,1],
      "edge1": [1,0,0], "edge2": [2,0,0], "cells": [2,2]})";
  EXPECT_NE(error_of(replaced(valid_scene(),
                              R"({"name": "floor", "type": "surface", "mesh": "floor"})", grid))
                .find("targets[0].edge2: edge1 and edge2 are parallel"),
            std::string::npos);
}

TEST(SceneErrors, NoLuminaireOrNoTarget) {
  EXPECT_NE(
      error_of(
          replaced(valid_scene(),
                   R"({"name": "lamp", "type": "point", "flux_lm": 1000, "position": [0.5,0.5,2]})",
                   ""))
          .find("luminaires: the scene has no luminaire"),
      std::string::npos);
  EXPECT_NE(error_of(replaced(valid_scene(),
                              R"({"name": "floor", "type": "surface", "mesh": "floor"})", ""))
                .find("targets: the scene has no target"),
            std::string::npos);
}

TEST(SceneErrors, MeshFiles) {
  const std::string ok = R"({"name": "floor", "material": "white", "file": "triangle.ply"})";
  const std::string inline_mesh = R"({"name": "floor", "material": "white",
              "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "triangles": [[0,1,2],[0,2,3]]})";
  const Scene s = scene_from_json(replaced(valid_scene(), inline_mesh, ok), "scene.json", kData);
  EXPECT_EQ(s.meshes[0].triangles.size(), 1u);
  const Scene q = scene_from_json(
      replaced(valid_scene(), inline_mesh, replaced(ok, "triangle.ply", "quad.obj")), "scene.json",
      kData);
  EXPECT_EQ(q.meshes[0].triangles.size(), 2u);  // the quad face is triangulated
  EXPECT_TRUE(s.warnings.empty() && q.warnings.empty());
  // Georeferenced coordinates in a file: read in float, so the scene says how coarse they are
  // (0.5 m steps at 5.2e6 m) and how to avoid it.
  const Scene g = scene_from_json(
      replaced(valid_scene(), inline_mesh, replaced(ok, "triangle.ply", "georeferenced.obj")),
      "scene.json", kData);
  ASSERT_EQ(g.warnings.size(), 1u);
  for (const char* part : {"meshes[0] (\"georeferenced.obj\")", "coordinates reach 5.2e+06 m",
                           "500 mm steps", "\"transform\""}) {
    EXPECT_NE(g.warnings[0].find(part), std::string::npos) << part << " in " << g.warnings[0];
  }
  for (const char* bad : {"missing.ply", "truncated.ply", "garbage.obj"}) {
    const std::string e =
        error_of(replaced(valid_scene(), inline_mesh, replaced(ok, "triangle.ply", bad)));
    EXPECT_NE(e.find(bad), std::string::npos) << e;
    EXPECT_EQ(e.find("<no error>"), std::string::npos) << bad;
  }
}

TEST(SceneErrors, MissingSceneFile) {
  try {
    load_scene("/nonexistent/room.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/room.json: cannot open"), std::string::npos);
  }
}

TEST(SceneErrors, ImpossibleSolveOptions) {
  Scene s = scene_from_json(valid_scene(), "scene.json", kData);
  SolveOptions o;
  o.photons = 0;
  EXPECT_THROW(solve(s, o), InputError);
  o.photons = 10;
  o.confidence = 1.5;
  EXPECT_THROW(solve(s, o), InputError);
  o.confidence.reset();
  o.backend = "quantum";
  EXPECT_THROW(solve(s, o), InputError);
}

TEST(SceneErrors, SpotAndAreaGeometryChecks) {
  const std::string spot = R"({"name": "s", "type": "spot", "flux_lm": 100, "position": [0,0,2],
      "direction": [0,0,-1], "beam_angle_deg": 60, "field_angle_deg": 40})";
  const std::string lamp =
      R"({"name": "lamp", "type": "point", "flux_lm": 1000, "position": [0.5,0.5,2]})";
  EXPECT_NE(error_of(replaced(valid_scene(), lamp, spot)).find("beam_angle_deg < field_angle_deg"),
            std::string::npos);
  const std::string area = R"({"name": "a", "type": "area", "flux_lm": 100, "corner": [0,0,2],
      "edge1": [1,0,0], "edge2": [0,0,0]})";
  EXPECT_NE(error_of(replaced(valid_scene(), lamp, area))
                .find("luminaires[0].edge2: must not be the zero vector"),
            std::string::npos);
}

}  // namespace
}  // namespace lightsolver::test

namespace lightsolver::test {
namespace {

// Every error docs/scene-format.md states, one check each: the message names the file and the
// field. `patch` replaces `from` in the valid scene.
void expect_error(const std::string& from, const std::string& to, const std::string& expected) {
  const std::string e = error_of(replaced(valid_scene(), from, to));
  EXPECT_NE(e.find("scene.json: " + expected), std::string::npos)
      << "expected \"" << expected << "\" in: " << e;
}

const std::string kLamp =
    R"({"name": "lamp", "type": "point", "flux_lm": 1000, "position": [0.5,0.5,2]})";
const std::string kFloorTarget = R"({"name": "floor", "type": "surface", "mesh": "floor"})";
const std::string kMaterial = R"("white": {"type": "diffuse", "reflectance": 0.7})";
const std::string kTriangles = R"("triangles": [[0,1,2],[0,2,3]])";

TEST(SceneErrorsDocumented, MissingTopLevelKeys) {
  const std::string v = valid_scene();
  for (const char* key : {"format", "materials", "meshes", "luminaires", "targets"}) {
    nlohmann::json doc = nlohmann::json::parse(v);
    doc.erase(key);
    const std::string e = error_of(doc.dump());
    EXPECT_NE(e.find(std::string("scene.json: missing required key \"") + key + "\""),
              std::string::npos)
        << e;
  }
  EXPECT_EQ(error_of(replaced(v, R"(,
  "settings": {"photons": 1000})",
                              "")),
            "<no error>");  // settings are optional
}

TEST(SceneErrorsDocumented, MaterialRanges) {
  expect_error(kMaterial, R"("white": {"type": "mirror", "reflectance": -0.1})",
               "materials.white.reflectance: must lie in 0..1 (got -0.1)");
  expect_error(kMaterial, R"("white": {"type": "glass", "ior": 0.9})",
               "materials.white.ior: must lie in 1..10");
  expect_error(kMaterial, R"("white": {"type": "glass", "ior": 11})",
               "materials.white.ior: must lie in 1..10");
  expect_error(kMaterial, R"("white": {"type": "glass", "transmittance": 1.5})",
               "materials.white.transmittance: must lie in 0..1");
  expect_error(kMaterial, R"("white": {"type": "glass", "transmittance": -0.5})",
               "materials.white.transmittance: must lie in 0..1");
  expect_error(kMaterial, R"("white": {"type": "glossy", "reflectance": 0.6, "specular": 0.5})",
               "materials.white: reflectance + specular must not exceed 1");
  expect_error(kMaterial, R"("white": {"type": "glossy", "specular": 1.2})",
               "materials.white.specular: must lie in 0..1");
  expect_error(kMaterial, R"("white": {"type": "glossy", "roughness": 2})",
               "materials.white.roughness: must lie in 0..1");
  expect_error(kMaterial, R"("white": {"type": "glass", "thin": 1})",
               "materials.white.thin: expected true or false");
  // At the limits: accepted.
  EXPECT_EQ(error_of(replaced(valid_scene(), kMaterial,
                              R"("white": {"type": "glossy", "reflectance": 0.5, "specular": 0.5,
                                 "roughness": 1})")),
            "<no error>");
}

TEST(SceneErrorsDocumented, MeshNamesAreUnique) {
  const std::string mesh = R"({"name": "floor", "material": "white",
              "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "triangles": [[0,1,2],[0,2,3]]})";
  expect_error(mesh, mesh + ", " + mesh,
               "meshes[1].name: duplicate mesh name \"floor\" (also meshes[0])");
  Scene s = scene_from_json(valid_scene(), "scene.json", kData);
  s.meshes.push_back(s.meshes[0]);  // in memory too
  EXPECT_THROW(validate(s), InputError);
  s.meshes[1].name = "floor 2";
  EXPECT_NO_THROW(validate(s));
}

TEST(SceneErrorsDocumented, MeshGeometry) {
  expect_error(kTriangles, R"("triangles": [[0,1,2],[0,2]])",
               "meshes[0].triangles[1]: expected [i, j, k] (3 vertex indices)");
  expect_error(kTriangles, R"("triangles": [[0,1,2,3]])",
               "meshes[0].triangles[0]: expected [i, j, k]");
  expect_error("[1,1,0],", "[1,1],", "meshes[0].vertices[2]: expected [x, y, z]");
  expect_error(kTriangles, R"("triangles": [[0,1,-2]])",
               "meshes[0].triangles[0][2]: must be >= 0 (got -2)");
  expect_error(kTriangles, kTriangles + R"(, "file": "triangle.ply")",
               "meshes[0]: give either \"file\" or inline geometry");
  expect_error(R"(, "triangles": [[0,1,2],[0,2,3]])", "",
               "meshes[0]: missing required key \"triangles\"");
}

TEST(SceneErrorsDocumented, TransformShapeAndLastRow) {
  auto with = [](const std::string& t) { return kTriangles + R"(, "transform": )" + t; };
  expect_error(kTriangles, with("[[1,0,0,0],[0,1,0,0],[0,0,1,0]]"),
               "meshes[0].transform: expected a 4x4 matrix (4 rows of 4 numbers)");
  expect_error(kTriangles, with("[[1,0,0,0],[0,1,0,0],[0,0,1],[0,0,0,1]]"),
               "meshes[0].transform[2]: expected a row of 4 numbers");
  expect_error(kTriangles, with("[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,1,1]]"),
               "meshes[0].transform[3]: the last row of an affine transform must be [0, 0, 0, 1]");
  expect_error(kTriangles, with("[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,2]]"),
               "meshes[0].transform[3]: the last row");
  const Scene s = scene_from_json(
      replaced(valid_scene(), kTriangles, with("[[1,0,0,2.5],[0,1,0,0],[0,0,1,0],[0,0,0,1]]")),
      "scene.json", kData);
  EXPECT_EQ(s.meshes[0].vertices[1], glm::dvec3(3.5, 0, 0));  // applied to the vertices
}

TEST(SceneErrorsDocumented, SpotAngles) {
  auto spot = [](const std::string& beam, const std::string& field) {
    return R"({"name": "s", "type": "spot", "flux_lm": 100, "position": [0,0,2],
      "direction": [0,0,-1], "beam_angle_deg": )" +
           beam + R"(, "field_angle_deg": )" + field + "}";
  };
  expect_error(kLamp, spot("20", "361"), "luminaires[0].field_angle_deg: must be <= 360");
  expect_error(kLamp, spot("0", "40"),
               "luminaires[0].beam_angle_deg: need 0 < beam_angle_deg < field_angle_deg");
  expect_error(kLamp, spot("40", "40"), "luminaires[0].beam_angle_deg: need 0 < beam_angle_deg");
  expect_error(kLamp, spot("20", "40").replace(spot("20", "40").find("[0,0,-1]"), 8, "[0,0,0]"),
               "luminaires[0].direction: must not be the zero vector");
  EXPECT_EQ(error_of(replaced(valid_scene(), kLamp, spot("180", "360"))), "<no error>");
}

TEST(SceneErrorsDocumented, DirectionalBeamParallelToItsOpening) {
  const std::string sun = R"({"name": "sun", "type": "directional", "direction": [1,0,0],
      "corner": [0,0,2], "edge1": [1,0,0], "edge2": [0,1,0], "illuminance_lx": 1000})";
  expect_error(kLamp, sun, "luminaires[0].direction: the beam runs parallel to its parallelogram");
  expect_error(kLamp, replaced(sun, "1000", "-1"),
               "luminaires[0].illuminance_lx: must be a finite value >= 0 (got -1)");
  expect_error(kLamp, replaced(sun, "[0,1,0]", "[2,0,0]"),
               "luminaires[0].edge2: edge1 and edge2 are parallel: the area is zero");
  EXPECT_EQ(error_of(replaced(valid_scene(), kLamp, replaced(sun, "[1,0,0],", "[1,0,-1],"))),
            "<no error>");
}

TEST(SceneErrorsDocumented, PhotometricFluxAndFile) {
  const std::string lum = R"({"name": "d", "type": "photometric", "file": "FILE",
      "position": [0.5,0.5,2], "flux_lm": 1000})";
  const std::string file = std::string(LIGHTSOLVER_SOURCE_DIR) + "/Resources/luminaires/";
  expect_error(kLamp, replaced(replaced(lum, "FILE", file + "downlight.ies"), "1000", "-1"),
               "luminaires[0].flux_lm: must be a finite value >= 0");
  const std::string missing =
      error_of(replaced(valid_scene(), kLamp, replaced(lum, "FILE", "none.ies")));
  EXPECT_NE(missing.find("none.ies"), std::string::npos) << missing;
}

TEST(SceneErrorsDocumented, GridCells) {
  const std::string grid = R"({"name": "g", "type": "grid", "corner": [0,0,1],
      "edge1": [1,0,0], "edge2": [0,1,0], "cells": CELLS})";
  auto with = [&](const std::string& cells) { return replaced(grid, "CELLS", cells); };
  expect_error(kFloorTarget, with("[0, 4]"), "targets[0].cells: a grid needs at least 1x1 cells");
  expect_error(kFloorTarget, with("[4, 0]"), "targets[0].cells: a grid needs at least 1x1 cells");
  expect_error(kFloorTarget, with("[10000, 1001]"),
               "targets[0].cells: more than 10^7 cells in one grid");
  expect_error(kFloorTarget, with("[4]"), "targets[0].cells: expected [nu, nv]");
  expect_error(kFloorTarget, with("[4, 2.5]"), "targets[0].cells[1]: expected a non-negative");
  EXPECT_EQ(error_of(replaced(valid_scene(), kFloorTarget, with("[1000, 1000]"))), "<no error>");
}

TEST(SceneErrorsDocumented, Settings) {
  const std::string photons = R"("photons": 1000)";
  expect_error(photons, R"("photons": 1000, "max_bounces": 1000001)",
               "settings.max_bounces: must be <= 1000000");
  expect_error(photons, R"("photons": 1000, "max_bounces": -1)",
               "settings.max_bounces: must be >= 0");
  expect_error(photons, R"("photons": 1000, "confidence": 0)",
               "settings.confidence: must lie strictly between 0 and 1");
  expect_error(photons, R"("photons": 1000, "seed": 1.5)",
               "settings.seed: expected a non-negative");
  expect_error(photons, R"("photons": 1000, "threads": 2)", "settings.threads: unknown key");
  EXPECT_EQ(
      error_of(replaced(valid_scene(), photons,
                        R"("photons": 1000, "max_bounces": 0, "seed": 18446744073709551615)")),
      "<no error>");
}

}  // namespace
}  // namespace lightsolver::test
