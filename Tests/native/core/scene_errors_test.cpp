// Bad input must produce a clear InputError naming the file and the field (or line), never a
// crash, hang or silent nonsense; recoverable problems produce warnings.
#include <gtest/gtest.h>

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
