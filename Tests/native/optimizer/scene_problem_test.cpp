// The `optimization` block: parsing, one test per bad-input case (file and field named),
// applying values to a scene, the evaluator's contract and the U0 interval's coverage.
#include "lightsolver/optimizer/scene_problem.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

namespace lightsolver::optimizer {
namespace {

using nlohmann::json;

// A 4 x 4 x 3 m room (inline geometry), a box that may move, four kinds of luminaires, a
// surface and a grid target, and a valid optimization block to break.
json base_scene() {
  json room = {{"name", "floor"},
               {"material", "grey"},
               {"vertices", {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}}},
               {"triangles", {{0, 1, 2}, {0, 2, 3}}}};
  json cube = {
      {"name", "cube"},
      {"material", "grey"},
      {"vertices",
       {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}},
      {"triangles",
       {{0, 2, 1},
        {0, 3, 2},
        {4, 5, 6},
        {4, 6, 7},
        {0, 1, 5},
        {0, 5, 4},
        {3, 6, 2},
        {3, 7, 6},
        {0, 4, 7},
        {0, 7, 3},
        {1, 2, 6},
        {1, 6, 5}}}};
  return {
      {"format", "lightsolver.scene/1"},
      {"materials", {{"grey", {{"type", "diffuse"}, {"reflectance", 0.3}}}}},
      {"meshes", {room, cube}},
      {"luminaires",
       {{{"name", "p"}, {"type", "point"}, {"flux_lm", 1000}, {"position", {2, 2, 2.9}}},
        {{"name", "s"},
         {"type", "spot"},
         {"flux_lm", 500},
         {"position", {1, 1, 2.9}},
         {"direction", {0, 0, -1}},
         {"beam_angle_deg", 30},
         {"field_angle_deg", 60}},
        {{"name", "a"},
         {"type", "area"},
         {"flux_lm", 800},
         {"corner", {3, 3, 2.9}},
         {"edge1", {0, 0.4, 0}},
         {"edge2", {0.4, 0, 0}}},
        {{"name", "sun"},
         {"type", "directional"},
         {"direction", {0, 0, -1}},
         {"corner", {0, 0, 2.95}},
         {"edge1", {4, 0, 0}},
         {"edge2", {0, 4, 0}},
         {"illuminance_lx", 100}}}},
      {"targets",
       {{{"name", "cube"}, {"type", "surface"}, {"mesh", "cube"}},
        {{"name", "wp"},
         {"type", "grid"},
         {"corner", {0, 0, 0.8}},
         {"edge1", {4, 0, 0}},
         {"edge2", {0, 4, 0}},
         {"cells", {2, 2}}}}},
      {"optimization",
       {{"intention", {{"type", "maximize_uniformity"}, {"target", "wp"}, {"min_mean_lux", 10}}},
        {"variables",
         {{{"type", "position"},
           {"luminaire", "p"},
           {"corner", {0, 0, 2.9}},
           {"edge1", {4, 0, 0}},
           {"edge2", {0, 4, 0}},
           {"cells", {4, 4}}},
          {{"type", "translation"},
           {"mesh", "cube"},
           {"corner", {0, 0, 0}},
           {"edge1", {3, 0, 0}},
           {"edge2", {0, 3, 0}},
           {"cells", {3, 3}}},
          {{"type", "aim"},
           {"luminaire", "s"},
           {"angle", "tilt"},
           {"min_deg", 0},
           {"max_deg", 60},
           {"cells", 3}},
          {{"type", "flux"}, {"luminaires", {"p", "a"}}, {"levels_lm", {500, 1000, 2000}}}}},
        {"search", {{"seed", 3}, {"max_iterations", 5}, {"strategy", "refine_at_end"}}}}}};
}

SceneProblem parse_problem(const json& scene) {
  return problem_from_json(scene.dump(), "t.json", ".");
}

TEST(SceneProblem, ParsesTheDocumentedBlock) {
  const SceneProblem p = parse_problem(base_scene());
  ASSERT_EQ(p.domain.dimensions(), 6u);
  EXPECT_EQ(p.domain.variables()[0].name, "p.u");
  EXPECT_EQ(p.domain.variables()[2].name, "cube.u");
  EXPECT_EQ(p.domain.variables()[4].name, "s.tilt_deg");
  EXPECT_EQ(p.domain.variables()[5].name, "p+a.flux_lm");
  EXPECT_EQ(p.domain.cell_count(), 4u * 4 * 3 * 3 * 3 * 3);
  EXPECT_EQ(p.intention.constraints.size(), 1u);
  EXPECT_EQ(p.search.seed, 3u);
  EXPECT_EQ(p.search.strategy, PhotonStrategy::kRefineAtEnd);
  EXPECT_EQ(p.movable_meshes(), std::vector<std::string>{"cube"});
}

struct BadCase {
  const char* name;
  std::function<void(json&)> edit;  // applied to the optimization block
  const char* where;
  const char* message;  // a substring of the message
};

class BadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInput, NamesTheFileAndField) {
  json scene = base_scene();
  GetParam().edit(scene["optimization"]);
  try {
    parse_problem(scene);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "t.json");
    EXPECT_EQ(e.where(), GetParam().where) << e.what();
    EXPECT_NE(std::string(e.what()).find(GetParam().message), std::string::npos) << e.what();
  }
}

