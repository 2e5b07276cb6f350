// Guth position index against CIE 117-1995 Table 4.1's printed values, its limits and voids.
#include <gtest/gtest.h>

#include "lightsolver/glare.hpp"

namespace lightsolver {
namespace {

TEST(GuthPositionIndex, TableNodes) {
  // (H/R, T/R) -> Table 4.1 value.
  EXPECT_DOUBLE_EQ(*guth_position_index(0.0, 0.0), 1.00);
  EXPECT_DOUBLE_EQ(*guth_position_index(0.5, 0.0), 2.86);
  EXPECT_DOUBLE_EQ(*guth_position_index(1.0, 1.0), 7.00);
  EXPECT_DOUBLE_EQ(*guth_position_index(0.3, 2.0), 4.90);
  EXPECT_DOUBLE_EQ(*guth_position_index(1.7, 0.0), 16.20);
  EXPECT_DOUBLE_EQ(*guth_position_index(1.9, 3.0), 16.00);
  EXPECT_DOUBLE_EQ(*guth_position_index(0.0, 3.0), 4.22);
  EXPECT_DOUBLE_EQ(*guth_position_index(0.5, 0.5), 2.91);
}

TEST(GuthPositionIndex, BilinearBetweenNodes) {
  EXPECT_NEAR(*guth_position_index(0.05, 0.0), 0.5 * (1.00 + 1.26), 1e-12);
  EXPECT_NEAR(*guth_position_index(0.0, 0.05), 0.5 * (1.00 + 1.05), 1e-12);
  // Centre of the cell H/R 0.5..0.6, T/R 1.0..1.1: mean of its four corners.
  EXPECT_NEAR(*guth_position_index(0.55, 1.05), 0.25 * (3.91 + 4.40 + 4.20 + 4.70), 1e-12);
}

TEST(GuthPositionIndex, LateralSignIgnored) {
  EXPECT_DOUBLE_EQ(*guth_position_index(0.4, -1.3), *guth_position_index(0.4, 1.3));
}

TEST(GuthPositionIndex, OutsideTheFieldAndVoids) {
  EXPECT_FALSE(guth_position_index(0.5, 3.05));  // beyond T/R = 3
  EXPECT_FALSE(guth_position_index(1.95, 1.0));  // beyond H/R = 1.9
  EXPECT_FALSE(guth_position_index(-0.1, 0.0));  // below the line of sight
  EXPECT_FALSE(guth_position_index(1.8, 0.0));   // void: hidden by brow
  EXPECT_FALSE(guth_position_index(1.75, 0.2));  // next to a void node
  EXPECT_FALSE(guth_position_index(1.9, 0.8));   // void
  EXPECT_TRUE(guth_position_index(1.8, 0.4));    // 16.00, the first value in that column
  EXPECT_TRUE(guth_position_index(1.9, 0.9));
}

TEST(GuthPositionIndex, LevinFormulaIsCloseButNotTheTable) {
  // Levin's closed form is 1 on the line of sight and rises like the table; it is a fit,
  // within a few percent near the line of sight and off by more toward the field's edge.
  EXPECT_NEAR(levin_position_index(0.0, 0.0), 1.0, 1e-12);
  EXPECT_NEAR(levin_position_index(0.5, 0.0) / *guth_position_index(0.5, 0.0), 1.0, 0.1);
  EXPECT_GT(levin_position_index(1.0, 1.0), levin_position_index(0.5, 0.5));
}

}  // namespace
}  // namespace lightsolver
