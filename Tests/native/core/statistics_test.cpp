// Estimates, intervals and the comparison operators; the honesty of the intervals (coverage over
// many seeds); determinism across thread counts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "run_facts.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

TEST(Statistics, CriticalValues) {
  EXPECT_NEAR(z_for_confidence(0.90), 1.6448536269514722, 1e-12);
  EXPECT_NEAR(z_for_confidence(0.95), 1.959963984540054, 1e-12);
  EXPECT_NEAR(z_for_confidence(0.99), 2.5758293035489004, 1e-12);
  EXPECT_NEAR(z_for_confidence(1 - 5.733e-7), 5.0, 1e-4);
  EXPECT_THROW(z_for_confidence(1.0), std::invalid_argument);
  EXPECT_THROW(z_for_confidence(0.0), std::invalid_argument);
}

TEST(Statistics, CriticalValuesToFullPrecision) {
  // sqrt(2) erf^-1(c) for the double c, from mpmath at 50 digits. Relative 1e-15 is ~4 ulps:
  // the bisection on erfc that this replaced missed 1e-10 by 2e-9 relative and was up to ~160
  // ulps off elsewhere; a formula on erf instead of erfc would lose everything near 1.
  const struct {
    double confidence, z;
  } cases[] = {{1e-300, 1.253314137315500282615e-300},
               {1e-10, 1.2533141373155002969e-10},
               {0.3, 0.38532046640756760882},
               {0.5, 0.6744897501960817432},
               {0.9, 1.6448536269514728225},
               {0.95, 1.9599639845400538556},
               {0.99, 2.5758293035489004539},
               {1 - 5.733e-7, 5.0000010572734583047},
               {1 - 1e-12, 7.1305098928792724473},
               {1 - 1e-15, 8.0269570180338918552},
               {std::nextafter(1.0, 0.0), 8.292361075813595538234}};
  for (const auto& c : cases) {
    EXPECT_NEAR(z_for_confidence(c.confidence), c.z, 1e-15 * c.z) << c.confidence;
  }
}

TEST(Statistics, EstimatesUseTheCurrentConfidence) {
  // z is cached per thread by confidence; switching back and forth must not reuse a stale one.
  const Tally t{30, 70};  // multi-hit: mean ± z·sigma
  for (double c : {0.95, 0.99, 0.95, 0.5}) {
    const Estimate e = make_estimate(t, 100, 1.0, c);
    EXPECT_DOUBLE_EQ(e.ci_high, e.mean + z_for_confidence(c) * e.sigma) << c;
  }
  EXPECT_THROW(make_estimate(t, 100, 1.0, 1.0), std::invalid_argument);
  EXPECT_DOUBLE_EQ(make_estimate(t, 100, 1.0, 0.95).ci_high,
                   0.3 + z_for_confidence(0.95) * make_estimate(t, 100, 1.0, 0.9).sigma);
}

TEST(Statistics, PerPathVarianceIsExact) {
  // Four paths depositing 0, 1, 3, 0 times: S = 4, Q = 10. Sample variance of (0,1,3,0) is
  // (10 - 16/4) / 3 = 2, so the variance of the mean is 2 / 4 = 0.5.
  const Estimate e = make_estimate({4, 10}, 4, 2.0, 0.95);
  EXPECT_DOUBLE_EQ(e.mean, 2.0);
  EXPECT_DOUBLE_EQ(e.sigma, 2.0 * std::sqrt(0.5));
  EXPECT_DOUBLE_EQ(e.ci_high, 2.0 + z_for_confidence(0.95) * e.sigma);
  EXPECT_DOUBLE_EQ(e.ci_low, 0.0);  // clamped: illuminance is never negative
  EXPECT_EQ(e.hits, 4u);
}