json& var(json& o, int i) { return o["variables"][i]; }

// Turns the cube a quarter at a time about the vertical through its default pivot. A value is
// its cell's centre, so quarter turns 0, 90, 180, 270 are the cells of [-45, 315].
json cube_rotation() {
  return {{"type", "rotation"}, {"mesh", "cube"}, {"min_deg", -45}, {"max_deg", 315}, {"cells", 4}};
}

json& with_rotation(json& o) {
  o["variables"].push_back(cube_rotation());
  return var(o, 4);
}

const BadCase kBadCases[] = {
    {"UnknownBlockKey", [](json& o) { o["goal"] = 1; }, "optimization.goal", "unknown key"},
    {"UnknownIntention", [](json& o) { o["intention"]["type"] = "maximize_joy"; },
     "optimization.intention.type", "unknown intention"},
    {"UnknownTarget", [](json& o) { o["intention"]["target"] = "nope"; },
     "optimization.intention.target", "unknown target"},
    {"UniformityOnSurface", [](json& o) { o["intention"]["target"] = "cube"; },
     "optimization.intention.target", "grid"},
    {"MissingBound", [](json& o) { o["intention"].erase("min_mean_lux"); },
     "optimization.intention", "min_mean_lux"},
    {"UniformityAboveOne",
     [](json& o) {
       o["intention"] = {{"type", "minimize_installed_flux"},
                         {"target", "wp"},
                         {"min_mean_lux", 1},
                         {"min_uniformity", 1.5}};
     },
     "optimization.intention.min_uniformity", "exceed 1"},
    {"NoVariables", [](json& o) { o["variables"] = json::array(); }, "optimization.variables",
     "at least one"},
    {"UnknownVariableType", [](json& o) { var(o, 0)["type"] = "colour"; },
     "optimization.variables[0].type", "unknown variable type"},
    {"UnknownLuminaire", [](json& o) { var(o, 0)["luminaire"] = "zz"; },
     "optimization.variables[0].luminaire", "unknown luminaire"},
    {"LuminaireAndLuminaires", [](json& o) { var(o, 0)["luminaires"] = {"a"}; },
     "optimization.variables[0]", "exactly one"},
    {"CellsNotAPair", [](json& o) { var(o, 1)["cells"] = {3}; }, "optimization.variables[1].cells",
     "[k, m]"},
    {"ZeroCells",
     [](json& o) {
       var(o, 1)["cells"] = {0, 3};
     },
     "optimization.variables[1].cells[0]", "between 1"},
    {"ParallelEdges",
     [](json& o) {
       var(o, 1)["edge2"] = {6, 0, 0};
     },
     "optimization.variables[1].edge2", "not parallel"},
    {"UnknownMesh", [](json& o) { var(o, 1)["mesh"] = "table"; }, "optimization.variables[1].mesh",
     "unknown mesh"},
    {"AimAPointLight", [](json& o) { var(o, 2)["luminaire"] = "p"; },
     "optimization.variables[2].luminaire", "can be aimed"},
    {"BadAngle", [](json& o) { var(o, 2)["angle"] = "roll"; }, "optimization.variables[2].angle",
     "tilt"},
    {"TiltBeyond180", [](json& o) { var(o, 2)["max_deg"] = 200; },
     "optimization.variables[2].max_deg", "[0, 180]"},
    {"FluxOfDirectional", [](json& o) { var(o, 3)["luminaires"] = {"sun"}; },
     "optimization.variables[3]", "directional"},
    {"NegativeLevel",
     [](json& o) {
       var(o, 3)["levels_lm"] = {100, -1};
     },
     "optimization.variables[3].levels_lm[1]", ">= 0"},
    {"LevelsAndRange", [](json& o) { var(o, 3)["cells"] = 3; }, "optimization.variables[3]",
     "either"},
    {"PositionTwice", [](json& o) { o["variables"].push_back(o["variables"][0]); },
     "optimization.variables[4]", "already set"},
    {"RotationUnknownMesh", [](json& o) { with_rotation(o)["mesh"] = "table"; },
     "optimization.variables[4].mesh", "unknown mesh"},
    {"RotationZeroAxis",
     [](json& o) {
       with_rotation(o)["axis"] = {0, 0, 0};
     },
     "optimization.variables[4].axis", "zero vector"},
    {"RotationBeyondOneTurn", [](json& o) { with_rotation(o)["max_deg"] = 400; },
     "optimization.variables[4].max_deg", "one turn"},
    {"RotationEmptyRange", [](json& o) { with_rotation(o)["max_deg"] = -45; },
     "optimization.variables[4].max_deg", "greater than min_deg"},
    {"RotationUnknownKey",
     [](json& o) {
       with_rotation(o)["centre"] = {0, 0, 0};
     },
     "optimization.variables[4].centre", "unknown key"},
    {"RotationTwice",
     [](json& o) {
       with_rotation(o);
       o["variables"].push_back(cube_rotation());
     },
     "optimization.variables[5].mesh", "already set"},
    {"WithinTwoPoints",
     [](json& o) {
       var(o, 0)["within"] = {{0, 0, 2.9}, {4, 0, 2.9}};
     },
     "optimization.variables[0].within", "at least 3 points"},
    {"WithinNoArea",
     [](json& o) {
       var(o, 0)["within"] = {{0, 0, 2.9}, {2, 2, 2.9}, {4, 4, 2.9}};
     },
     "optimization.variables[0].within", "no area"},
    {"WithinMissesEveryCell",
     [](json& o) {
       var(o, 0)["within"] = {{5, 5, 2.9}, {6, 5, 2.9}, {6, 6, 2.9}};
     },
     "optimization.variables[0].within", "no cell centre"},
    {"WithinBadPoint",
     [](json& o) {
       var(o, 1)["within"] = {{0, 0}, {1, 0}, {0, 1}};
     },
     "optimization.variables[1].within[0]", "[x, y, z]"},
    {"WithinHoleTwoPoints",
     [](json& o) {
       var(o, 0)["within"] = {{"outer", {{0, 0, 2.9}, {4, 0, 2.9}, {4, 4, 2.9}}},
                              {"holes", {{{1, 1, 2.9}, {2, 1, 2.9}}}}};
     },
     "optimization.variables[0].within.holes[0]", "at least 3 points"},
    {"WithinUnknownKey",
     [](json& o) {
       var(o, 0)["within"] = {{"outer", {{0, 0, 2.9}, {4, 0, 2.9}, {4, 4, 2.9}}}, {"inner", 1}};
     },
     "optimization.variables[0].within.inner", "unknown key"},
    {"InitialOutsideWithin",
     [](json& o) {
       var(o, 0)["within"] = {{0, 0, 2.9}, {2, 0, 2.9}, {2, 2, 2.9}, {0, 2, 2.9}};
       o["search"]["initial"] = {{0, 0, 0, 0, 0, 0}, {3, 3, 0, 0, 0, 0}};
     },
     "optimization.search.initial[1]", "outside its variable's `within`"},
    {"BadStrategy", [](json& o) { o["search"]["strategy"] = "guess"; },
     "optimization.search.strategy", "confirm"},
    {"BadConfidence", [](json& o) { o["search"]["confidence"] = 1.5; },
     "optimization.search.confidence", "between 0 and 1"},
    {"ZeroConfirmation", [](json& o) { o["search"]["confirmation_photons"] = 0; },
     "optimization.search.confirmation_photons", "at least 1"},
    {"UnknownSearchKey", [](json& o) { o["search"]["temperature"] = 3; },
     "optimization.search.temperature", "unknown key"},
    {"InitialWrongLength",
     [](json& o) {
       o["search"]["initial"] = {{0, 0}};
     },
     "optimization.search.initial[0]", "6 cell indices"},
    {"InitialOutOfRange",
     [](json& o) {
       o["search"]["initial"] = {{0, 4, 0, 0, 0, 0}};
     },
     "optimization.search.initial[0][1]", "out of range"},
};

