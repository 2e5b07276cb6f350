// Type conformance (issue 23): every row of the luminaire and target type tables is handled by
// every layer that asks a per-type question. A new row without an example here, or one a layer
// does not handle, fails: emission and its flux, reach (support and the target's record), glare
// shape, the effect and its name in the results schema, the bin layout that results,
// contributions and rescale read, and the type's name and result fields in the results schema.
// The GPU's rows (LS_LUMINAIRE_TYPES, Shaders/shared/luminaires.h) are held by vulkan_tests
// (GpuLuminaireTypes, Bindings.EmbeddedShaderHasEveryBinding); Python layers (workbench export,
// report) by Tests/python/test_type_tables.py.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "types/luminaire_types.hpp"
#include "model/prepared_scene.hpp"
#include "prepare/scene_effects.hpp"
#include "prepare/target_reach.hpp"
#include "types/target_types.hpp"
#include "lightsolver/photometry.hpp"
#include "lightsolver/rescale.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

const nlohmann::json& results_schema() {
  static const nlohmann::json schema = [] {
    std::ifstream in(std::string(LIGHTSOLVER_SOURCE_DIR) + "/docs/schemas/results.schema.json");
    return nlohmann::json::parse(in);
  }();
  return schema;
}

std::set<std::string> schema_enum(const nlohmann::json& node) {
  std::set<std::string> out;
  for (const auto& v : node.at("enum")) out.insert(v.get<std::string>());
  return out;
}

// One valid luminaire of each type, lighting the floor of a 4 x 4 x 3 m room from above.
Luminaire example_luminaire(Luminaire::Type type) {
  Luminaire l = point_light({2, 2, 2.5}, 1000);
  l.type = type;
  switch (type) {  // the test's own table of examples: a new type needs one here
    case Luminaire::Type::Point:
      break;
    case Luminaire::Type::Spot:
      l = spot_light({2, 2, 2.5}, {0, 0, -1}, 40, 80, 1000);
      break;
    case Luminaire::Type::Area:
    case Luminaire::Type::Directional:
    case Luminaire::Type::Sun:
      // The sun's opening (as a sky's portal below) lies in the ceiling's plane: an opening
      // under the closed ceiling would see it outside and, rightly, pass no light.
      l.corner = {1.5, 1.5, type == Luminaire::Type::Sun ? 3.0 : 2.9};
      l.edge1 = {0, 1, 0};  // edge1 x edge2 = -z
      l.edge2 = {1, 0, 0};
      l.direction = {0, 0, -1};
      l.illuminance_lx = 1000;
      break;
    case Luminaire::Type::Photometric:
      l.aim = {0, 0, -1};
      l.file = "downlight.ies";
      load_photometric(l,
                       std::string(LIGHTSOLVER_SOURCE_DIR) + "/Resources/luminaires/downlight.ies",
                       std::nullopt, "flux_lm");
      break;
    case Luminaire::Type::Sky:  // the uniform sky through a 1 m² opening in the ceiling
      l.sky.model = "uniform";
      l.sky.zenith_luminance_cd_m2 = 1000.0;
      l.sky.portals.push_back({{1.5, 1.5, 3.0}, {0, 1, 0}, {1, 0, 0}});
      break;
  }
  return l;
}

Scene room_with(const Luminaire& l) {
  Scene s;
  add_material(s, "grey", Material::Type::Diffuse, 0.5);
  s.meshes.push_back(room_mesh("room", 0, dvec3(0), dvec3(4, 4, 3)));
  s.luminaires.push_back(l);
  s.luminaires.back().name = "lamp";
  return s;
}

TEST(TypeConformance, EveryLuminaireRowIsHandledByEveryLayer) {
  const nlohmann::json& schema = results_schema();
  const std::set<std::string> effects = schema_enum(
      schema.at("properties").at("effects").at("properties").at("simulated").at("items"));
  std::set<std::string> names;
  ASSERT_LE(detail::luminaire_types().size(), detail::kMaxLuminaireTypes);
  for (const detail::LuminaireType& row : detail::luminaire_types()) {
    SCOPED_TRACE(row.name);
    EXPECT_TRUE(names.insert(row.name).second);
    EXPECT_TRUE(row.read && row.check && row.prepare && row.emit && row.emitted_flux &&
                row.support && row.glare && row.anchor && row.centre && row.move_to && row.aim);
    EXPECT_FALSE(row.keys.empty());
    // Its effect: named by the row, listed by the results schema, switched on by the analysis.
    EXPECT_STREQ(detail::effect_name(detail::emission_effect(row.type)), row.effect);
    EXPECT_TRUE(effects.contains(row.effect)) << "results.schema.json lacks " << row.effect;
    Scene s = room_with(example_luminaire(row.type));
    s.targets.push_back(grid("floor", {0.5, 0.5, 0.1}, {3, 0, 0}, {0, 3, 0}, 2, 2));
    validate(s);
    const detail::PreparedScene p = detail::prepare(s);
    EXPECT_TRUE(detail::analyse_effects(p).has(detail::emission_effect(row.type)));
    // Emission and flux as traced.
    EXPECT_EQ(p.luminaires[0].flux_lm, row.emitted_flux(s.luminaires[0]));
    EXPECT_GT(p.luminaires[0].flux_lm, 0.0);
    ASSERT_NE(p.luminaires[0].emit, nullptr);
    // Reach: where and in which directions it emits.
    const detail::EmissionSupport support = row.support(p.luminaires[0]);
    EXPECT_FALSE(support.points.empty());
    EXPECT_NEAR(glm::length(support.axis), 1.0, 1e-9);
    EXPECT_TRUE(support.half_angle_rad >= 0.0 && support.half_angle_rad <= std::numbers::pi);
    // Glare: of the row's kind, or none with a reason.
    const detail::GlareShape g = row.glare(s.luminaires[0]);
    EXPECT_EQ(g.kind, row.glare_kind);
    if (g.kind == detail::GlareShape::Kind::None) EXPECT_FALSE(g.why_not.empty());
    // A run: the floor grid below the lamp gets its light.
    const Results r = run_on_backend("embree", s, 20000, 1);
    EXPECT_GT(r.targets[0].estimate.hits, 0u);
  }
}

