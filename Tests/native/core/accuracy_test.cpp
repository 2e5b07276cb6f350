// The per-cell accuracy rule (lightsolver/accuracy.hpp) and the study's checkpoints, on
// hand-made estimates. End-to-end checks against a closed form: Tests/python/test_study.py.
#include "lightsolver/accuracy.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "lightsolver/study.hpp"

namespace lightsolver {
namespace {

Estimate estimate(double mean, double half_width) {
  Estimate e;
  e.mean = mean;
  e.ci_low = std::max(0.0, mean - half_width);
  e.ci_high = mean + half_width;
  return e;
}

TEST(CellAccuracy, LitCellsAreJudgedByTheirOwnMean) {
  EXPECT_DOUBLE_EQ(cell_relative_half_width(estimate(200.0, 10.0), 400.0), 0.05);
  // At exactly 1 % of the grid's mean both rules agree (the switch is continuous).
  EXPECT_NEAR(cell_relative_half_width(estimate(4.0, 0.2), 400.0), 0.05, 1e-12);
}

TEST(CellAccuracy, DarkCellsAreJudgedAgainstOnePercentOfTheGridMean) {
  Estimate shadow;  // zero hits: Wilson interval [0, u]
  shadow.ci_high = 0.3;
  EXPECT_DOUBLE_EQ(cell_relative_half_width(shadow, 400.0), 0.15 / 4.0);
  EXPECT_DOUBLE_EQ(cell_relative_half_width(estimate(1.0, 0.5), 400.0), 0.5 / 4.0);
  // No light on the grid yet: nothing can be judged.
  EXPECT_TRUE(std::isinf(cell_relative_half_width(shadow, 0.0)));
}

TEST(CellAccuracy, ErrorsUseTheSameFloor) {
  EXPECT_DOUBLE_EQ(*cell_relative_error(210.0, 200.0, 400.0), 0.05);
  EXPECT_DOUBLE_EQ(*cell_relative_error(0.2, 0.0, 400.0), 0.05);
  EXPECT_FALSE(cell_relative_error(1.0, 0.0, 0.0).has_value());
}

TEST(CellAccuracy, WidthsOverTargetsCountEveryCellAndSurface) {
  TargetResult grid;
  grid.is_grid = true;
  grid.estimate = estimate(100.0, 1.0);
  grid.cells = {estimate(100.0, 10.0), estimate(100.0, 20.0), estimate(100.0, 30.0)};
  TargetResult surface;
  surface.estimate = estimate(50.0, 20.0);
  const CellWidths w = cell_widths(std::vector<TargetResult>{grid, surface});
  EXPECT_EQ(w.units, 4u);
  EXPECT_DOUBLE_EQ(w.worst, 0.4);
  EXPECT_DOUBLE_EQ(w.mean, (0.1 + 0.2 + 0.3 + 0.4) / 4);
  surface.estimate = Estimate{};  // no hit yet
  EXPECT_TRUE(std::isinf(cell_widths(std::vector<TargetResult>{grid, surface}).worst));
}

TEST(StudyCheckpoints, DoubleFromTenThousandWithoutOverflow) {
  EXPECT_TRUE(study_checkpoints(9'999).empty());
  EXPECT_EQ(study_checkpoints(10'000), (std::vector<std::uint64_t>{10'000}));
  EXPECT_EQ(study_checkpoints(79'999), (std::vector<std::uint64_t>{10'000, 20'000, 40'000}));
  const auto all = study_checkpoints(std::numeric_limits<std::uint64_t>::max());
  ASSERT_FALSE(all.empty());
  for (std::size_t i = 1; i < all.size(); ++i) EXPECT_EQ(all[i], 2 * all[i - 1]);
  EXPECT_GT(all.back(), std::numeric_limits<std::uint64_t>::max() / 2);
}

}  // namespace
}  // namespace lightsolver
