// The stopping rules and batch observers of a run, each alone (run/stop_policies.hpp): fed
// batch states by hand, no tracing. run_limits_test.cpp and simulation_test.cpp check them
// together in traced runs.
#include "run/stop_policies.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "run/shared_tracing.hpp"
#include "lightsolver/process_group.hpp"
#include "lightsolver/simulation.hpp"
#include "scene_builders.hpp"

namespace lightsolver::detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

BatchState at(std::uint64_t photons, std::uint64_t requested = 1000, double elapsed_s = 0.0) {
  return {photons, requested, elapsed_s};
}

TEST(StopPolicies, PhotonLimitStopsWhenTheBudgetIsTraced) {
  PhotonLimit p;
  EXPECT_STREQ(p.reason(), "photons");
  EXPECT_FALSE(p.stop_before(at(0)));
  EXPECT_FALSE(p.stop_before(at(999)));
  EXPECT_TRUE(p.stop_before(at(1000)));
  EXPECT_FALSE(p.stop_after(at(1000)));  // a before-batch rule only
}

TEST(StopPolicies, CancelStopsOnTheFlagOrARequest) {
  std::atomic<bool> flag = false;
  CancelPolicy c(&flag);
  EXPECT_STREQ(c.reason(), "cancelled");
  EXPECT_FALSE(c.stop_before(at(10)));
  flag = true;
  EXPECT_TRUE(c.stop_before(at(10)));
  flag = false;
  EXPECT_FALSE(c.stop_before(at(10)));

  CancelPolicy no_flag(nullptr);
  EXPECT_FALSE(no_flag.stop_before(at(10)));
  no_flag.request();  // the progress callback's false: for good
  EXPECT_TRUE(no_flag.stop_before(at(10)));
  EXPECT_TRUE(no_flag.stop_before(at(20)));
}

TEST(StopPolicies, TimeLimitStopsOnlyAfterAPhotonAndPastTheLimit) {
  TimeLimit t(2.0);
  EXPECT_STREQ(t.reason(), "time");
  EXPECT_FALSE(t.stop_before(at(0, 1000, 5.0)));  // no photon yet: the first batch is traced
  EXPECT_FALSE(t.stop_before(at(10, 1000, 1.99)));
  EXPECT_TRUE(t.stop_before(at(10, 1000, 2.0)));
  TimeLimit none(std::nullopt);
  EXPECT_FALSE(none.stop_before(at(10, 1000, 1e9)));
}

TEST(StopPolicies, TimeLimitShortensABatchToTheTimeLeft) {
  const TimeLimit t(2.0);
  // 1e6 photons/s and 1.5 s left: 1.5e6 fit.
  EXPECT_EQ(t.fit(4'000'000, 1e6, 0.5), 1'500'000u);
  EXPECT_EQ(t.fit(1'000'000, 1e6, 0.5), 1'000'000u);  // fits already
  EXPECT_EQ(t.fit(1'000'000, 0.0, 0.5), 1'000'000u);  // no rate yet
  EXPECT_EQ(t.fit(1'000'000, 1e6, 3.0), 1u << 14);    // past the limit: the smallest batch
  EXPECT_EQ(TimeLimit(std::nullopt).fit(1'000'000, 1e6, 9.0), 1'000'000u);
}

TEST(StopPolicies, AccuracyGoalStopsWhenTheWidthIsAtMostTheGoal) {
  std::vector<double> widths = {kInf, 0.05, 0.021, 0.02};  // no hit yet, then narrowing
  std::size_t asked = 0;
  AccuracyGoal a(0.02, [&](const BatchState&) { return widths.at(asked++); });
  EXPECT_STREQ(a.reason(), "accuracy");
  EXPECT_FALSE(a.stop_before(at(10)));  // an after-batch rule only
  EXPECT_EQ(asked, 0u);
  EXPECT_FALSE(a.stop_after(at(10)));
  EXPECT_FALSE(a.stop_after(at(20)));
  EXPECT_FALSE(a.stop_after(at(40)));
  EXPECT_TRUE(a.stop_after(at(80)));
  EXPECT_EQ(asked, 4u);

  AccuracyGoal none(std::nullopt, [&](const BatchState&) -> double {
    ADD_FAILURE() << "a run without a goal measures nothing";
    return 0.0;
  });
  EXPECT_FALSE(none.stop_after(at(10)));
}