// A scene with one target of `type` (the test's table of examples: a new type needs one here).
Target example_target(Target::Type type) {
  Target t;
  t.name = "target";
  t.type = type;
  switch (type) {
    case Target::Type::Surface:
      t.mesh = 0;
      break;
    case Target::Type::Grid:
      t = grid("target", {0.5, 0.5, 0.8}, {3, 0, 0}, {0, 3, 0}, 3, 2);
      break;
    case Target::Type::Observer:
      t.position = {0.5, 2, 1.2};
      t.view_direction = {1, 0, 0};
      break;
    case Target::Type::ObserverGrid:
      t.positions = {{0.5, 1, 1.2}, {0.5, 3, 1.2}};
      t.view_step_deg = 90;
      break;
  }
  return t;
}

TEST(TypeConformance, EveryTargetRowIsHandledByEveryLayer) {
  const nlohmann::json& schema = results_schema();
  const nlohmann::json& target = schema.at("$defs").at("target");
  const std::set<std::string> type_names = schema_enum(target.at("properties").at("type"));
  std::set<std::string> fields;
  for (const auto& [key, _] : target.at("properties").items()) fields.insert(key);
  for (const detail::TargetType& row : detail::target_types()) {
    SCOPED_TRACE(row.name);
    EXPECT_TRUE(row.read && row.check && row.eyes && row.anchor && row.prepare && row.result);
    EXPECT_FALSE(row.keys.empty());
    EXPECT_TRUE(type_names.contains(row.name)) << "results.schema.json lacks type " << row.name;
    for (const char* f : row.result_fields) {
      EXPECT_TRUE(fields.contains(f)) << "results.schema.json lacks target field " << f;
    }
    Scene s = room_with(point_light({2, 2, 2.5}, 1000));
    s.targets.push_back(example_target(row.type));
    validate(s);
    const detail::PreparedScene p = detail::prepare(s);
    // Its record: the layout every reader takes.
    ASSERT_EQ(p.targets.size(), 1u);
    const detail::PreparedTarget& at = p.targets[0];
    const std::uint32_t eyes = row.eyes(s.targets[0]);
    EXPECT_EQ(at.points, eyes);
    EXPECT_EQ(at.cells, row.cells ? s.targets[0].nu * s.targets[0].nv : 0u);
    EXPECT_EQ(at.bin_count, eyes > 0 ? detail::kEyeBins * eyes : 1 + at.cells);
    EXPECT_EQ(at.bin + at.bin_count, p.bins.size());
    EXPECT_EQ(at.mesh >= 0, row.tally == detail::TallyKind::MeshBin);
    EXPECT_EQ(at.grid_rows, row.tally == detail::TallyKind::MeshBin ? 0u : std::max(eyes, 1u));
    EXPECT_EQ(at.first_grid + at.grid_rows, p.grids.size());
    for (std::uint32_t k = 0; k < at.grid_rows; ++k) {
      EXPECT_EQ(p.grids[at.first_grid + k].bin, eyes > 0 ? at.point_bin(k) : at.bin);
    }
    // Reach: judged from the record without error (something reflects: nothing is dark).
    EXPECT_TRUE(detail::dark_targets(s, p, detail::analyse_effects(p)).empty());
    // Results and rescale: the type's name, and a rescale at factor 1 rebuilds the estimate.
    s.settings.contributions = true;
    const Results r = run_on_backend("embree", s, 20000, 1);
    ASSERT_EQ(r.targets.size(), 1u);
    EXPECT_EQ(r.targets[0].type, row.name);
    EXPECT_GT(r.targets[0].estimate.hits, 0u);
    const Results again = rescale_results(results_to_json(r), {});
    EXPECT_EQ(again.targets[0].estimate.mean, r.targets[0].estimate.mean);
    EXPECT_EQ(again.targets[0].cells.size(), r.targets[0].cells.size());
  }
}

}  // namespace
}  // namespace lightsolver::test
