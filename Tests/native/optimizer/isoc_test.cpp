// ISOC / SIISOC update rules (Sec. III-C2), one test per state and case, for maximisation and
// minimisation, with hand-made intervals. z(0.95) = 1.95996; with sigma = 1 on both sides the
// =α threshold of a pair is 1.95996 * sqrt(2) = 2.7718.

#include "lightsolver/optimizer/isoc.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

namespace lightsolver::optimizer {
namespace {

constexpr double kConf = 0.95;

Estimate est(double mean, double sigma) {
  const double z = z_for_confidence(kConf);
  return {mean, sigma, mean - z * sigma, mean + z * sigma, 0};
}

std::set<std::uint64_t> keys(const Isoc& isoc) {
  std::set<std::uint64_t> k;
  for (const IsocMember& m : isoc.members()) k.insert(m.key);
  return k;
}

// The operators the ISOC relies on, on the intervals used below.
TEST(IsocOperators, HandMadeIntervalsCompareAsExpected) {
  EXPECT_TRUE(greater_alpha(est(100, 1), est(97, 1), kConf));  // 3 > 2.77
  EXPECT_TRUE(equal_alpha(est(100, 1), est(98, 1), kConf));    // 2 < 2.77
  EXPECT_TRUE(less_alpha(est(97, 1), est(100, 1), kConf));
  EXPECT_TRUE(equal_alpha(est(100, 1), est(101, 3), kConf));      // wide CI: 1 < 6.2
  EXPECT_TRUE(greater_alpha(est(103, 0.3), est(100, 1), kConf));  // 3 > 2.05
}

TEST(Isoc, RejectsBadConfidenceAndNaN) {
  EXPECT_THROW(Isoc(Goal::kMaximize, 0.0), std::invalid_argument);
  EXPECT_THROW(Isoc(Goal::kMaximize, 1.0), std::invalid_argument);
  Isoc isoc(Goal::kMaximize, kConf);
  EXPECT_THROW(isoc.update(1, est(NAN, 1)), std::invalid_argument);
  EXPECT_TRUE(isoc.empty());
}

TEST(IsocMax, FirstCandidateIsAdmitted) {
  Isoc isoc(Goal::kMaximize, kConf);
  const IsocUpdate u = isoc.update(1, est(100, 1));
  EXPECT_EQ(u.region, Region::kEmpty);
  EXPECT_EQ(u.result, UpdateCase::kFirst);
  EXPECT_EQ(paper_case(u.result), "init");
  EXPECT_EQ(u.comparisons, 0);
  EXPECT_NEAR(isoc.siisoc().low, 98.04, 0.01);
  EXPECT_NEAR(isoc.siisoc().high, 101.96, 0.01);
}

// ISOC {A=100±1.96, B=98±1.96}: SIISOC = [98.04, 99.96].
Isoc max_pair() {
  Isoc isoc(Goal::kMaximize, kConf);
  isoc.update(1, est(100, 1));
  isoc.update(2, est(98, 1));
  return isoc;
}

TEST(IsocMax, SiisocIsMaxminToMinmax) {
  const Isoc isoc = max_pair();
  EXPECT_NEAR(isoc.siisoc().low, 98.0399, 1e-3);   // maxmin: A's low end
  EXPECT_NEAR(isoc.siisoc().high, 99.9600, 1e-3);  // minmax: B's high end
  EXPECT_TRUE(isoc.invariant_holds());
}

TEST(IsocMax, State1CandidateBelowSiisocIsDiscardedWithOneComparison) {
  Isoc isoc = max_pair();
  const IsocUpdate u = isoc.update(3, est(90, 1));  // CI [88.04, 91.96] < maxmin
  EXPECT_EQ(u.region, Region::kWorse);
  EXPECT_EQ(u.result, UpdateCase::kDiscarded);
  EXPECT_EQ(paper_case(u.result), "1");
  EXPECT_EQ(u.comparisons, 1);
  EXPECT_FALSE(u.admitted());
  EXPECT_EQ(keys(isoc), (std::set<std::uint64_t>{1, 2}));
  EXPECT_TRUE(isoc.dominated(est(90, 1)));
}

TEST(IsocMax, Case2aCandidateBeatenByAMemberStaysOut) {
  Isoc isoc = max_pair();
  // CI [95.04, 98.96] meets the SIISOC, but A >α C (3 > 2.77) although B =α C.
  const IsocUpdate u = isoc.update(3, est(97, 1));
  EXPECT_EQ(u.region, Region::kOverlap);
  EXPECT_EQ(u.result, UpdateCase::kRejected);
  EXPECT_EQ(paper_case(u.result), "2a");
  EXPECT_TRUE(u.removed.empty());
  EXPECT_EQ(keys(isoc), (std::set<std::uint64_t>{1, 2}));
  EXPECT_FALSE(isoc.dominated(est(97, 1)));  // overlapping: strategy A would confirm it
}

TEST(IsocMax, Case2bCandidateReplacesTheMemberItBeats) {
  Isoc isoc = max_pair();
  const IsocUpdate u = isoc.update(3, est(101, 1));  // =α A, >α B
  EXPECT_EQ(u.region, Region::kOverlap);
  EXPECT_EQ(u.result, UpdateCase::kReplaced);
  EXPECT_EQ(paper_case(u.result), "2b");
  EXPECT_EQ(u.removed, (std::vector<std::uint64_t>{2}));
  EXPECT_EQ(keys(isoc), (std::set<std::uint64_t>{1, 3}));
  EXPECT_TRUE(isoc.invariant_holds());
  EXPECT_NEAR(isoc.siisoc().low, 99.04, 1e-2);
  EXPECT_NEAR(isoc.siisoc().high, 101.96, 1e-2);
}

TEST(IsocMax, Case2bCandidateMayBeatSeveralMembers) {
  Isoc isoc(Goal::kMaximize, kConf);
  isoc.update(1, est(100, 1));
  isoc.update(2, est(98.5, 1));
  isoc.update(3, est(98, 1));
  ASSERT_EQ(isoc.size(), 3u);
  const IsocUpdate u = isoc.update(4, est(101.5, 1));  // =α A; >α B (3.0) and D (3.5)
  EXPECT_EQ(u.region, Region::kOverlap);
  EXPECT_EQ(u.result, UpdateCase::kReplaced);
  EXPECT_EQ(u.removed, (std::vector<std::uint64_t>{2, 3}));
  EXPECT_EQ(keys(isoc), (std::set<std::uint64_t>{1, 4}));
  EXPECT_TRUE(isoc.invariant_holds());
}

TEST(IsocMax, Case2cIndistinguishableCandidateJoins) {
  Isoc isoc = max_pair();
  const IsocUpdate u = isoc.update(3, est(99, 1));
  EXPECT_EQ(u.region, Region::kOverlap);
  EXPECT_EQ(u.result, UpdateCase::kJoined);
  EXPECT_EQ(paper_case(u.result), "2c");
  EXPECT_EQ(keys(isoc), (std::set<std::uint64_t>{1, 2, 3}));
  EXPECT_TRUE(isoc.invariant_holds());
}

TEST(IsocMax, State3CandidateAboveLeadsAndKeepsOnlyIndistinguishableMembers) {
  Isoc isoc(Goal::kMaximize, kConf);
  isoc.update(1, est(100, 1));
  isoc.update(2, est(101, 3));  // wide CI, =α A: like x4 in the paper's Fig. 3
  // SIISOC = [98.04, 101.96]; C = 103 ± 0.59 lies above it.
  const IsocUpdate u = isoc.update(3, est(103, 0.3));
  EXPECT_EQ(u.region, Region::kBetter);
  EXPECT_EQ(u.result, UpdateCase::kLeads);
  EXPECT_EQ(paper_case(u.result), "3");
  EXPECT_EQ(u.removed, (std::vector<std::uint64_t>{1}));  // A <α C; W =α C stays
  EXPECT_EQ(keys(isoc), (std::set<std::uint64_t>{2, 3}));
  EXPECT_TRUE(isoc.invariant_holds());
}

TEST(IsocMax, UnconfirmedState1FallsBackToFullComparison) {
  // An asymmetric (Wilson-like) CI can lie below maxmin while compare(), which uses sigma,
  // finds the candidate =α: the state-1 shortcut must not discard it.
  Isoc isoc(Goal::kMaximize, kConf);
  isoc.update(1, est(100, 1));
  const Estimate c{97.0, 1.5, 94.0, 97.9, 0};  // 3 < 1.96 * sqrt(1 + 2.25) = 3.53
  EXPECT_EQ(isoc.classify(c), Region::kWorse);
  EXPECT_FALSE(isoc.dominated(c));
  const IsocUpdate u = isoc.update(2, c);
  EXPECT_EQ(u.region, Region::kWorse);
  EXPECT_EQ(u.result, UpdateCase::kJoined);
  EXPECT_TRUE(isoc.invariant_holds());
  EXPECT_TRUE(isoc.siisoc().empty());  // the CIs do not meet, yet the pair is =α
}

TEST(IsocMax, ReofferingAMemberReplacesItsEstimate) {
  Isoc isoc = max_pair();
  const IsocUpdate u = isoc.update(2, est(99.5, 0.5));  // B re-evaluated with more photons
  EXPECT_TRUE(u.admitted());
  EXPECT_EQ(isoc.size(), 2u);
  EXPECT_DOUBLE_EQ(isoc.members().back().estimate.mean, 99.5);
  EXPECT_EQ(isoc.best()->key, 1u);
}

TEST(IsocMin, MirroredRulesForMinimisation) {
  auto pair = [] {
    Isoc isoc(Goal::kMinimize, kConf);
    isoc.update(1, est(100, 1));
    isoc.update(2, est(102, 1));  // SIISOC = [100.04, 101.96]
    return isoc;
  };
  {
    Isoc isoc = pair();
    const IsocUpdate u = isoc.update(3, est(110, 1));
    EXPECT_EQ(u.region, Region::kWorse);
    EXPECT_EQ(u.result, UpdateCase::kDiscarded);
    EXPECT_EQ(u.comparisons, 1);
  }
  {
    Isoc isoc = pair();
    const IsocUpdate u = isoc.update(3, est(103, 1));  // A (100) is better than 103 by 3
    EXPECT_EQ(u.region, Region::kOverlap);
    EXPECT_EQ(u.result, UpdateCase::kRejected);
  }
  {
    Isoc isoc = pair();
    const IsocUpdate u = isoc.update(3, est(99, 1));  // beats B (102), =α A
    EXPECT_EQ(u.region, Region::kOverlap);
    EXPECT_EQ(u.result, UpdateCase::kReplaced);
    EXPECT_EQ(u.removed, (std::vector<std::uint64_t>{2}));
    EXPECT_EQ(keys(isoc), (std::set<std::uint64_t>{1, 3}));
    EXPECT_EQ(isoc.best()->key, 3u);
  }
  {
    Isoc isoc = pair();
    const IsocUpdate u = isoc.update(3, est(101, 1));
    EXPECT_EQ(u.result, UpdateCase::kJoined);
    EXPECT_EQ(isoc.size(), 3u);
    EXPECT_TRUE(isoc.invariant_holds());
  }
  {
    Isoc isoc(Goal::kMinimize, kConf);
    isoc.update(1, est(100, 1));
    isoc.update(2, est(99, 3));                         // wide, =α A
    const IsocUpdate u = isoc.update(3, est(97, 0.3));  // CI [96.4, 97.6] < maxmin 98.04
    EXPECT_EQ(u.region, Region::kBetter);
    EXPECT_EQ(u.result, UpdateCase::kLeads);
    EXPECT_EQ(u.removed, (std::vector<std::uint64_t>{1}));
    EXPECT_EQ(keys(isoc), (std::set<std::uint64_t>{2, 3}));
    EXPECT_TRUE(isoc.invariant_holds());
  }
}

// Random streams: the invariant holds after every update, every offered non-member is beaten
// by a member (Eq. 10, second line), and the final set is the non-dominated set whatever the
// order of the offers.
class IsocRandomStream : public ::testing::TestWithParam<Goal> {};

TEST_P(IsocRandomStream, InvariantsAndOrderIndependence) {
  const Goal goal = GetParam();
  std::mt19937_64 g(42);
  std::vector<Estimate> all;
  for (int i = 0; i < 300; ++i) {
    const double mean = 50.0 + static_cast<double>(g() % 10000) / 200.0;  // 50..100
    const double sigma = 0.5 + static_cast<double>(g() % 1000) / 250.0;   // 0.5..4.5
    all.push_back(est(mean, sigma));
  }
  std::set<std::uint64_t> nondominated;
  for (std::uint64_t i = 0; i < all.size(); ++i) {
    bool beaten = false;
    for (std::uint64_t j = 0; j < all.size() && !beaten; ++j) {
      const Relation r = compare(all[j], all[i], kConf);
      beaten = r == (goal == Goal::kMaximize ? Relation::Greater : Relation::Less);
    }
    if (!beaten) nondominated.insert(i);
  }
  ASSERT_GT(nondominated.size(), 1u);
  ASSERT_LT(nondominated.size(), all.size() / 4);
  std::vector<std::uint64_t> order(all.size());
  for (std::uint64_t i = 0; i < order.size(); ++i) order[i] = i;
  for (int trial = 0; trial < 5; ++trial) {
    std::shuffle(order.begin(), order.end(), g);
    Isoc isoc(goal, kConf);
    for (std::uint64_t i : order) {
      isoc.update(i, all[i]);
      ASSERT_TRUE(isoc.invariant_holds());
    }
    EXPECT_EQ(keys(isoc), nondominated);
    for (std::uint64_t i = 0; i < all.size(); ++i) {
      if (isoc.contains(i)) continue;
      EXPECT_TRUE(
          std::any_of(isoc.members().begin(), isoc.members().end(), [&](const IsocMember& m) {
            const Relation r = compare(m.estimate, all[i], kConf);
            return goal == Goal::kMaximize ? r == Relation::Greater : r == Relation::Less;
          }));
    }
  }
}

INSTANTIATE_TEST_SUITE_P(BothGoals, IsocRandomStream,
                         ::testing::Values(Goal::kMaximize, Goal::kMinimize));

}  // namespace
}  // namespace lightsolver::optimizer