TEST(StopPolicies, DecideLooksOnlyWhenThePhotonsDouble) {
  std::vector<std::pair<std::uint64_t, int>> looks;
  DecidePolicy d(true, [&](std::uint64_t photons, int look) {
    looks.emplace_back(photons, look);
    return photons >= 1024;  // every verdict decided from 1024 photons on
  });
  EXPECT_STREQ(d.reason(), "decided");
  for (std::uint64_t n : {3u, 256u, 300u, 512u, 1000u}) EXPECT_FALSE(d.stop_after(at(n)));
  EXPECT_TRUE(d.stop_after(at(1024)));
  const std::vector<std::pair<std::uint64_t, int>> expected = {{256, 1}, {512, 2}, {1024, 3}};
  EXPECT_EQ(looks, expected);
  EXPECT_EQ(d.looks(), 3);

  DecidePolicy off(false, [](std::uint64_t, int) { return true; });
  EXPECT_FALSE(off.stop_after(at(1024)));
  EXPECT_EQ(off.looks(), 0);
}

TEST(StopPolicies, TheFirstPolicyInOrderNamesTheStop) {
  std::atomic<bool> flag = true;
  PhotonLimit photons;
  CancelPolicy cancel(&flag);
  TimeLimit time(1.0);
  AccuracyGoal accuracy(0.5, [](const BatchState&) { return 0.1; });
  DecidePolicy decide(true, [](std::uint64_t, int) { return true; });
  const StopPolicies list({&photons, &cancel, &time, &accuracy, &decide});
  // Budget traced: "photons" before a cancel or a time limit (as the loop condition was).
  EXPECT_STREQ(list.reason(list.before(at(1000, 1000, 5.0))), "photons");
  EXPECT_STREQ(list.reason(list.before(at(10, 1000, 5.0))), "cancelled");
  flag = false;
  EXPECT_STREQ(list.reason(list.before(at(10, 1000, 5.0))), "time");
  EXPECT_EQ(list.before(at(10, 1000, 0.5)), 0u);
  // After a batch: accuracy before decide.
  EXPECT_STREQ(list.reason(list.after(at(1024))), "accuracy");
  EXPECT_EQ(list.after(at(1024)), 4u);
}

TEST(StopPolicies, TheForecastComesOnceAfterHalfASecond) {
  std::vector<double> given;
  ForecastObserver f([&](const BatchState& s) { given.push_back(s.elapsed_s); });
  f.after_batch(at(10, 1000, 0.2));
  f.after_batch(at(20, 1000, 0.49));
  EXPECT_TRUE(given.empty());
  f.after_batch(at(40, 1000, 0.6));
  f.after_batch(at(80, 1000, 1.2));
  EXPECT_EQ(given, std::vector<double>{0.6});

  ForecastObserver finished(
      [&](const BatchState&) { ADD_FAILURE() << "nothing left to forecast"; });
  finished.after_batch(at(1000, 1000, 0.7));
  ForecastObserver none;  // no callback: nothing to call
  none.after_batch(at(10, 1000, 0.7));
}

TEST(StopPolicies, ProgressReturningFalseCancelsBeforeTheNextBatch) {
  std::vector<std::uint64_t> seen;
  const ProgressFn progress = [&](std::uint64_t done, std::uint64_t total) {
    EXPECT_EQ(total, 1000u);
    seen.push_back(done);
    return done < 200;
  };
  CancelPolicy cancel(nullptr);
  ProgressObserver p(progress, cancel);
  p.after_batch(at(100));
  EXPECT_FALSE(cancel.stop_before(at(100)));
  p.after_batch(at(200));
  EXPECT_TRUE(cancel.stop_before(at(200)));
  EXPECT_EQ(seen, (std::vector<std::uint64_t>{100, 200}));
}

