// The luminaire-type table (core/luminaire_types.hpp): one complete row per Luminaire::Type,
// found by its scene-file name; the reader's message lists every name.
#include "core/luminaire_types.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "lightsolver/scene_io.hpp"

namespace lightsolver::test {
namespace {

using detail::find_luminaire_type;
using detail::luminaire_type;
using detail::luminaire_types;

constexpr Luminaire::Type kAll[] = {Luminaire::Type::Point, Luminaire::Type::Spot,
                                    Luminaire::Type::Area, Luminaire::Type::Directional,
                                    Luminaire::Type::Photometric};

TEST(LuminaireTypes, OneCompleteRowPerType) {
  EXPECT_EQ(luminaire_types().size(), std::size(kAll));
  std::set<std::string> names;
  for (Luminaire::Type type : kAll) {
    const detail::LuminaireType& row = luminaire_type(type);
    EXPECT_EQ(row.type, type);
    EXPECT_TRUE(row.read && row.check && row.prepare && row.emit && row.anchor) << row.name;
    EXPECT_TRUE(names.insert(row.name).second) << "duplicate name " << row.name;
    EXPECT_EQ(find_luminaire_type(row.name), &row);
  }
  EXPECT_EQ(find_luminaire_type("laser"), nullptr);
  EXPECT_EQ(find_luminaire_type(""), nullptr);
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
                       "spot, area, directional or photometric)"),
            std::string::npos)
      << error;
}

}  // namespace
}  // namespace lightsolver::test
