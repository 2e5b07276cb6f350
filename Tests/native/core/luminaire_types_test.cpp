// The luminaire-type table (types/luminaire_types.hpp): one complete row per Luminaire::Type,
// found by its scene-file name; the reader's message lists every name.
#include "types/luminaire_types.hpp"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <set>
#include <string>

#include "lightsolver/scene_io.hpp"

namespace lightsolver::test {
namespace {

using detail::find_luminaire_type;
using detail::luminaire_type;
using detail::luminaire_types;

constexpr Luminaire::Type kAll[] = {Luminaire::Type::Point,       Luminaire::Type::Spot,
                                    Luminaire::Type::Area,        Luminaire::Type::Directional,
                                    Luminaire::Type::Photometric, Luminaire::Type::Sun,
                                    Luminaire::Type::Sky};

TEST(LuminaireTypes, OneCompleteRowPerType) {
  EXPECT_EQ(luminaire_types().size(), std::size(kAll));
  std::set<std::string> names;
  for (Luminaire::Type type : kAll) {
    const detail::LuminaireType& row = luminaire_type(type);
    EXPECT_EQ(row.type, type);
    EXPECT_TRUE(row.read && row.check && row.prepare && row.emit && row.anchor && row.centre &&
                row.move_to && row.aim)
        << row.name;
    EXPECT_TRUE(names.insert(row.name).second) << "duplicate name " << row.name;
    EXPECT_EQ(find_luminaire_type(row.name), &row);
  }
  EXPECT_EQ(find_luminaire_type("laser"), nullptr);
  EXPECT_EQ(find_luminaire_type(""), nullptr);
}

// The optimizer's hooks: move_to puts centre() where asked without changing the shape; aim
// hooks hand out a field of the luminaire itself.
TEST(LuminaireTypes, PlacementHooksAgree) {
  for (Luminaire::Type type : kAll) {
    const detail::LuminaireType& row = luminaire_type(type);
    Luminaire l;
    l.type = type;
    l.position = {1, 2, 3};
    l.corner = {4, 5, 6};
    l.edge1 = {0.6, 0, 0};
    l.edge2 = {0, 1.2, 0};
    const glm::dvec3 target(-2.0, 7.5, 2.8);
    row.move_to(l, target);
    const glm::dvec3 c = row.centre(l);
    EXPECT_NEAR(glm::length(c - target), 0.0, 1e-12) << row.name;
    EXPECT_EQ(l.edge1, glm::dvec3(0.6, 0, 0)) << row.name;
    if (glm::dvec3* aim = row.aim(l)) {
      EXPECT_TRUE(aim == &l.direction || aim == &l.aim) << row.name;
    }
  }
  EXPECT_EQ(detail::aimable_luminaire_type_names(), "spot, directional, photometric or sun");
  EXPECT_FALSE(luminaire_type(Luminaire::Type::Directional).placed);
  EXPECT_FALSE(luminaire_type(Luminaire::Type::Sun).placed);
  // A sun placed by site and time is not aimed: its time is what moves it.
  Luminaire sun;
  sun.type = Luminaire::Type::Sun;
  sun.site = Site{45, 7, 0};
  EXPECT_EQ(luminaire_type(Luminaire::Type::Sun).aim(sun), nullptr);
  EXPECT_TRUE(luminaire_type(Luminaire::Type::Area).placed);
}

TEST(LuminaireTypes, UnknownTypeMessageListsEveryName) {
  const std::string scene = R"({"format": "lightsolver.scene/1",
    "materials": {"white": {"type": "diffuse", "reflectance": 0.7}},
    "meshes": [{"name": "floor", "material": "white",
                "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "triangles": [[0,1,2],[0,2,3]]}],
    "luminaires": [{"name": "lamp", "type": "laser", "flux_lm": 1000, "position": [0.5,0.5,2]}],
    "targets": [{"name": "floor", "type": "surface", "mesh": "floor"}]})";
  std::string error = "<no error>";
  try {
    scene_from_json(scene, "scene.json", ".");
  } catch (const InputError& e) {
    error = e.what();
  }
  EXPECT_NE(error.find("luminaires[0].type: unknown luminaire type \"laser\" (expected point, "
                       "spot, area, directional, photometric, sun or sky)"),
            std::string::npos)
      << error;
}

}  // namespace
}  // namespace lightsolver::test
