// VNS on synthetic evaluators: finding the optimum, both peaks of a tie, the tabu cache, the
// photon strategies, determinism, statistics and cancellation.

#include "lightsolver/optimizer/vns.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>

#include "synthetic.hpp"

namespace lightsolver::optimizer {
namespace {

using testing::bump;
using testing::NoisyMetric;
using testing::SyntheticEvaluator;

constexpr std::uint64_t kN = 1u << 20;  // confirmation photons
constexpr std::uint64_t kn = kN / 16;   // screening photons: sigma 4x larger
constexpr double kSigmaN = 1.5;         // sigma of the objective with N photons

Domain unit_square(std::uint32_t cells) {
  Domain d;
  d.add_rectangle("lum", 0.0, 1.0, cells, 0.0, 1.0, cells);
  return d;
}

// Peak exactly at the centre of cell (17, 8) of a 25 x 25 grid.
double bump_truth(const std::vector<double>& v) { return bump(v, 0.70, 0.34, 0.15, 100.0, 10.0); }

SyntheticEvaluator bump_evaluator(double confidence = 0.95) {
  return SyntheticEvaluator({bump_truth, kSigmaN, kN}, {}, confidence);
}

VnsOptions base_options(std::uint64_t seed) {
  VnsOptions o;
  o.seed = seed;
  o.screening_photons = kn;
  o.confirmation_photons = kN;
  o.max_iterations = 150;
  o.starts = 2;
  return o;
}

std::set<std::uint64_t> isoc_cells(const Domain& d, const OptimizationResult& r) {
  std::set<std::uint64_t> s;
  for (const ResultMember& m : r.isoc) s.insert(d.index(m.cells));
  return s;
}

// A member may differ from the true optimum by the =α threshold of a pair at N photons plus
// each estimate's own error (bounded at 3.29 sigma, two-sided 99.9 %).
double resolution(double confidence) {
  return z_for_confidence(confidence) * std::sqrt(2.0) * kSigmaN + 2.0 * 3.29 * kSigmaN;
}

void expect_pairwise_indistinguishable(const OptimizationResult& r) {
  for (std::size_t i = 0; i < r.isoc.size(); ++i)
    for (std::size_t j = i + 1; j < r.isoc.size(); ++j)
      EXPECT_TRUE(equal_alpha(r.isoc[i].objective, r.isoc[j].objective, r.confidence));
}

struct StrategyCase {
  PhotonStrategy strategy;
  std::uint64_t seed;
};

class BumpSearch : public ::testing::TestWithParam<StrategyCase> {};

TEST_P(BumpSearch, IsocHoldsTheTrueOptimumAndOnlyCellsWithinResolution) {
  const Domain d = unit_square(25);
  SyntheticEvaluator ev = bump_evaluator();
  VnsOptions o = base_options(GetParam().seed);
  o.strategy = GetParam().strategy;
  const OptimizationResult r = optimize(d, maximize_mean_illuminance("t"), ev, o);

  const std::uint64_t optimum = d.index({17, 8});
  const double best = bump_truth(d.values({17, 8}));
  ASSERT_FALSE(r.isoc.empty());
  EXPECT_TRUE(isoc_cells(d, r).count(optimum)) << "optimum cell missing from the ISOC";
  std::size_t far_evaluated = 0;  // cells the ISOC had to keep out
  for (const auto& [key, calls] : ev.calls())
    if (bump_truth(d.values(d.configuration(key.first))) < best - resolution(0.95)) ++far_evaluated;
  EXPECT_GT(far_evaluated, 20u);
  for (const ResultMember& m : r.isoc) {
    EXPECT_GE(bump_truth(m.values), best - resolution(0.95));
    EXPECT_EQ(m.photons, kN);  // A admits N estimates; B refines with N
  }
  EXPECT_LT(r.isoc.size(), 10u);
  expect_pairwise_indistinguishable(r);
  EXPECT_EQ(r.stop, StopReason::kIterationLimit);
  EXPECT_EQ(r.counters.iterations, o.max_iterations);
}

INSTANTIATE_TEST_SUITE_P(StrategiesAndSeeds, BumpSearch,
                         ::testing::Values(StrategyCase{PhotonStrategy::kConfirm, 1},
                                           StrategyCase{PhotonStrategy::kConfirm, 2},
                                           StrategyCase{PhotonStrategy::kConfirm, 3},
                                           StrategyCase{PhotonStrategy::kRefineAtEnd, 1},
                                           StrategyCase{PhotonStrategy::kRefineAtEnd, 2},
                                           StrategyCase{PhotonStrategy::kRefineAtEnd, 3}));

TEST(VnsPhotons, StrategyAScreensWithFewPhotonsAndSpendsLessThanStaticN) {
  const Domain d = unit_square(25);
  SyntheticEvaluator ev_a = bump_evaluator(), ev_static = bump_evaluator();
  VnsOptions a = base_options(11);
  VnsOptions fixed = a;
  fixed.screening_photons = 0;  // every evaluation with N
  const OptimizationResult ra = optimize(d, maximize_mean_illuminance("t"), ev_a, a);
  const OptimizationResult rs = optimize(d, maximize_mean_illuminance("t"), ev_static, fixed);
  EXPECT_TRUE(isoc_cells(d, ra).count(d.index({17, 8})));
  EXPECT_TRUE(isoc_cells(d, rs).count(d.index({17, 8})));
  EXPECT_GT(ra.counters.screened_out, 0u);
  EXPECT_LT(ra.counters.confirmations, ra.counters.evaluations / 2);
  EXPECT_EQ(rs.counters.confirmations, rs.counters.evaluations);
  EXPECT_LT(ra.counters.photons * 2, rs.counters.photons);  // at least twice cheaper
  // Strategy A confirms exactly the screened candidates the ISOC did not dominate.
  std::uint64_t n_calls = 0, big_calls = 0;
  for (const auto& [key, calls] : ev_a.calls()) (key.second == kn ? n_calls : big_calls) += calls;
  EXPECT_EQ(big_calls, ra.counters.confirmations);
  EXPECT_EQ(n_calls - ra.counters.screened_out - ra.counters.infeasible, big_calls);
}

TEST(VnsPhotons, StrategyBRefinesTheFinalIsocWithN) {
  const Domain d = unit_square(25);
  SyntheticEvaluator ev = bump_evaluator();
  VnsOptions o = base_options(5);
  o.strategy = PhotonStrategy::kRefineAtEnd;
  const OptimizationResult r = optimize(d, maximize_mean_illuminance("t"), ev, o);
  EXPECT_GT(r.counters.refined, 0u);
  EXPECT_EQ(r.counters.confirmations, r.counters.refined);  // no constraint asked for N early
  for (const ResultMember& m : r.isoc) {
    EXPECT_EQ(m.photons, kN);
    EXPECT_EQ(ev.calls().at({d.index(m.cells), kN}), 1);
  }
}

TEST(VnsSearch, TwoEqualPeaksBothStayInTheIsoc) {
  // Equal true heights: with confidence 0.99 the two estimates are declared different with
  // probability 1 %, so for fixed seeds both peaks must be members.
  const Domain d = unit_square(25);
  auto truth = [](const std::vector<double>& v) {
    return std::max(bump(v, 0.22, 0.22, 0.08, 100.0), bump(v, 0.78, 0.78, 0.08, 100.0));
  };
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    SyntheticEvaluator ev({truth, kSigmaN, kN}, {}, 0.99);
    VnsOptions o = base_options(seed);
    o.confidence = 0.99;
    o.starts = 4;
    o.max_iterations = 200;
    const OptimizationResult r = optimize(d, maximize_mean_illuminance("t"), ev, o);
    const std::set<std::uint64_t> cells = isoc_cells(d, r);
    EXPECT_TRUE(cells.count(d.index({5, 5}))) << "seed " << seed;
    EXPECT_TRUE(cells.count(d.index({19, 19}))) << "seed " << seed;
    for (const ResultMember& m : r.isoc) EXPECT_GE(truth(m.values), 100.0 - resolution(0.99));
    expect_pairwise_indistinguishable(r);
  }
}

TEST(VnsSearch, MinimisationFindsTheValley) {
  const Domain d = unit_square(25);
  auto truth = [](const std::vector<double>& v) { return 120.0 - bump_truth(v); };
  SyntheticEvaluator ev({truth, kSigmaN, kN}, {}, 0.95);
  const OptimizationResult r = optimize(d, minimize_mean_illuminance("t"), ev, base_options(8));
  EXPECT_EQ(r.goal, Goal::kMinimize);
  EXPECT_TRUE(isoc_cells(d, r).count(d.index({17, 8})));
  for (const ResultMember& m : r.isoc) EXPECT_LE(truth(m.values), 10.0 + resolution(0.95));
}

TEST(VnsTabu, EachCellIsTracedOncePerPhotonLevel) {
  const Domain d = unit_square(25);
  SyntheticEvaluator ev = bump_evaluator();
  const OptimizationResult r = optimize(d, maximize_mean_illuminance("t"), ev, base_options(4));
  for (const auto& [key, calls] : ev.calls()) EXPECT_EQ(calls, 1);
  EXPECT_EQ(ev.total_calls(), r.counters.evaluations);
  EXPECT_GT(r.counters.cache_hits, r.counters.evaluations);  // revisits are free
}

TEST(VnsTabu, SmallGridIsExhaustedWithOneScreeningTracePerCell) {
  const Domain d = unit_square(6);
  SyntheticEvaluator ev = bump_evaluator();
  VnsOptions o = base_options(4);
  o.max_iterations = 100000;
  const OptimizationResult r = optimize(d, maximize_mean_illuminance("t"), ev, o);
  EXPECT_EQ(r.stop, StopReason::kExhausted);
  std::uint64_t screened = 0;
  for (const auto& [key, calls] : ev.calls()) {
    EXPECT_EQ(calls, 1);
    if (key.second == kn) ++screened;
  }
  EXPECT_EQ(screened, d.cell_count());
  EXPECT_LT(r.counters.iterations, 1000u);
}

TEST(VnsDeterminism, SameSeedSameIsocAndSameTraces) {
  const Domain d = unit_square(25);
  SyntheticEvaluator e1 = bump_evaluator(), e2 = bump_evaluator();
  VnsOptions o = base_options(21);
  o.starts = 3;
  const OptimizationResult r1 = optimize(d, maximize_mean_illuminance("t"), e1, o);
  const OptimizationResult r2 = optimize(d, maximize_mean_illuminance("t"), e2, o);
  ASSERT_EQ(r1.isoc.size(), r2.isoc.size());
  for (std::size_t i = 0; i < r1.isoc.size(); ++i) {
    EXPECT_EQ(r1.isoc[i].cells, r2.isoc[i].cells);
    EXPECT_EQ(r1.isoc[i].objective.mean, r2.isoc[i].objective.mean);  // bitwise
    EXPECT_EQ(r1.isoc[i].objective.ci_low, r2.isoc[i].objective.ci_low);
  }
  EXPECT_EQ(e1.calls(), e2.calls());
  EXPECT_EQ(r1.counters.photons, r2.counters.photons);
  EXPECT_EQ(r1.counters.cases, r2.counters.cases);
  EXPECT_EQ(r1.siisoc.low, r2.siisoc.low);
  // Another seed walks elsewhere.
  SyntheticEvaluator e3 = bump_evaluator();
  VnsOptions other = o;
  other.seed = 22;
  optimize(d, maximize_mean_illuminance("t"), e3, other);
  EXPECT_NE(e1.calls(), e3.calls());
}

TEST(VnsDeterminism, EvaluationSeedDependsOnlyOnRunSeedCellAndPhotons) {
  const Domain d = unit_square(25);
  SyntheticEvaluator ev = bump_evaluator();
  VnsOptions o = base_options(77);
  optimize(d, maximize_mean_illuminance("t"), ev, o);
  for (const auto& [key, seed] : ev.seeds())
    EXPECT_EQ(seed, evaluation_seed(o.seed, key.first, key.second));
}

TEST(VnsStatistics, PerIterationSplitAndTotalsAddUp) {
  const Domain d = unit_square(25);
  SyntheticEvaluator ev = bump_evaluator();
  std::vector<IterationStats> seen;
  Control ctl;
  ctl.progress = [&](const IterationStats& s) {
    seen.push_back(s);
    return true;
  };
  const OptimizationResult r =
      optimize(d, maximize_mean_illuminance("t"), ev, base_options(3), ctl);
  ASSERT_EQ(seen.size(), r.history.size());
  ASSERT_EQ(seen.size(), r.counters.iterations);
  std::uint64_t photons = 0, evaluations = 0;
  double update = 0.0, trace = 0.0;
  for (std::size_t i = 0; i < seen.size(); ++i) {
    const IterationStats& s = seen[i];
    EXPECT_EQ(s.iteration, i + 1);
    EXPECT_GE(s.other_seconds, 0.0);
    EXPECT_NEAR(s.update_seconds, 1e-3 * s.evaluations, 1e-12);  // evaluator-reported
    EXPECT_NEAR(s.trace_seconds, 2e-3 * s.evaluations, 1e-12);
    photons += s.photons;
    evaluations += s.evaluations;
    update += s.update_seconds;
    trace += s.trace_seconds;
    EXPECT_EQ(s.total_photons, photons);
    if (s.isoc_size > 0) {
      ASSERT_TRUE(s.has_best);
      EXPECT_LE(s.best.ci_low, s.siisoc.low);  // every member's CI contains the SIISOC
    }
  }
  EXPECT_EQ(photons, r.counters.photons);
  EXPECT_EQ(evaluations, r.counters.evaluations);
  EXPECT_NEAR(update, r.counters.update_seconds, 1e-9);
  EXPECT_NEAR(trace, r.counters.trace_seconds, 1e-9);
  EXPECT_GE(r.counters.other_seconds, 0.0);
  EXPECT_EQ(seen.back().isoc_size, r.isoc.size());
}

TEST(VnsControl, EveryIsocUpdateIsReportedWithItsCase) {
  const Domain d = unit_square(25);
  SyntheticEvaluator ev = bump_evaluator();
  CaseCounts seen{};
  std::uint64_t wrong_level = 0;
  Control ctl;
  ctl.on_update = [&](const Configuration& c, std::uint64_t photons, const IsocUpdate& u) {
    ++seen[static_cast<std::size_t>(u.result)];
    if (photons != kN || ev.calls().count({d.index(c), kN}) == 0) ++wrong_level;
  };
  const OptimizationResult r =
      optimize(d, maximize_mean_illuminance("t"), ev, base_options(6), ctl);
  EXPECT_EQ(seen, r.counters.cases);
  EXPECT_EQ(wrong_level, 0u);  // strategy A offers N estimates only
  EXPECT_EQ(seen[static_cast<std::size_t>(UpdateCase::kFirst)], 1u);
  EXPECT_GT(seen[static_cast<std::size_t>(UpdateCase::kReplaced)] +
                seen[static_cast<std::size_t>(UpdateCase::kLeads)],
            0u);
}

TEST(VnsControl, ProgressCallbackReturningFalseStopsTheRun) {
  const Domain d = unit_square(25);
  SyntheticEvaluator ev = bump_evaluator();
  Control ctl;
  ctl.progress = [](const IterationStats& s) { return s.iteration < 5; };
  const OptimizationResult r =
      optimize(d, maximize_mean_illuminance("t"), ev, base_options(3), ctl);
  EXPECT_EQ(r.stop, StopReason::kCancelled);
  EXPECT_EQ(r.counters.iterations, 5u);
}

TEST(VnsControl, CancelFlagIsPolledBeforeEveryTrace) {
  const Domain d = unit_square(25);
  std::atomic<bool> cancel{false};
  int calls = 0;
  SyntheticEvaluator inner = bump_evaluator();
  FunctionEvaluator ev([&](const EvaluationRequest& r) {
    if (++calls == 10) cancel = true;
    return inner.evaluate(r);
  });
  Control ctl;
  ctl.cancel = &cancel;
  const OptimizationResult r =
      optimize(d, maximize_mean_illuminance("t"), ev, base_options(3), ctl);
  EXPECT_EQ(r.stop, StopReason::kCancelled);
  EXPECT_EQ(calls, 10);
  EXPECT_EQ(r.counters.evaluations, 10u);
}

TEST(VnsControl, EvaluationLimitAndBadOptions) {
  const Domain d = unit_square(25);
  SyntheticEvaluator ev = bump_evaluator();
  VnsOptions o = base_options(3);
  o.max_evaluations = 37;
  const OptimizationResult r = optimize(d, maximize_mean_illuminance("t"), ev, o);
  EXPECT_EQ(r.stop, StopReason::kEvaluationLimit);
  EXPECT_EQ(r.counters.evaluations, 37u);
  VnsOptions bad = base_options(3);
  bad.starts = 0;
  EXPECT_THROW(optimize(d, maximize_mean_illuminance("t"), ev, bad), std::invalid_argument);
  bad = base_options(3);
  bad.confirmation_photons = 0;
  EXPECT_THROW(optimize(d, maximize_mean_illuminance("t"), ev, bad), std::invalid_argument);
  bad = base_options(3);
  bad.initial = {{25, 0}};
  EXPECT_THROW(optimize(d, maximize_mean_illuminance("t"), ev, bad), std::invalid_argument);
  FunctionEvaluator wrong([](const EvaluationRequest&) {
    Evaluation e;
    e.constraints.resize(1);  // the intention has none
    return e;
  });
  EXPECT_THROW(optimize(d, maximize_mean_illuminance("t"), wrong, base_options(3)),
               std::invalid_argument);
}

TEST(VnsSearch, InitialConfigurationIsTheFirstCellTraced) {
  const Domain d = unit_square(25);
  std::vector<std::uint64_t> order;
  SyntheticEvaluator inner = bump_evaluator();
  FunctionEvaluator ev([&](const EvaluationRequest& r) {
    order.push_back(r.cell_index);
    return inner.evaluate(r);
  });
  VnsOptions o = base_options(3);
  o.initial = {{0, 0}};  // the paper starts in a corner
  o.local_search = LocalSearch::kBestImprovement;
  o.neighbourhood = Neighbourhood::kChebyshev;
  const OptimizationResult r = optimize(d, maximize_mean_illuminance("t"), ev, o);
  ASSERT_FALSE(order.empty());
  EXPECT_EQ(order.front(), d.index({0, 0}));
  EXPECT_TRUE(isoc_cells(d, r).count(d.index({17, 8})));
}

TEST(VnsSearch, AdmissibleFilterSkipsMirrorImagesOfInterchangeableLuminaires) {
  // Two identical luminaires on a line: (a, b) and (b, a) are the same design. Keeping
  // lum0 <= lum1 halves the grid and leaves one copy of the optimum (cells 2 and 7).
  Domain d;
  d.add_range("lum0.x", 0.0, 1.0, 10).add_range("lum1.x", 0.0, 1.0, 10);
  auto h = [](double x, double c) { return 50.0 * std::exp(-(x - c) * (x - c) / 0.02); };
  auto truth = [&](const std::vector<double>& v) {
    return std::max(h(v[0], 0.25) + h(v[1], 0.75), h(v[0], 0.75) + h(v[1], 0.25));
  };
  SyntheticEvaluator ev({truth, kSigmaN, kN}, {}, 0.95);
  VnsOptions o = base_options(2);
  o.max_iterations = 100000;  // run until the 55 admissible cells are exhausted
  o.admissible = [](const Configuration& c) { return c[0] <= c[1]; };
  const OptimizationResult r = optimize(d, maximize_mean_illuminance("t"), ev, o);
  for (const auto& [key, calls] : ev.calls()) {
    const Configuration c = d.configuration(key.first);
    EXPECT_LE(c[0], c[1]);
  }
  ASSERT_EQ(r.stop, StopReason::kExhausted);
  EXPECT_EQ(r.counters.inadmissible, 45u);  // the 10 * 9 / 2 cells with lum0 > lum1
  EXPECT_EQ(ev.calls().size() - r.counters.confirmations, 55u);  // one n trace per kept cell
  const std::set<std::uint64_t> cells = isoc_cells(d, r);
  EXPECT_TRUE(cells.count(d.index({2, 7})));
  EXPECT_FALSE(cells.count(d.index({7, 2})));
  VnsOptions bad = o;
  bad.initial = {{7, 2}};
  EXPECT_THROW(optimize(d, maximize_mean_illuminance("t"), ev, bad), std::invalid_argument);
  bad = o;
  bad.admissible = [](const Configuration&) { return false; };
  EXPECT_THROW(optimize(d, maximize_mean_illuminance("t"), ev, bad), std::invalid_argument);
}

TEST(VnsResult, JsonCarriesTheIsocAndCounters) {
  const Domain d = unit_square(25);
  SyntheticEvaluator ev = bump_evaluator();
  const OptimizationResult r = optimize(d, maximize_mean_illuminance("t"), ev, base_options(3));
  const nlohmann::json j = nlohmann::json::parse(to_json(r));
  EXPECT_EQ(j["format"], "lightsolver.optimization/1");
  EXPECT_EQ(j["goal"], "maximize");
  EXPECT_EQ(j["variables"], (nlohmann::json{"lum.x", "lum.y"}));
  ASSERT_EQ(j["isoc"].size(), r.isoc.size());
  EXPECT_EQ(j["isoc"][0]["cells"].get<Configuration>(), r.isoc[0].cells);
  EXPECT_DOUBLE_EQ(j["isoc"][0]["objective"]["mean"].get<double>(), r.isoc[0].objective.mean);
  EXPECT_EQ(j["counters"]["evaluations"].get<std::uint64_t>(), r.counters.evaluations);
  EXPECT_TRUE(j["counters"]["cases"].contains("2b"));
  EXPECT_EQ(j["history"].size(), r.history.size());
  EXPECT_DOUBLE_EQ(j["siisoc"][0].get<double>(), r.siisoc.low);
}

}  // namespace
}  // namespace lightsolver::optimizer