TEST(StopPolicies, CheckpointsSplitBatchesWithoutLosingAPhoton) {
  const std::vector<std::uint64_t> points = {0, 100, 250, 250, 200, 1000};
  CheckpointSplitter split(points);
  std::vector<std::pair<std::uint64_t, std::uint64_t>> ranges;
  std::vector<std::uint64_t> reached;
  auto trace = [&](std::uint64_t first, std::uint64_t n) { ranges.emplace_back(first, n); };
  auto report = [&](std::uint64_t at) { reached.push_back(at); };
  // 0, the second 250 and 200 (behind 250: not ascending) are skipped.
  split.trace(0, 300, trace, report);
  split.trace(300, 500, trace, report);  // no checkpoint inside: one piece
  split.trace(800, 400, trace, report);
  const std::vector<std::pair<std::uint64_t, std::uint64_t>> expected = {
      {0, 100}, {100, 150}, {250, 50}, {300, 500}, {800, 200}, {1000, 200}};
  EXPECT_EQ(ranges, expected);
  EXPECT_EQ(reached, (std::vector<std::uint64_t>{100, 250, 1000}));
}

// Rank 1 of 2, alone in this process: sum() leaves its own tallies (rank 0's part is missing,
// which these tests do not read); broadcast() gives rank 0's words, scripted by call number.
class RankOne final : public ProcessGroup {
 public:
  /// Rank 0's stop word at broadcast `call` (0-based); its batch size is this rank's own.
  std::vector<std::pair<std::size_t, std::uint64_t>> stops;
  std::size_t calls = 0;
  int rank() const override { return 1; }
  int size() const override { return 2; }
  void sum(std::span<std::uint64_t>) override {}
  void broadcast(std::span<std::uint64_t> words) override {
    words[1] = 0;
    for (const auto& [call, stop] : stops) {
      if (call == calls) words[1] = stop;
    }
    ++calls;
  }
};

TEST(StopPolicies, EveryProcessTakesRankZerosStopBeforeABatch) {
  PhotonLimit photons;
  CancelPolicy cancel(nullptr);
  TimeLimit time(1.0);
  const StopPolicies list({&photons, &cancel, &time});
  RankOne group;
  group.stops = {{0, 3}};  // rank 0's clock is past the limit, this rank's is not
  const SharedTracing shared(&group, 0);
  std::uint64_t n = 4096, stop = list.before(at(10, 1000, 0.5));
  EXPECT_EQ(stop, 0u);
  shared.agree(n, stop);
  EXPECT_EQ(n, 4096u);
  EXPECT_STREQ(list.reason(stop), "time");
}

TEST(StopPolicies, ARunOnAnotherRankStopsWhereRankZeroCancels) {
  Scene s;
  test::add_material(s, "white", Material::Type::Diffuse, 0.6);
  s.meshes.push_back(test::room_mesh("room", 0, test::dvec3(0), test::dvec3(4, 3, 3)));
  s.targets.push_back(test::surface("room", 0));
  s.luminaires.push_back(test::point_light({2, 1.5, 2.5}, 2000.0));
  Simulation sim(s, {.backend = "embree", .threads = 1, .movable_meshes = {}});
  auto group = std::make_shared<RankOne>();
  group->stops = {{2, 2}};  // rank 0 cancels before the third batch (index 2: cancel)
  SolveOptions o;
  o.photons = std::uint64_t(1) << 28;  // more than two batches can hold (at most 2^14 + 2^25)
  o.processes = group;
  const Results r = sim.run(o);
  EXPECT_EQ(r.stop_reason, "cancelled");
  EXPECT_TRUE(r.partial);
  EXPECT_EQ(group->calls, 3u);  // no batch after the agreed stop
  EXPECT_LE(r.photons, (1u << 14) + (8u << 22));
  EXPECT_GT(r.photons, 0u);
}

}  // namespace
}  // namespace lightsolver::detail
