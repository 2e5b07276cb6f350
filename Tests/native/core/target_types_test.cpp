// The target-type table (types/target_types.hpp): one complete row per Target::Type, found by
// its scene-file name; the reader's message lists every name; a task row's limits reach only
// the types that take them.
#include "types/target_types.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "lightsolver/scene_io.hpp"

namespace lightsolver::test {
namespace {

using detail::find_target_type;
using detail::target_type;
using detail::target_types;

constexpr Target::Type kAll[] = {Target::Type::Surface, Target::Type::Grid, Target::Type::Observer,
                                 Target::Type::ObserverGrid};

TEST(TargetTypes, OneCompleteRowPerType) {
  EXPECT_EQ(target_types().size(), std::size(kAll));
  std::set<std::string> names;
  for (Target::Type type : kAll) {
    const detail::TargetType& row = target_type(type);
    EXPECT_EQ(row.type, type);
    EXPECT_TRUE(row.read && row.check && row.anchor && row.prepare && row.result) << row.name;
    EXPECT_NE(row.requirements, 0u) << row.name << " takes no requirement";
    EXPECT_TRUE(row.other_requirements) << row.name;
    EXPECT_TRUE(names.insert(row.name).second) << "duplicate name " << row.name;
    EXPECT_EQ(find_target_type(row.name), &row);
  }
  EXPECT_EQ(find_target_type("volume"), nullptr);
  EXPECT_EQ(detail::target_type_names(), "surface, grid, observer or observer_grid");
}

TEST(TargetTypes, TheUnknownTypeMessageListsEveryRow) {
  const std::string scene = R"({"format": "lightsolver.scene/1",
    "materials": {"white": {"type": "diffuse", "reflectance": 0.7}}, "meshes": [],
    "luminaires": [{"name": "lamp", "type": "point", "flux_lm": 1000, "position": [0, 0, 2]}],
    "targets": [{"name": "t", "type": "volume"}]})";
  try {
    scene_from_json(scene, "scene.json", "");
    FAIL() << "an unknown target type was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("targets[0].type: unknown target type \"volume\" "
                                         "(expected surface, grid, observer or observer_grid)"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace lightsolver::test
