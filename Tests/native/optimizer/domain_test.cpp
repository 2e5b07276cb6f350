// Discretised domain (Sec. IV-B): cells, centres, indices, distances, neighbourhoods, shaking.

#include "lightsolver/optimizer/domain.hpp"

#include <gtest/gtest.h>

#include <map>
#include <set>

namespace lightsolver::optimizer {
namespace {

TEST(Variable, CellCentresAndLookup) {
  Domain d;
  d.add_range("x", 0.0, 4.0, 8);
  const Variable& v = d.variables()[0];
  EXPECT_DOUBLE_EQ(v.value(0), 0.25);
  EXPECT_DOUBLE_EQ(v.value(7), 3.75);
  EXPECT_EQ(v.cell_of(0.25), 0u);
  EXPECT_EQ(v.cell_of(2.49), 4u);
  EXPECT_EQ(v.cell_of(-5.0), 0u);  // clamped
  EXPECT_EQ(v.cell_of(9.0), 7u);
  EXPECT_THROW(v.value(8), std::out_of_range);
}

TEST(Variable, LevelsAndPeriodicAngles) {
  Domain d;
  d.add_levels("flux", {1000, 2000, 3500});
  d.add_angle("azimuth", 0.0, 360.0, 12);  // full turn: periodic
  d.add_angle("tilt", 0.0, 60.0, 6);       // not periodic
  EXPECT_EQ(d.variables()[0].size(), 3u);
  EXPECT_DOUBLE_EQ(d.variables()[0].value(2), 3500.0);
  EXPECT_EQ(d.variables()[0].cell_of(2600.0), 1u);  // nearest level
  EXPECT_TRUE(d.variables()[1].periodic);
  EXPECT_FALSE(d.variables()[2].periodic);
  EXPECT_DOUBLE_EQ(d.variables()[1].value(0), 15.0);
  EXPECT_EQ(d.variables()[1].cell_of(-10.0), 11u);  // -10 deg wraps to 350
  EXPECT_EQ(d.cell_count(), 3u * 12u * 6u);
  EXPECT_EQ(d.distance({0, 0, 0}, {0, 11, 0}), 1u);  // across 0/360
  EXPECT_EQ(d.distance({0, 0, 0}, {0, 6, 0}), 6u);
  EXPECT_EQ(d.distance({0, 0, 0}, {2, 1, 5}), 5u);
}

TEST(Domain, RejectsBadVariables) {
  Domain d;
  EXPECT_THROW(d.add_range("x", 1.0, 1.0, 4), std::invalid_argument);
  EXPECT_THROW(d.add_range("x", 0.0, 1.0, 0), std::invalid_argument);
  EXPECT_THROW(d.add_range("", 0.0, 1.0, 2), std::invalid_argument);
  EXPECT_THROW(d.add_levels("f", {}), std::invalid_argument);
  EXPECT_THROW(d.add_angle("a", 0.0, 400.0, 4), std::invalid_argument);
  d.add_range("x", 0.0, 1.0, 2);
  EXPECT_THROW(d.add_range("x", 0.0, 1.0, 2), std::invalid_argument);  // duplicate name
  Domain big;
  for (int i = 0; i < 3; ++i) big.add_range("v" + std::to_string(i), 0, 1, 1u << 20);
  EXPECT_THROW(big.add_range("v3", 0, 1, 1u << 20), std::invalid_argument);  // > 2^63 cells
}

TEST(Domain, TwoLuminairesMakeA4DGridWithRoundTripIndices) {
  Domain d;
  d.add_rectangle("lum0", 0.0, 6.0, 6, 0.0, 4.0, 4).add_rectangle("lum1", 0.0, 6.0, 6, 0.0, 4.0, 4);
  ASSERT_EQ(d.dimensions(), 4u);
  EXPECT_EQ(d.variables()[0].name, "lum0.x");
  EXPECT_EQ(d.variables()[3].name, "lum1.y");
  EXPECT_EQ(d.cell_count(), 6u * 4u * 6u * 4u);
  std::set<std::uint64_t> seen;
  for (std::uint64_t i = 0; i < d.cell_count(); ++i) {
    const Configuration c = d.configuration(i);
    EXPECT_EQ(d.index(c), i);
    seen.insert(i);
  }
  EXPECT_EQ(d.index({1, 0, 0, 0}), 1u);  // first variable fastest
  EXPECT_EQ(d.index({0, 1, 0, 0}), 6u);
  const std::vector<double> v = d.values({5, 3, 0, 1});
  EXPECT_EQ(v, (std::vector<double>{5.5, 3.5, 0.5, 1.5}));
  EXPECT_EQ(d.cell_of(v), (Configuration{5, 3, 0, 1}));
  EXPECT_THROW(d.index({6, 0, 0, 0}), std::out_of_range);
  EXPECT_THROW(d.index({0, 0, 0}), std::out_of_range);
}

TEST(Domain, NeighbourhoodsAtCornersInteriorAndAcrossWrap) {
  Domain d;
  d.add_range("x", 0, 1, 5).add_range("y", 0, 1, 5);
  EXPECT_EQ(d.neighbours({2, 2}, Neighbourhood::kAxis).size(), 4u);
  EXPECT_EQ(d.neighbours({0, 0}, Neighbourhood::kAxis).size(), 2u);
  EXPECT_EQ(d.neighbours({2, 2}, Neighbourhood::kChebyshev).size(), 8u);
  EXPECT_EQ(d.neighbours({0, 0}, Neighbourhood::kChebyshev).size(), 3u);
  for (const Configuration& n : d.neighbours({2, 2}, Neighbourhood::kChebyshev))
    EXPECT_EQ(d.distance(n, {2, 2}), 1u);
  Domain p;
  p.add_angle("a", 0, 360, 8);
  const auto wrap = p.neighbours({0}, Neighbourhood::kAxis);
  EXPECT_EQ(wrap, (std::vector<Configuration>{{7}, {1}}));
  Domain two;
  two.add_angle("a", 0, 360, 2);  // -1 and +1 are the same cell: listed once
  EXPECT_EQ(two.neighbours({0}, Neighbourhood::kAxis).size(), 1u);
}

TEST(Domain, ShakeLandsAtExactlyDistanceK) {
  Domain d;
  d.add_range("x", 0, 1, 20).add_range("y", 0, 1, 20).add_angle("a", 0, 360, 12);
  std::mt19937_64 rng(7);
  std::map<std::uint32_t, int> seen_k;
  for (int i = 0; i < 3000; ++i) {
    const Configuration c = d.random(rng);
    const std::uint32_t k = 1 + static_cast<std::uint32_t>(uniform_below(rng, 6));
    const Configuration s = d.shake(c, k, rng);
    ASSERT_TRUE(d.contains(s));
    ASSERT_EQ(d.distance(c, s), k);  // every variable can move 6 from any cell here
    ++seen_k[k];
  }
  EXPECT_EQ(seen_k.size(), 6u);
}

TEST(Domain, ShakeSaturatesWhenKExceedsTheGrid) {
  Domain d;
  d.add_range("x", 0, 1, 3).add_range("y", 0, 1, 2);
  std::mt19937_64 rng(3);
  for (int i = 0; i < 200; ++i) {
    const Configuration c = d.random(rng);
    const Configuration s = d.shake(c, 10, rng);
    const std::uint32_t reach = c[0] == 1 ? 1u : 2u;  // farthest x cell from c
    EXPECT_EQ(d.distance(c, s), reach);
  }
  Domain single;
  single.add_range("x", 0, 1, 1);
  EXPECT_EQ(single.shake({0}, 3, rng), (Configuration{0}));
}

TEST(Domain, ShakeIsDeterministicForASeed) {
  Domain d;
  d.add_rectangle("l", 0, 1, 30, 0, 1, 30);
  std::mt19937_64 a(99), b(99);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(d.shake({15, 15}, 4, a), d.shake({15, 15}, 4, b));
}

TEST(UniformBelow, StaysInRangeAndCoversIt) {
  std::mt19937_64 rng(1);
  std::vector<int> hist(7, 0);
  for (int i = 0; i < 7000; ++i) ++hist[uniform_below(rng, 7)];
  for (int h : hist) EXPECT_GT(h, 850);  // expected 1000 each; 850 is > 5 sigma below
}

}  // namespace
}  // namespace lightsolver::optimizer