TEST(Statistics, HugeCountsKeepPrecision) {
  // 5 * 10^11 paths each depositing exactly twice: S = 10^12, Q = 2 * 10^12, N Q = S^2.
  const Estimate e =
      make_estimate({1'000'000'000'000ull, 2'000'000'000'000ull}, 500'000'000'000ull, 1.0, 0.95);
  EXPECT_DOUBLE_EQ(e.mean, 2.0);
  EXPECT_EQ(e.sigma, 0.0);
}

TEST(Statistics, WilsonIntervalAtZeroAndFewHits) {
  const double z = z_for_confidence(0.95);
  const Estimate none = make_estimate({0, 0}, 1000, 100.0, 0.95);
  EXPECT_EQ(none.mean, 0.0);
  EXPECT_EQ(none.ci_low, 0.0);
  EXPECT_NEAR(none.ci_high, 100.0 * z * z / (1000 + z * z), 1e-12);  // not a zero-width lie
  const Estimate few = make_estimate({3, 3}, 1000, 100.0, 0.95);
  EXPECT_GT(few.ci_low, 0.0);
  EXPECT_LT(few.ci_low, few.mean);
  EXPECT_GT(few.ci_high - few.mean, few.mean - few.ci_low);  // skewed like the binomial
}

TEST(Statistics, ComparisonOperatorsFollowEquations7To9) {
  const double z = z_for_confidence(0.95);
  Estimate a, b;
  a.sigma = 3.0;
  b.sigma = 4.0;  // combined sigma 5: the threshold is 5 z
  a.mean = 100.0;
  b.mean = 100.0 - 5.0 * z - 1e-9;
  EXPECT_EQ(compare(a, b, 0.95), Relation::Greater);
  EXPECT_EQ(compare(b, a, 0.95), Relation::Less);
  EXPECT_TRUE(greater_alpha(a, b, 0.95));
  EXPECT_TRUE(less_alpha(b, a, 0.95));
  EXPECT_TRUE(distinguishable_alpha(a, b, 0.95));
  b.mean = 100.0 - 5.0 * z + 1e-9;  // just inside: indistinguishable
  EXPECT_EQ(compare(a, b, 0.95), Relation::Indistinguishable);
  EXPECT_TRUE(equal_alpha(a, b, 0.95));
  // CIs that overlap can still be distinguishable (Eq. 11 vs Eq. 9): 3z + 4z > 5z.
  b.mean = 100.0 - 6.0 * z;
  EXPECT_TRUE(greater_alpha(a, b, 0.95));
  EXPECT_GT(b.mean + z * b.sigma, a.mean - z * a.sigma);
  // A higher confidence widens the threshold.
  EXPECT_EQ(compare(a, b, 0.999), Relation::Indistinguishable);
}

// Runs `seeds` small independent solves and counts how often the 95% interval holds `exact`.
// A naive interval from the hit count alone (the paper's binomial/Poisson formula) is counted
// too, to show why per-path variances are needed in reflective rooms.
struct Coverage {
  int honest = 0, naive = 0, runs = 0;
};

Coverage coverage(Scene s, std::uint64_t photons, double exact, int seeds) {
  validate(s);
  Coverage c;
  const double z = z_for_confidence(0.95);
  for (int seed = 1; seed <= seeds; ++seed) {
    SolveOptions o;
    o.photons = photons;
    o.seed = 1000003ull * seed;
    o.threads = 1;
    const Results r = solve(s, o);
    const TargetResult& t = r.targets[0];
    const Estimate& e = t.is_grid ? t.cells[0] : t.estimate;
    c.honest += e.ci_low <= exact && exact <= e.ci_high;
    const double naive_sigma = e.mean / std::sqrt(std::max<double>(1.0, double(e.hits)));
    c.naive += std::abs(e.mean - exact) <= z * naive_sigma;
    ++c.runs;
  }
  return c;
}

TEST(CiHonesty, OnceHitTargetCovers95Percent) {
  Scene s;
  const dvec3 src(0, 0, 2), c(-0.2, -0.2, 0), e(0.4, 0, 0), f(0, 0.4, 0);
  s.luminaires.push_back(point_light(src, 1000.0));
  s.targets.push_back(grid("probe", c, e, f, 1, 1));
  const Coverage cov = coverage(s, 4000, point_source_patch_lux(src, 1000.0, c, e, f), 1000);
  // Binomial sd of the coverage over 1000 runs is 0.7%: [93%, 97%] is about +-2.9 sd.
  EXPECT_GE(cov.honest, 930) << "coverage " << cov.honest / 10.0 << "%";
  EXPECT_LE(cov.honest, 970) << "coverage " << cov.honest / 10.0 << "%";
}

TEST(CiHonesty, ReflectiveCubeCovers95PercentWhereHitCountsDoNot) {
  Scene s;
  add_material(s, "white", Material::Type::Diffuse, 0.9);
  Mesh room = room_mesh("cube", 0, dvec3(0), dvec3(4), 1);
  Mesh floor;  // the floor as its own target mesh: paths hit it again and again
  floor.name = "floor";
  floor.material = 0;
  floor.vertices = room.vertices;
  floor.triangles.assign(room.triangles.begin(), room.triangles.begin() + 2);
  room.triangles.erase(room.triangles.begin(), room.triangles.begin() + 2);
  s.meshes = {room, floor};
  s.targets.push_back(surface("floor", 1));
  s.luminaires.push_back(point_light(dvec3(2), 10'000.0));
  const double exact = 10'000.0 / (96.0 * 0.1);  // each face of the cube: Phi / (S (1 - rho))
  const Coverage cov = coverage(s, 2000, exact, 1000);
  EXPECT_GE(cov.honest, 930) << "coverage " << cov.honest / 10.0 << "%";
  EXPECT_LE(cov.honest, 970) << "coverage " << cov.honest / 10.0 << "%";
  // Measured about 80%: more than 20 coverage-sd below 95%.
  EXPECT_LT(cov.naive, 900) << "hit-count intervals should under-cover here: " << cov.naive;
}

TEST(Determinism, BitIdenticalForAnyThreadCount) {
  Scene s;
  add_material(s, "white", Material::Type::Diffuse, 0.7);
  s.meshes.push_back(room_mesh("room", 0, dvec3(0), dvec3(5, 4, 3), 3));
  s.targets.push_back(surface("room", 0));
  s.targets.push_back(grid("workplane", {0.5, 0.5, 0.8}, {4, 0, 0}, {0, 3, 0}, 8, 6));
  s.luminaires.push_back(point_light({2.5, 2, 2.8}, 3000.0));
  validate(s);
  std::string reference;
  for (int threads : {1, 2, 3, 0}) {
    SolveOptions o;
    o.photons = 300'000;
    o.seed = 42;
    o.threads = threads;
    // The timing and the provenance's run facts (threads among them) are all that may differ.
    const std::string json = results_to_json(without_run_facts(solve(s, o)));
    if (reference.empty()) reference = json;
    EXPECT_EQ(json, reference) << "threads = " << threads;
  }
  SolveOptions other;
  other.photons = 300'000;
  other.seed = 43;
  Results r = solve(s, other);
  EXPECT_NE(r.targets[0].estimate.hits, 0u);
  EXPECT_NE(results_to_json(without_run_facts(r)), reference)
      << "a different seed must give different photons";
}

TEST(Cancellation, StopsAtABatchBoundaryAndMarksPartial) {
  Scene s;
  s.luminaires.push_back(point_light({0, 0, 1}, 100.0));
  s.targets.push_back(grid("g", {-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 2, 2));
  validate(s);
  SolveOptions o;
  // Batches grow to ~0.2 s each (at most 2^25 photons): three of them never finish 10^9,
  // however fast the machine.
  o.photons = 1'000'000'000;
  int calls = 0;
  const Results r = solve(s, o, [&](std::uint64_t, std::uint64_t) { return ++calls < 3; });
  EXPECT_TRUE(r.partial);
  EXPECT_GT(r.photons, 0u);
  EXPECT_LT(r.photons, 1'000'000'000u);
  EXPECT_GT(r.targets[0].estimate.mean, 0.0);  // an unbiased estimate from what was traced
  std::atomic<bool> cancel{true};
  o.cancel = &cancel;
  const Results none = solve(s, o);
  EXPECT_TRUE(none.partial);
  EXPECT_EQ(none.photons, 0u);
}

}  // namespace
}  // namespace lightsolver::test

namespace lightsolver::test {
namespace {

TEST(Accuracy, StopsWhenEveryTargetIsPreciseEnough) {
  Scene s;
  add_material(s, "white", Material::Type::Diffuse, 0.6);
  s.meshes.push_back(room_mesh("room", 0, dvec3(0), dvec3(4, 3, 3), 2));
  s.targets.push_back(surface("room", 0));
  s.targets.push_back(grid("desk", {1, 1, 0.8}, {1, 0, 0}, {0, 0.6, 0}, 1, 1));
  s.luminaires.push_back(point_light({2, 1.5, 2.5}, 2000.0));
  validate(s);
  SolveOptions o;
  o.photons = 100'000'000;
  o.target_accuracy = 0.03;
  const Results r = solve(s, o);
  EXPECT_TRUE(r.accuracy_met);
  EXPECT_FALSE(r.partial);
  EXPECT_LT(r.photons, 100'000'000u);
  for (const auto& t : r.targets) {
    EXPECT_LE(0.5 * (t.estimate.ci_high - t.estimate.ci_low), 0.03 * t.estimate.mean) << t.name;
  }
  const Results again = solve(s, o);
  EXPECT_EQ(again.photons, r.photons);  // the stopping point is deterministic
  o.photons = 2'000;                    // a budget too small for the goal
  const Results short_run = solve(s, o);
  EXPECT_FALSE(short_run.accuracy_met);
  EXPECT_EQ(short_run.photons, 2'000u);
  EXPECT_FALSE(short_run.warnings.empty());
  o.target_accuracy = 0.0;
  EXPECT_THROW(solve(s, o), InputError);
}

}  // namespace
}  // namespace lightsolver::test

namespace lightsolver::test {
namespace {

TEST(Statistics, EstimateRecordsWhichIntervalItUsed) {
  EXPECT_TRUE(make_estimate({3, 3}, 1000, 1.0, 0.95).binomial);
  EXPECT_FALSE(make_estimate({4, 10}, 4, 1.0, 0.95).binomial);
  const auto [low, high] = wilson_interval(3, 1000, z_for_confidence(0.95));
  const Estimate e = make_estimate({3, 3}, 1000, 2.0, 0.95);
  EXPECT_DOUBLE_EQ(e.ci_low, 2.0 * low);
  EXPECT_DOUBLE_EQ(e.ci_high, 2.0 * high);
  EXPECT_EQ(wilson_interval(0, 50, 2.0).first, 0.0);
}

}  // namespace
}  // namespace lightsolver::test

// Every interval holds its estimate, exactly, at the edges where rounding bites: p = 0 and
// p = 1 (a closed black room where each path deposits once gave ci_high one ulp below the
// mean), one hit or one miss in 1..10^13 trials, scales from 1e-300 to 1e12 including ones
// that are not powers of two, and per-path tallies with S^2 at or next to N Q.
namespace lightsolver::test {
namespace {

std::vector<std::uint64_t> edge_trial_counts() {
  std::vector<std::uint64_t> n = {1, 2, 3};
  for (int k = 2; k <= 43; ++k) {  // 2^43 ~ 8.8e12
    n.push_back((1ull << k) - 1);
    n.push_back((1ull << k) + 1);
  }
  for (std::uint64_t p = 10; p <= 10'000'000'000'000ull; p *= 10) n.push_back(p);
  return n;
}

const double kEdgeScales[] = {1e-300, 1e-100, 3.7e-7, 0.1,  1.0 / 3.0, 0.7,
                              1.0,    100.0,  1e6,    1e12, 0.0};
const double kEdgeConfidences[] = {0.5, 0.68, 0.9, 0.95, 0.99, 0.999, 0.999999, 0.9999994};

// Counts every failure instead of stopping at the first, so a regression shows its extent.
struct Containment {
  int checked = 0, failed = 0;
  std::string first_failure;
  void check(const Tally& t, std::uint64_t n, double scale, double confidence) {
    const Estimate e = make_estimate(t, n, scale, confidence);
    ++checked;
    const bool ok = std::isfinite(e.mean) && std::isfinite(e.sigma) && std::isfinite(e.ci_low) &&
                    std::isfinite(e.ci_high) && e.ci_low >= 0.0 && e.ci_low <= e.mean &&
                    e.mean <= e.ci_high && e.sigma >= 0.0;
    if (!ok && failed++ == 0) {
      char buf[256];
      std::snprintf(buf, sizeof buf,
                    "S=%llu Q=%llu N=%llu scale=%.17g c=%g: [%.17g, %.17g] mean %.17g",
                    (unsigned long long)t.sum, (unsigned long long)t.sum_sq, (unsigned long long)n,
                    scale, confidence, e.ci_low, e.ci_high, e.mean);
      first_failure = buf;
    }
  }
};

TEST(Statistics, BinomialIntervalsContainTheirEstimateAtTheEdges) {
  Containment c;
  for (const std::uint64_t n : edge_trial_counts()) {
    for (const std::uint64_t hits : {std::uint64_t(0), std::uint64_t(1), n - 1, n}) {
      if (hits > n) continue;
      for (const double scale : kEdgeScales) {
        for (const double conf : kEdgeConfidences) c.check({hits, hits}, n, scale, conf);
      }
    }
  }
  EXPECT_EQ(c.failed, 0) << "of " << c.checked << "; first: " << c.first_failure;
  EXPECT_GT(c.checked, 30'000);
}

TEST(Statistics, PerPathIntervalsContainTheirEstimateAtTheEdges) {
  Containment c;
  for (const std::uint64_t n : edge_trial_counts()) {
    for (const std::uint64_t k : {std::uint64_t(2), std::uint64_t(3), std::uint64_t(1001)}) {
      if (n > max_photons(1000)) continue;  // k <= max_bounces + 1: as large as a run can be
      std::vector<Tally> tallies = {
          {n * k, n * k * k},                  // every path k times: S^2 = N Q, sigma 0
          {n * k + 1, n * k * k + 2 * k + 1},  // one path once more: S^2 just below N Q
          {k, k * k},                          // a single path deposited k times
          {n + 1, n + 3},                      // every path once, one path twice: p > 1
      };
      if (n >= 2) tallies.push_back({n * k - 1, n * k * k - 2 * k + 1});  // one path once less
      for (const Tally& t : tallies) {
        for (const double scale : kEdgeScales) {
          for (const double conf : kEdgeConfidences) c.check(t, n, scale, conf);
        }
      }
    }
  }
  EXPECT_EQ(c.failed, 0) << "of " << c.checked << "; first: " << c.first_failure;
  EXPECT_GT(c.checked, 30'000);
}

TEST(Statistics, EveryPathOnceGivesAnUpperBoundEqualToTheMean) {
  // The closed black room: N paths, each deposits exactly once, p = 1. Wilson's upper end is
  // exactly 1 there, so ci_high is exactly the mean, not one ulp below it.
  for (const std::uint64_t n : {1ull, 3ull, 1000ull, 123'457ull, 1ull << 40}) {
    const Estimate e = make_estimate({n, n}, n, 100.0, 0.95);
    EXPECT_EQ(e.mean, 100.0);
    EXPECT_EQ(e.ci_high, 100.0) << n;
    EXPECT_LE(e.ci_low, 100.0);
    EXPECT_TRUE(e.binomial);
  }
  const auto [low, high] = wilson_interval(7, 7, 3.0);
  EXPECT_EQ(high, 1.0);
  EXPECT_LT(low, 1.0);
  EXPECT_EQ(wilson_interval(0, 0, 2.0), std::make_pair(0.0, 1.0));
  EXPECT_THROW(wilson_interval(8, 7, 2.0), std::invalid_argument);
}

TEST(Statistics, BinomialSigmaIsPinned) {
  // 25 hits in 100 paths at scale 4: sigma = 4 sqrt(0.25 * 0.75 / 100) = sqrt(0.03). The
  // optimizer's comparisons use sigma, not the Wilson bounds: a doubled sigma must fail here.
  const Estimate e = make_estimate({25, 25}, 100, 4.0, 0.95);
  ASSERT_TRUE(e.binomial);
  EXPECT_DOUBLE_EQ(e.mean, 1.0);
  EXPECT_NEAR(e.sigma, 0.17320508075688773, 1e-15);
}

TEST(Statistics, PerPathSigmaIsPinned) {
  // Five paths depositing 0, 2, 0, 2, 1 times: S = 5, Q = 9. Sample variance
  // (9 - 25/5) / 4 = 1, variance of the mean 1/5; at scale 10 sigma = 10 sqrt(0.2).
  const Estimate e = make_estimate({5, 9}, 5, 10.0, 0.95);
  ASSERT_FALSE(e.binomial);
  EXPECT_DOUBLE_EQ(e.mean, 10.0);
  EXPECT_NEAR(e.sigma, 4.47213595499958, 1e-13);
  const double z = z_for_confidence(0.95);
  EXPECT_NEAR(e.ci_low, 10.0 - z * 4.47213595499958, 1e-12);
  EXPECT_NEAR(e.ci_high, 10.0 + z * 4.47213595499958, 1e-12);
}

TEST(Statistics, EstimatesAreFiniteOrRefused) {
  EXPECT_THROW(make_estimate({1, 1}, 10, INFINITY, 0.95), std::invalid_argument);
  EXPECT_THROW(make_estimate({1, 1}, 10, -1.0, 0.95), std::invalid_argument);
  EXPECT_THROW(make_estimate({1, 1}, 10, NAN, 0.95), std::invalid_argument);
  // A scale no validated scene reaches (flux / area <= 10^12 lm / 10^-12 m2 per luminaire):
  // mean ± z sigma would overflow; refused rather than reported as inf.
  EXPECT_THROW(make_estimate({2002, 2002 * 1001}, 2, 1e306, 0.95), std::overflow_error);
}

TEST(Statistics, PhotonMaximumKeepsTalliesFromOverflowing) {
  constexpr std::uint64_t kAll = std::numeric_limits<std::uint64_t>::max();
  EXPECT_EQ(max_photons(0), kMaxPhotons);
  EXPECT_EQ(max_photons(1000), kMaxPhotons);  // the default max_bounces: 10^13 photons
  for (const std::uint32_t b : {0u, 1000u, 3000u, 4000u, 100'000u, 1'000'000u, 4'000'000'000u}) {
    // Q <= N (B + 1)^2 must fit in 64 bits; S and the ray-segment count, N (B + 1), are smaller.
    const unsigned __int128 per_path = static_cast<unsigned __int128>(b + 1ull) * (b + 1ull);
    const std::uint64_t n = max_photons(b);
    EXPECT_GE(n, 1u) << b;
    EXPECT_LE(n * per_path, kAll) << b;
    if (n < kMaxPhotons) EXPECT_GT((n + 1) * per_path, kAll) << "not the largest for " << b;
  }
  EXPECT_LT(max_photons(1'000'000), 20'000'000u);  // (2^64 - 1) / (10^6 + 1)^2 = 18446707
}

}  // namespace
}  // namespace lightsolver::test
