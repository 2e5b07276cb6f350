// Intentions and statistical feasibility; evaluation seeds; the tabu cache.

#include "lightsolver/optimizer/intention.hpp"

#include <gtest/gtest.h>

#include <set>

#include "lightsolver/optimizer/evaluator.hpp"

namespace lightsolver::optimizer {
namespace {

Estimate ci(double low, double high) { return {(low + high) / 2, (high - low) / 4, low, high, 0}; }

TEST(Feasibility, CiEntirelyOnOneSideDecides) {
  const Constraint at_least{{MetricKind::kMeanIlluminance, "desk"}, Sense::kAtLeast, 500.0};
  EXPECT_EQ(judge(ci(500, 520), at_least), Feasibility::kMet);  // bound included
  EXPECT_EQ(judge(ci(490, 520), at_least), Feasibility::kUncertain);
  EXPECT_EQ(judge(ci(470, 499), at_least), Feasibility::kViolated);
  const Constraint at_most{{MetricKind::kMeanIlluminance, "screen"}, Sense::kAtMost, 100.0};
  EXPECT_EQ(judge(ci(80, 100), at_most), Feasibility::kMet);
  EXPECT_EQ(judge(ci(80, 101), at_most), Feasibility::kUncertain);
  EXPECT_EQ(judge(ci(101, 120), at_most), Feasibility::kViolated);
  const Estimate exact{300.0, 0.0, 300.0, 300.0, 0};  // installed flux: no noise
  EXPECT_EQ(judge(exact, {{MetricKind::kInstalledFlux, ""}, Sense::kAtMost, 300.0}),
            Feasibility::kMet);
}

TEST(Feasibility, WorstVerdictAndViolationAmount) {
  const Intention in = minimize_installed_flux("floor", 300.0, 0.6);
  ASSERT_EQ(in.constraints.size(), 2u);
  EXPECT_EQ(judge_all({ci(310, 330), ci(0.65, 0.7)}, in), Feasibility::kMet);
  EXPECT_EQ(judge_all({ci(290, 330), ci(0.65, 0.7)}, in), Feasibility::kUncertain);
  EXPECT_EQ(judge_all({ci(290, 330), ci(0.4, 0.5)}, in), Feasibility::kViolated);
  EXPECT_EQ(judge_each({ci(290, 330), ci(0.4, 0.5)}, in),
            (std::vector<Feasibility>{Feasibility::kUncertain, Feasibility::kViolated}));
  EXPECT_DOUBLE_EQ(violation({ci(310, 330), ci(0.65, 0.7)}, in), 0.0);
  // means 270 (10 % short of 300) and 0.45 (25 % short of 0.6)
  EXPECT_NEAR(violation({ci(260, 280), ci(0.4, 0.5)}, in), 0.10 + 0.25, 1e-12);
  EXPECT_THROW(judge_all({ci(1, 2)}, in), std::invalid_argument);
  EXPECT_EQ(judge_all({}, maximize_mean_illuminance("desk")), Feasibility::kMet);
}

TEST(Intentions, FactoriesDescribeThePaperProblemAndTheTwoConstrainedOnes) {
  const Intention a = maximize_mean_illuminance("podium");
  EXPECT_EQ(a.goal, Goal::kMaximize);
  EXPECT_EQ(a.objective.kind, MetricKind::kMeanIlluminance);
  EXPECT_EQ(a.objective.target, "podium");
  EXPECT_TRUE(a.constraints.empty());
  EXPECT_EQ(minimize_mean_illuminance("screen").goal, Goal::kMinimize);
  const Intention u = maximize_uniformity("workplane", 500.0);
  EXPECT_EQ(u.objective.kind, MetricKind::kUniformity);
  ASSERT_EQ(u.constraints.size(), 1u);
  EXPECT_EQ(u.constraints[0].metric.kind, MetricKind::kMeanIlluminance);
  EXPECT_EQ(u.constraints[0].sense, Sense::kAtLeast);
  EXPECT_DOUBLE_EQ(u.constraints[0].bound, 500.0);
  const Intention f = minimize_installed_flux("workplane", 500.0, 0.6);
  EXPECT_EQ(f.goal, Goal::kMinimize);
  EXPECT_EQ(f.objective.kind, MetricKind::kInstalledFlux);
  EXPECT_EQ(f.constraints[1].metric.kind, MetricKind::kUniformity);
  EXPECT_DOUBLE_EQ(f.constraints[1].bound, 0.6);
}

TEST(EvaluationSeed, DependsOnEveryInputAndNothingElse) {
  std::set<std::uint64_t> seeds;
  for (std::uint64_t run : {1ull, 2ull})
    for (std::uint64_t cell = 0; cell < 50; ++cell)
      for (std::uint64_t photons : {1000ull, 64000ull})
        seeds.insert(evaluation_seed(run, cell, photons));
  EXPECT_EQ(seeds.size(), 2u * 50u * 2u);
  EXPECT_EQ(evaluation_seed(5, 17, 4096), evaluation_seed(5, 17, 4096));
  EXPECT_NE(evaluation_seed(5, 17, 4096), evaluation_seed(5, 4096, 17));
}

TEST(TabuCache, OneEvaluationPerCellAndPhotonLevel) {
  TabuCache cache;
  EXPECT_EQ(cache.find(3, 100), nullptr);
  EXPECT_EQ(cache.most_precise(3), nullptr);
  Evaluation lo, hi;
  lo.objective.mean = 1.0;
  hi.objective.mean = 2.0;
  cache.insert(3, 100, lo);
  cache.insert(3, 6400, hi);
  EXPECT_THROW(cache.insert(3, 100, lo), std::logic_error);
  EXPECT_DOUBLE_EQ(cache.find(3, 100)->objective.mean, 1.0);
  EXPECT_DOUBLE_EQ(cache.most_precise(3)->objective.mean, 2.0);
  EXPECT_EQ(cache.most_photons(3), 6400u);
  EXPECT_EQ(cache.cells(), 1u);
  EXPECT_EQ(cache.entries(), 2u);
}

}  // namespace
}  // namespace lightsolver::optimizer
