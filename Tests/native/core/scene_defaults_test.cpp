// Material defaults and format tags are defined once (lightsolver/defaults.hpp): the scene
// reader, default_material() and the in-memory Material agree with each other and with the
// documented values (docs/scene-format.md, "Materials").
#include <gtest/gtest.h>

#include <string>

#include "lightsolver/defaults.hpp"
#include "lightsolver/scene_io.hpp"

namespace lightsolver::test {
namespace {

void expect_same(const Material& a, const Material& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.type, b.type) << a.name;
  EXPECT_EQ(a.reflectance, b.reflectance) << a.name;
  EXPECT_EQ(a.ior, b.ior) << a.name;
  EXPECT_EQ(a.transmittance, b.transmittance) << a.name;
  EXPECT_EQ(a.thin, b.thin) << a.name;
  EXPECT_EQ(a.specular, b.specular) << a.name;
  EXPECT_EQ(a.roughness, b.roughness) << a.name;
}

TEST(SceneDefaults, DocumentedValues) {
  using T = Material::Type;
  EXPECT_EQ(default_material("d", T::Diffuse).reflectance, 0.5);
  EXPECT_EQ(default_material("m", T::Mirror).reflectance, 0.9);
  const Material glass = default_material("g", T::Glass);
  EXPECT_EQ(glass.ior, 1.52);
  EXPECT_EQ(glass.transmittance, 1.0);
  EXPECT_FALSE(glass.thin);
  const Material glossy = default_material("s", T::Glossy);
  EXPECT_EQ(glossy.reflectance, 0.0);
  EXPECT_EQ(glossy.specular, 0.5);
  EXPECT_EQ(glossy.roughness, 0.2);
  expect_same(Material{"d"}, default_material("d", T::Diffuse));
  EXPECT_STREQ(kSceneFormat, "lightsolver.scene/1");
  EXPECT_STREQ(kResultsFormat, "lightsolver.results/1");
  EXPECT_STREQ(kOptimizationFormat, "lightsolver.optimization/1");
}

TEST(SceneDefaults, KeysLeftOutGetTheDefaults) {
  const Scene s = scene_from_json(std::string(R"({"format": ")") + kSceneFormat + R"(",
    "materials": {"d": {"type": "diffuse"}, "m": {"type": "mirror"}, "g": {"type": "glass"},
                  "s": {"type": "glossy"}, "x": {"type": "glossy", "roughness": 0.7}},
    "meshes": [{"name": "floor", "material": "d", "vertices": [[0,0,0],[1,0,0],[0,1,0]],
                "triangles": [[0,1,2]]}],
    "luminaires": [{"name": "lamp", "type": "point", "flux_lm": 1, "position": [0,0,1]}],
    "targets": [{"name": "floor", "type": "surface", "mesh": "floor"}]})",
                                  "scene.json", ".");
  using T = Material::Type;
  expect_same(s.materials.at(s.find_material("d")), default_material("d", T::Diffuse));
  expect_same(s.materials.at(s.find_material("m")), default_material("m", T::Mirror));
  expect_same(s.materials.at(s.find_material("g")), default_material("g", T::Glass));
  expect_same(s.materials.at(s.find_material("s")), default_material("s", T::Glossy));
  Material x = default_material("x", T::Glossy);
  x.roughness = 0.7;  // a given key is kept, the others default
  expect_same(s.materials.at(s.find_material("x")), x);
}

}  // namespace
}  // namespace lightsolver::test
