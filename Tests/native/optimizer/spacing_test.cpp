// Never two luminaires in one place: position variables of several luminaires (a placement
// domain's template and its copies) all want the cell over a small target; the search may not
// generate, trace or return a configuration that stacks them, nor one closer than
// min_spacing_m, nor one on top of a luminaire no variable moves.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lightsolver/optimizer/scene_problem.hpp"

namespace lightsolver::optimizer {
namespace {

using nlohmann::json;

constexpr int kCells = 4;  // 4 x 4 cells on a 4 x 4 m ceiling: centres 1 m apart

// A 4 x 4 m floor, `movers` point lights (each its own position variable on the ceiling), one
// fixed light at (`fixed_x`, `fixed_y`), and a 1 x 1 m grid target in the corner (x, y in
// [3, 4]): every light wants the cell centred at (3.5, 3.5).
json scene(int movers, double fixed_x, double fixed_y, double min_spacing_m) {
  json floor = {{"name", "floor"},
                {"material", "grey"},
                {"vertices", {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}}},
                {"triangles", {{0, 1, 2}, {0, 2, 3}}}};
  json lights = json::array(), variables = json::array();
  for (int i = 0; i < movers; ++i) {
    const std::string name = "lum" + std::to_string(i);
    lights.push_back(
        {{"name", name}, {"type", "point"}, {"flux_lm", 1000}, {"position", {0.5, 0.5, 2.9}}});
    variables.push_back({{"type", "position"},
                         {"luminaire", name},
                         {"corner", {0, 0, 2.9}},
                         {"edge1", {4, 0, 0}},
                         {"edge2", {0, 4, 0}},
                         {"cells", {kCells, kCells}}});
  }
  lights.push_back({{"name", "fixed"},
                    {"type", "point"},
                    {"flux_lm", 10},
                    {"position", {fixed_x, fixed_y, 2.9}}});
  return {{"format", "lightsolver.scene/1"},
          {"materials", {{"grey", {{"type", "diffuse"}, {"reflectance", 0.3}}}}},
          {"meshes", {floor}},
          {"luminaires", lights},
          {"targets",
           {{{"name", "corner"},
             {"type", "grid"},
             {"corner", {3, 3, 0.0}},
             {"edge1", {1, 0, 0}},
             {"edge2", {0, 1, 0}},
             {"cells", {1, 1}}}}},
          {"optimization",
           {{"intention", {{"type", "maximize_mean_illuminance"}, {"target", "corner"}}},
            {"variables", variables},
            {"search",
             {{"seed", 5},
              {"max_iterations", 30},
              {"min_spacing_m", min_spacing_m},
              {"screening_photons", 4000},
              {"confirmation_photons", 40000}}}}}};
}

SceneProblem parse_spacing(const json& s) {
  return problem_from_json(s.dump(), "spacing.json", ".");
}

// (x, y) of mover k in a configuration: cell centres are (i + 0.5) m.
std::pair<double, double> place(const Configuration& c, int k) {
  return {c[2 * k] + 0.5, c[2 * k + 1] + 0.5};
}

double smallest_distance(const Configuration& c, int movers, double fx, double fy) {
  double d = INFINITY;
  for (int a = 0; a < movers; ++a) {
    const auto [xa, ya] = place(c, a);
    d = std::min(d, std::hypot(xa - fx, ya - fy));
    for (int b = a + 1; b < movers; ++b) {
      const auto [xb, yb] = place(c, b);
      d = std::min(d, std::hypot(xa - xb, ya - yb));
    }
  }
  return d;
}

TEST(Spacing, TwoLuminairesInOneCellAreNotAdmissible) {
  const SceneProblem p = parse_spacing(scene(2, 0.0, 0.0, 0.0));
  ASSERT_TRUE(p.search.admissible);
  EXPECT_FALSE(p.search.admissible({3, 3, 3, 3}));  // both at (3.5, 3.5)
  EXPECT_TRUE(p.search.admissible({3, 3, 2, 3}));   // neighbours, 1 m apart
}

TEST(Spacing, MinimumSpacingAndFixedLuminairesAreKept) {
  const SceneProblem p = parse_spacing(scene(2, 1.5, 1.5, 1.2));
  ASSERT_TRUE(p.search.admissible);
  EXPECT_DOUBLE_EQ(p.min_spacing_m, 1.2);
  EXPECT_FALSE(p.search.admissible({3, 3, 2, 3}));  // 1 m < 1.2 m
  EXPECT_TRUE(p.search.admissible({3, 3, 2, 2}));   // √2 m
  EXPECT_FALSE(p.search.admissible({1, 1, 3, 3}));  // on the fixed light at (1.5, 1.5)
}

TEST(Spacing, NegativeSpacingIsAnError) {
  EXPECT_THROW(parse_spacing(scene(2, 0.0, 0.0, -1.0)), std::exception);
}

// The search itself: all three lights want (3.5, 3.5); no member of the ISOC may hold two of
// them in one cell (or closer than the spacing asked for), and stacked cells were met and
// refused (counted as inadmissible), not traced.
TEST(Spacing, NoOptimumHasTwoLuminairesInOneCell) {
  for (const double spacing : {0.0, 1.2}) {
    const SceneProblem p = parse_spacing(scene(3, 0.5, 0.5, spacing));
    const OptimizationResult r = run_problem(p, {});
    ASSERT_FALSE(r.isoc.empty()) << spacing;
    EXPECT_GT(r.counters.inadmissible, 0u) << spacing;
    for (const ResultMember& m : r.isoc) {
      EXPECT_GE(smallest_distance(m.cells, 3, 0.5, 0.5), std::max(spacing, 1.0) - 1e-9)
          << "spacing " << spacing << ": member " << ::testing::PrintToString(m.cells);
    }
    // Still an optimization: the best layout holds a light next to or on the corner cell.
    bool near = false;
    for (int k = 0; k < 3; ++k) {
      const auto [x, y] = place(r.isoc[0].cells, k);
      near |= std::hypot(x - 3.5, y - 3.5) <= 1.0 + 1e-9;
    }
    EXPECT_TRUE(near) << ::testing::PrintToString(r.isoc[0].cells);
  }
}

}  // namespace
}  // namespace lightsolver::optimizer