INSTANTIATE_TEST_SUITE_P(SceneProblem, BadInput, ::testing::ValuesIn(kBadCases),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(SceneProblem, MissingBlockIsAnError) {
  json scene = base_scene();
  scene.erase("optimization");
  try {
    parse_problem(scene);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where(), "optimization");
  }
}

TEST(SceneProblem, ValuesMoveAimAndDimTheScene) {
  json scene = base_scene();
  // Move the area light and the point together: the point keeps its offset to the panel.
  scene["optimization"]["variables"][0] = {{"type", "position"},    {"luminaires", {"a", "p"}},
                                           {"corner", {0, 0, 2.9}}, {"edge1", {4, 0, 0}},
                                           {"edge2", {0, 4, 0}},    {"cells", {4, 4}}};
  scene["optimization"]["variables"][3] = {
      {"type", "flux"}, {"luminaire", "s"}, {"min_lm", 0}, {"max_lm", 1000}, {"cells", 4}};
  scene["optimization"]["variables"].push_back({{"type", "aim"},
                                                {"luminaire", "s"},
                                                {"angle", "pan"},
                                                {"min_deg", 0},
                                                {"max_deg", 360},
                                                {"cells", 4}});
  const SceneProblem p = parse_problem(scene);
  // u = 0.125, v = 0.375 (cells 0, 1); cube to (1.5, 0.5); tilt 30; flux 375; pan 135.
  const std::vector<double> values = p.domain.values({0, 1, 1, 0, 1, 1, 1});
  const Scene s = apply_values(p, values);
  const Luminaire &a = s.luminaires[2], &pt = s.luminaires[0], &spot = s.luminaires[1];
  const glm::dvec3 centre = a.corner + 0.5 * (a.edge1 + a.edge2);
  EXPECT_NEAR(centre.x, 0.5, 1e-12);
  EXPECT_NEAR(centre.y, 1.5, 1e-12);
  EXPECT_NEAR(pt.position.x - centre.x, 2.0 - 3.2, 1e-12);  // loaded offset kept
  EXPECT_NEAR(pt.position.y - centre.y, 2.0 - 3.2, 1e-12);
  EXPECT_NEAR(spot.flux_lm, 375.0, 1e-9);
  const double t = 30 * M_PI / 180, ph = 135 * M_PI / 180;
  EXPECT_NEAR(spot.direction.x, std::sin(t) * std::cos(ph), 1e-12);
  EXPECT_NEAR(spot.direction.y, std::sin(t) * std::sin(ph), 1e-12);
  EXPECT_NEAR(spot.direction.z, -std::cos(t), 1e-12);
  EXPECT_NEAR(s.meshes[1].vertices[0].x, 1.5, 1e-12);  // anchor (origin) onto (1.5, 0.5, 0)
  EXPECT_NEAR(s.meshes[1].vertices[0].y, 0.5, 1e-12);
  const auto d = describe_values(p, values);
  EXPECT_NEAR(d.at("cube")[0], 1.5, 1e-12);
  EXPECT_NEAR(d.at("s.flux_lm")[0], 375.0, 1e-9);
}

