// The run options table (lightsolver/run_options.hpp): its one range message, the checks the
// library runs with it, and run_cost (lightsolver/cost.hpp), which the CLI and Python share.
#include "lightsolver/run_options.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "lightsolver/cost.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

const RunOptionInfo& row(const char* name) {
  const RunOptionInfo* info = find_run_option(name);
  EXPECT_NE(info, nullptr) << name;
  return *info;
}

TEST(RunOptions, OneMessagePerRangeAndSide) {
  EXPECT_EQ(range_error(row("confidence"), 0.5), "");
  EXPECT_EQ(range_error(row("confidence"), 2.0), "must lie strictly between 0 and 1 (got 2)");
  EXPECT_EQ(range_error(row("confidence"), 0.0), "must lie strictly between 0 and 1 (got 0)");
  EXPECT_EQ(range_error(row("photons"), 0.0), "must be at least 1 (got 0)");
  EXPECT_EQ(range_error(row("photons"), 1e13), "");  // the most: check_photon_count()
  EXPECT_EQ(range_error(row("max_bounces"), 1'000'001.0), "must be <= 1000000 (got 1000001)");
  EXPECT_EQ(range_error(row("max_seconds"), 0.0), "must be > 0 (got 0)");
  EXPECT_EQ(range_error(row("max_seconds"), INFINITY), "must be a finite number (got inf)");
  EXPECT_EQ(range_error(row("max_seconds"), NAN), "must be a finite number (got nan)");
  EXPECT_EQ(range_error(row("seed"), 1.8e19), "");  // any 64-bit seed
  EXPECT_EQ(range_text(row("confidence").range), "(0, 1)");
  EXPECT_EQ(range_text(row("photons").range), "[1, inf)");
  EXPECT_EQ(range_text(row("max_bounces").range), "[0, 1000000]");
  EXPECT_EQ(range_text(row("max_seconds").range), "(0, inf)");
  EXPECT_EQ(range_text(row("seed").range), "");
}

TEST(RunOptions, NamesAreUniqueAndKeysComeFromTheTable) {
  std::set<std::string> names;
  for (const RunOptionInfo& o : run_option_infos()) EXPECT_TRUE(names.insert(o.name).second);
  static_assert(std::string_view(result_key("photons")) == "photons_requested");
  static_assert(std::string_view(result_key("max_seconds")) == "max_seconds");
  EXPECT_EQ(find_run_option("no such option"), nullptr);
}

TEST(RunOptions, DefaultsAreTheStructsInitializers) {
  const Settings settings;
  const SolveOptions options;
  for_each_run_option([&](const auto& r) {
    using Row = std::decay_t<decltype(r)>;
    if constexpr (Row::kInScene) {
      EXPECT_EQ(r.default_value(), std::optional<typename Row::value_type>(settings.*r.setting));
    } else {
      EXPECT_EQ(r.default_value(), std::optional<typename Row::value_type>(options.*r.option));
    }
  });
  EXPECT_EQ(std::get<0>(kRunOptions).default_value(), 1'000'000u);
}

Scene lamp_over_floor() {
  Scene s;
  add_material(s, "white", Material::Type::Diffuse, 0.5);
  s.meshes.push_back(quad_mesh("floor", 0, dvec3(0), dvec3(2, 0, 0), dvec3(0, 2, 0)));
  s.targets.push_back(surface("floor", 0));
  s.luminaires.push_back(point_light({1, 1, 2}, 1000.0));
  validate(s);
  return s;
}

TEST(RunOptions, EveryRunChecksItsOptionsWithTheTablesMessage) {
  const Scene s = lamp_over_floor();
  const auto error_of = [&](const SolveOptions& o) {
    try {
      solve(s, o);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("<no error>");
  };
  SolveOptions o;
  o.photons = 1000;
  o.confidence = 1.0;
  EXPECT_NE(error_of(o).find("confidence: must lie strictly between 0 and 1 (got 1)"),
            std::string::npos);
  o.confidence.reset();
  o.threads = -2;
  EXPECT_NE(error_of(o).find("threads: must be at least 0 (got -2)"), std::string::npos);
  o.threads = 0;
  o.target_accuracy = 0.0;
  EXPECT_NE(error_of(o).find("target_accuracy: must lie strictly between 0 and 1"),
            std::string::npos);
}

TEST(RunOptions, ScenesBuiltInMemoryAreCheckedByTheSameTable) {
  Scene s = lamp_over_floor();
  s.settings.confidence = 1.5;
  try {
    validate(s);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "settings.confidence: must lie strictly between 0 and 1 (got 1.5)"),
              std::string::npos)
        << e.what();
  }
}

TEST(RunCost, RowsAreCheckpointsOfOneRunAndGoalsComeFromTheLast) {
  const Scene s = lamp_over_floor();
  CostOptions o;
  o.max_photons = 50'000;
  o.solve.seed = 3;
  std::vector<std::uint64_t> seen;
  const Cost c = run_cost(s, o, [&](const Checkpoint& row) { seen.push_back(row.photons); });
  ASSERT_EQ(seen, (std::vector<std::uint64_t>{10'000, 40'000}));
  ASSERT_EQ(c.rows.size(), 2u);
  EXPECT_EQ(c.results.photons, 40'000u);  // the run ends at the last row
  ASSERT_EQ(c.goals.size(), std::size(kCostGoals));
  for (std::size_t i = 0; i < c.goals.size(); ++i) {
    EXPECT_EQ(c.goals[i].accuracy, kCostGoals[i]);
    EXPECT_EQ(c.goals[i].need.photons, accuracy_cost(c.rows.back(), kCostGoals[i]).photons);
  }
  // The last row is what a plain run of its photons gives.
  SolveOptions plain;
  plain.photons = 40'000;
  plain.seed = 3;
  EXPECT_EQ(solve(s, plain).targets[0].estimate.mean, c.results.targets[0].estimate.mean);
  o.max_photons = 9'999;
  EXPECT_THROW(run_cost(s, o), InputError);
}

}  // namespace
}  // namespace lightsolver::test
