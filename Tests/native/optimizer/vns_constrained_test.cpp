// Constrained intentions: members must be feasible at N photons, the ISOC compares objectives
// among feasible candidates only, and uncertain verdicts follow the chosen policy.

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "lightsolver/optimizer/vns.hpp"
#include "synthetic.hpp"

namespace lightsolver::optimizer {
namespace {

using testing::NoisyMetric;
using testing::SyntheticEvaluator;

constexpr std::uint64_t kConstrainedN = 1u << 20;
constexpr std::uint64_t kConstrainedn = kConstrainedN / 16;

VnsOptions options(std::uint64_t seed, PhotonStrategy strategy) {
  VnsOptions o;
  o.seed = seed;
  o.screening_photons = kConstrainedn;
  o.confirmation_photons = kConstrainedN;
  o.strategy = strategy;
  o.max_iterations = 150;
  o.starts = 2;
  return o;
}

// Maximise a uniformity-like objective that grows with x, subject to Em >= 400 where
// Em = 600 - 400 x + 100 y: the constraint binds. On a 20 x 20 unit square the best feasible
// column is x = 0.725 (cell 14), feasible for y = 0.925 (Em = 402.5) and y = 0.975 (407.5).
double u_truth(const std::vector<double>& v) { return 0.3 + 0.5 * v[0]; }
double em_truth(const std::vector<double>& v) { return 600.0 - 400.0 * v[0] + 100.0 * v[1]; }
constexpr double kSigmaU = 0.005, kSigmaEm = 1.0;

class UniformityUnderIlluminance : public ::testing::TestWithParam<PhotonStrategy> {};

TEST_P(UniformityUnderIlluminance, MembersAreFeasibleAtNAndTheConstrainedOptimumIsFound) {
  Domain d;
  d.add_rectangle("lum", 0.0, 1.0, 20, 0.0, 1.0, 20);
  const Intention in = maximize_uniformity("workplane", 400.0);
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    SyntheticEvaluator ev({u_truth, kSigmaU, kConstrainedN}, {{em_truth, kSigmaEm, kConstrainedN}},
                          0.95);
    const OptimizationResult r = optimize(d, in, ev, options(seed, GetParam()));
    ASSERT_FALSE(r.isoc.empty()) << "seed " << seed;
    double best_member_u = 0.0;
    for (const ResultMember& m : r.isoc) {
      EXPECT_EQ(m.photons, kConstrainedN);
      ASSERT_EQ(m.constraints.size(), 1u);
      EXPECT_EQ(m.feasibility[0], Feasibility::kMet);
      EXPECT_GE(m.constraints[0].ci_low, 400.0);
      EXPECT_GE(em_truth(m.values), 400.0 - 3.29 * kSigmaEm);
      best_member_u = std::max(best_member_u, u_truth(m.values));
    }
    // Column 14 holds the constrained optimum: (14, 19) and, 2.5 sigma inside the bound,
    // (14, 18). The ISOC must hold one of them and nothing beyond the resolution at N.
    const double best = u_truth(d.values({14, 19}));
    EXPECT_EQ(best_member_u, best) << "seed " << seed;
    for (const ResultMember& m : r.isoc)
      EXPECT_GE(u_truth(m.values),
                best - z_for_confidence(0.95) * std::sqrt(2.0) * kSigmaU - 2.0 * 3.29 * kSigmaU);
    EXPECT_GT(r.counters.infeasible, 0u);
    // The constraint binds: the search saw cells with a far better objective and kept them out.
    bool saw_better_infeasible = false;
    for (const auto& [key, calls] : ev.calls()) {
      const std::vector<double> v = d.values(d.configuration(key.first));
      if (u_truth(v) > best_member_u + 0.05 && em_truth(v) < 400.0) saw_better_infeasible = true;
    }
    EXPECT_TRUE(saw_better_infeasible);
  }
}

INSTANTIATE_TEST_SUITE_P(BothStrategies, UniformityUnderIlluminance,
                         ::testing::Values(PhotonStrategy::kConfirm, PhotonStrategy::kRefineAtEnd));

// Minimise installed flux (exact, sigma 0) subject to Em >= 140 and U0 >= 0.6: only the
// centre position x = 0.55 with 1500 lm is feasible at the lowest feasible level.
TEST(MinimiseFlux, IsocIsTheCheapestFeasibleConfiguration) {
  Domain d;
  d.add_levels("flux", {1000, 1500, 2000, 2500, 3000}).add_range("x", 0.0, 1.0, 10);
  auto flux = [](const std::vector<double>& v) { return v[0]; };
  auto em = [](const std::vector<double>& v) {
    return v[0] / 10.0 * (0.5 + 0.5 * std::exp(-(v[1] - 0.55) * (v[1] - 0.55) / 0.02));
  };
  auto u0 = [](const std::vector<double>& v) {
    return 0.4 + 0.4 * std::exp(-(v[1] - 0.55) * (v[1] - 0.55) / 0.05);
  };
  const Intention in = minimize_installed_flux("workplane", 140.0, 0.6);
  for (PhotonStrategy s : {PhotonStrategy::kConfirm, PhotonStrategy::kRefineAtEnd}) {
    SyntheticEvaluator ev({flux, 0.0, kConstrainedN},
                          {{em, 1.0, kConstrainedN}, {u0, 0.005, kConstrainedN}}, 0.95);
    VnsOptions o = options(9, s);
    o.initial = {{4, 0}};  // most flux, worst position
    const OptimizationResult r = optimize(d, in, ev, o);
    ASSERT_EQ(r.isoc.size(), 1u);
    EXPECT_EQ(r.isoc[0].cells, (Configuration{1, 5}));
    EXPECT_EQ(r.isoc[0].values[0], 1500.0);
    EXPECT_EQ(r.isoc[0].objective.sigma, 0.0);
    EXPECT_EQ(r.isoc[0].feasibility,
              (std::vector<Feasibility>{Feasibility::kMet, Feasibility::kMet}));
    EXPECT_EQ(r.isoc[0].photons, kConstrainedN);
  }
}

TEST(Infeasible, NoFeasibleCellGivesAnEmptyIsoc) {
  Domain d;
  d.add_rectangle("lum", 0.0, 1.0, 5, 0.0, 1.0, 5);
  SyntheticEvaluator ev({u_truth, kSigmaU, kConstrainedN}, {{em_truth, kSigmaEm, kConstrainedN}},
                        0.95);
  const OptimizationResult r =
      optimize(d, maximize_uniformity("g", 10000.0), ev, options(1, PhotonStrategy::kConfirm));
  EXPECT_TRUE(r.isoc.empty());
  EXPECT_EQ(r.stop, StopReason::kExhausted);
  EXPECT_EQ(r.counters.infeasible, d.cell_count());
  EXPECT_EQ(r.counters.confirmations, 0u);  // violated at n: N cannot rescue it
  EXPECT_NE(to_json(r).find("\"siisoc\": null"), std::string::npos);
}

// Every cell's constraint CI straddles the bound, at any photon count.
class UncertainPolicyTest : public ::testing::TestWithParam<PhotonStrategy> {};

TEST_P(UncertainPolicyTest, RejectKeepsUncertainCellsOutAcceptKeepsThem) {
  Domain d;
  d.add_range("x", 0.0, 1.0, 4);
  FunctionEvaluator ev([](const EvaluationRequest& r) {
    Evaluation e;
    e.objective = {r.values[0], 0.001, r.values[0] - 0.002, r.values[0] + 0.002, 0};
    e.constraints.push_back({400.0, 1.0, 398.0, 402.0, 0});
    return e;
  });
  const Intention in = maximize_uniformity("g", 400.0);
  VnsOptions o = options(1, GetParam());
  const OptimizationResult rejected = optimize(d, in, ev, o);
  EXPECT_TRUE(rejected.isoc.empty());
  EXPECT_EQ(rejected.counters.infeasible, 4u);
  EXPECT_EQ(rejected.counters.confirmations, 4u);  // uncertain at n: settled with N
  o.uncertain = UncertainPolicy::kAccept;
  const OptimizationResult accepted = optimize(d, in, ev, o);
  ASSERT_EQ(accepted.isoc.size(), 1u);
  EXPECT_EQ(accepted.isoc[0].cells, (Configuration{3}));
  EXPECT_EQ(accepted.isoc[0].feasibility[0], Feasibility::kUncertain);
  EXPECT_EQ(accepted.isoc[0].photons, kConstrainedN);
}

INSTANTIATE_TEST_SUITE_P(BothStrategies, UncertainPolicyTest,
                         ::testing::Values(PhotonStrategy::kConfirm, PhotonStrategy::kRefineAtEnd));

}  // namespace
}  // namespace lightsolver::optimizer