TEST(SceneEvaluator, SameRequestSameEstimatesAndMovedGeometryMatchesARebuiltScene) {
  const SceneProblem p = parse_problem(base_scene());
  SceneEvaluator ev(p, 2, kAutoBackend, nullptr, /*reuse_traces=*/false);  // one run, one seed
  const Configuration cells{1, 2, 2, 0, 1, 2};
  const std::vector<double> values = p.domain.values(cells);
  const EvaluationRequest req{cells, values, p.domain.index(cells), 20000, 42};
  const Evaluation first = ev.evaluate(req);
  ev.evaluate({Configuration{0, 0, 0, 0, 0, 0}, p.domain.values({0, 0, 0, 0, 0, 0}), 0, 20000, 7});
  const Evaluation again = ev.evaluate(req);
  EXPECT_EQ(first.objective.mean, again.objective.mean);
  EXPECT_EQ(first.constraints.at(0).mean, again.constraints.at(0).mean);
  EXPECT_GT(first.trace_seconds, 0.0);
  EXPECT_GE(first.update_seconds, 0.0);
  // The instance-transformed cube sees what a scene rebuilt with moved vertices sees.
  SolveOptions o;
  o.photons = 20000;
  o.seed = 42;
  const Results rebuilt = solve(apply_values(p, values), o);
  EXPECT_NEAR(ev.last_results().targets[0].estimate.mean, rebuilt.targets[0].estimate.mean,
              1e-3 * rebuilt.targets[0].estimate.mean);
}

// A rotation turns the mesh about its pivot: the bounding-box centre alone, the translation's
// anchor when the mesh also moves (the anchor then still lands on its rectangle).
TEST(SceneProblem, RotationTurnsAboutThePivotThenTranslates) {
  json alone = base_scene();
  var(alone["optimization"], 1) = cube_rotation();
  const SceneProblem r = parse_problem(alone);
  EXPECT_EQ(r.domain.variables()[2].name, "cube.rotation_deg");
  EXPECT_EQ(r.movable_meshes(), std::vector<std::string>{"cube"});
  // Cells: p (0, 0), rotation 1 (90 degrees), tilt 0, flux 0.
  const std::vector<double> quarter = r.domain.values({0, 0, 1, 0, 0});
  EXPECT_DOUBLE_EQ(quarter[2], 90.0);
  Scene s = apply_values(r, quarter);
  // About the vertical through (0.5, 0.5): (0, 0, 0) -> (1, 0, 0); (1, 1, 1) -> (0, 1, 1).
  EXPECT_NEAR(glm::distance(s.meshes[1].vertices[0], glm::dvec3(1, 0, 0)), 0.0, 1e-12);
  EXPECT_NEAR(glm::distance(s.meshes[1].vertices[6], glm::dvec3(0, 1, 1)), 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(describe_values(r, quarter).at("cube.rotation_deg")[0], 90.0);

  json both = base_scene();
  both["optimization"]["variables"].push_back(cube_rotation());
  const SceneProblem t = parse_problem(both);
  EXPECT_EQ(t.movable_meshes(), std::vector<std::string>{"cube"});  // listed once
  // Translation cells (1, 0): anchor (origin) onto (1.5, 0.5, 0); rotation cell 1: 90 degrees.
  s = apply_values(t, t.domain.values({0, 0, 1, 0, 0, 0, 1}));
  EXPECT_NEAR(glm::distance(s.meshes[1].vertices[0], glm::dvec3(1.5, 0.5, 0)), 0.0, 1e-12);
  EXPECT_NEAR(glm::distance(s.meshes[1].vertices[1], glm::dvec3(1.5, 1.5, 0)), 0.0, 1e-12);
  // Another axis and an explicit pivot: half a turn about x through (0, 0.5, 0.5) takes the
  // origin to (0, 1, 1); translation cells (0, 0) then shift it by (0.5, 0.5, 0).
  var(both["optimization"], 4)["axis"] = {2, 0, 0};
  var(both["optimization"], 4)["pivot"] = {0, 0.5, 0.5};
  const SceneProblem x = parse_problem(both);
  s = apply_values(x, x.domain.values({0, 0, 0, 0, 0, 0, 2}));
  EXPECT_NEAR(glm::distance(s.meshes[1].vertices[0], glm::dvec3(0.5, 1.5, 1)), 0.0, 1e-12);
}

// Instances carry the rotation: what the evaluator traces equals a scene rebuilt with the
// turned vertices (same seed: same photons, bit-for-bit up to float rounding of the transform).
TEST(SceneEvaluator, RotatedGeometryMatchesARebuiltScene) {
  json scene = base_scene();
  scene["optimization"]["variables"].push_back(cube_rotation());
  var(scene["optimization"], 4)["max_deg"] = 75;  // -30, 0, 30, 60: no symmetry helps
  const SceneProblem p = parse_problem(scene);
  SceneEvaluator ev(p, 2, kAutoBackend, nullptr, /*reuse_traces=*/false);  // one run, one seed
  const Configuration cells{1, 2, 1, 1, 1, 2, 2};  // the cube turned 30 degrees
  const std::vector<double> values = p.domain.values(cells);
  ASSERT_DOUBLE_EQ(values[6], 30.0);
  ev.evaluate({cells, values, p.domain.index(cells), 20000, 42});
  SolveOptions o;
  o.photons = 20000;
  o.seed = 42;
  const Results rebuilt = solve(apply_values(p, values), o);
  for (std::size_t t = 0; t < rebuilt.targets.size(); ++t) {
    EXPECT_NEAR(ev.last_results().targets[t].estimate.mean, rebuilt.targets[t].estimate.mean,
                1e-3 * rebuilt.targets[t].estimate.mean)
        << rebuilt.targets[t].name;
  }
}

// The point light on the 4 x 4 ceiling (cells 1 m) limited to `within`, maximising the mean
// illuminance of a 1 m square target at the workplane with corner (x, y).
SceneProblem ceiling_within(const json& within, double x, double y, std::uint64_t seed) {
  json scene = base_scene();
  scene["targets"].push_back({{"name", "goal"},
                              {"type", "grid"},
                              {"corner", {x, y, 0.8}},
                              {"edge1", {1, 0, 0}},
                              {"edge2", {0, 1, 0}},
                              {"cells", {1, 1}}});
  json& o = scene["optimization"];
  o["intention"] = {{"type", "maximize_mean_illuminance"}, {"target", "goal"}};
  o["variables"] = {{{"type", "position"},
                     {"luminaire", "p"},
                     {"corner", {0, 0, 2.9}},
                     {"edge1", {4, 0, 0}},
                     {"edge2", {0, 4, 0}},
                     {"cells", {4, 4}},
                     {"within", within}}};
  o["search"] = {{"seed", seed},
                 {"max_iterations", 40},
                 {"screening_photons", 20000},
                 {"confirmation_photons", 200000}};
  return parse_problem(scene);
}

// An L-shaped ceiling: the point light may not go over the room's missing quadrant (x, y > 2),
// where the target wants it. Every cell there is skipped, never traced; the optimum is one of
// the admissible cells nearest the target's centre (3, 3): (2.5, 1.5), (1.5, 2.5), (3.5, 1.5)
// and (1.5, 3.5), all sqrt(2.5) m away and lighting the square target alike by its symmetry
// (only the small cube's faint reflections differ, far below the noise), so which of them a
// seed picks is noise.
TEST(SceneProblem, WithinKeepsTheSearchOnAnLShapedCeiling) {
  const SceneProblem p = ceiling_within(
      {{0, 0, 2.9}, {4, 0, 2.9}, {4, 2, 2.9}, {2, 2, 2.9}, {2, 4, 2.9}, {0, 4, 2.9}}, 2.5, 2.5, 5);
  ASSERT_TRUE(p.search.admissible);
  const OptimizationResult r = run_problem(p, {});
  EXPECT_GT(r.counters.inadmissible, 0u);
  ASSERT_FALSE(r.isoc.empty());
  for (const ResultMember& m : r.isoc) {
    const double x = 4 * m.values[0], y = 4 * m.values[1];
    EXPECT_FALSE(x > 2 && y > 2) << "member at (" << x << ", " << y << ") is off the ceiling";
  }
  const double x = 4 * r.isoc[0].values[0], y = 4 * r.isoc[0].values[1];
  EXPECT_NEAR(std::hypot(x - 3.0, y - 3.0), std::sqrt(2.5), 1e-12) << x << ", " << y;
}

// A column through the middle of the ceiling: the cell right above the target is a hole, so the
// light goes next to it (one of the four neighbours, all 1 m away), never into it.
TEST(SceneProblem, WithinHolesKeepTheSearchOffAColumn) {
  const json within = {
      {"outer", {{0, 0, 2.9}, {4, 0, 2.9}, {4, 4, 2.9}, {0, 4, 2.9}}},
      {"holes", {{{2.1, 2.1, 2.9}, {2.9, 2.1, 2.9}, {2.9, 2.9, 2.9}, {2.1, 2.9, 2.9}}}}};
  const OptimizationResult r = run_problem(ceiling_within(within, 2, 2, 2), {});
  EXPECT_EQ(r.counters.inadmissible, 1u);  // the one cell under the column, judged once
  ASSERT_FALSE(r.isoc.empty());
  for (const ResultMember& m : r.isoc) {
    EXPECT_FALSE(m.values[0] == 0.625 && m.values[1] == 0.625) << "a member in the column";
  }
  const double x = 4 * r.isoc[0].values[0], y = 4 * r.isoc[0].values[1];
  EXPECT_NEAR(std::hypot(x - 2.5, y - 2.5), 1.0, 1e-12) << x << ", " << y;
}

TEST(SceneEvaluator, InstalledFluxIsExact) {
  json scene = base_scene();
  scene["optimization"]["intention"] = {{"type", "minimize_installed_flux"},
                                        {"target", "wp"},
                                        {"min_mean_lux", 1},
                                        {"min_uniformity", 0.1}};
  const SceneProblem p = parse_problem(scene);
  SceneEvaluator ev(p, 2);
  const Configuration cells{0, 0, 0, 0, 0, 2};  // p and a at 2000 lm
  const auto values = p.domain.values(cells);
  const Evaluation e = ev.evaluate({cells, values, p.domain.index(cells), 1000, 1});
  const double flux = 2000 + 500 + 2000 + directional_flux_lm(p.scene.luminaires[3]);
  EXPECT_DOUBLE_EQ(e.objective.mean, flux);
  EXPECT_EQ(e.objective.sigma, 0.0);
  EXPECT_EQ(e.objective.ci_low, e.objective.ci_high);
}

// U0's interval must cover the true min/mean at least at the stated confidence. Truth: a run
// with 400x the photons; 100 independent small runs; with coverage >= 0.95 the chance of fewer
// than 90 covering is 0.3 % (binomial), so the bound is not tuned to the outcome.
TEST(Uniformity, IntervalCoversTheTruth) {
  json scene = base_scene();
  scene["luminaires"][3]["illuminance_lx"] = 0;  // keep it simple: point, spot, panel
  const Scene s = parse_problem(scene).scene;
  Simulation sim(s, Simulation::Options{"auto", 2, {}});
  SolveOptions o;
  o.photons = 4'000'000;
  const Results truth = sim.run(o);
  const TargetResult& g = truth.targets[1];
  const double u_true = g.min_lux / g.estimate.mean;
  int covered = 0;
  for (int i = 0; i < 100; ++i) {
    o.photons = 10000;
    o.seed = 1000 + i;
    o.confidence = 0.95;
    const Results r = sim.run(o);
    o.confidence = uniformity_confidence(r.targets[1].cells.size(), 0.95);
    const Results wide = sim.run(o);  // the same photons, the family's level
    const Estimate u = uniformity_estimate(r.targets[1], wide.targets[1], 0.95);
    EXPECT_LE(u.ci_low, u.mean);
    EXPECT_GE(u.ci_high, u.mean);
    EXPECT_LE(u.ci_high, 1.0);
    covered += u.ci_low <= u_true && u_true <= u.ci_high;
  }
  EXPECT_GE(covered, 90) << "true U0 " << u_true;
}

}  // namespace
}  // namespace lightsolver::optimizer
