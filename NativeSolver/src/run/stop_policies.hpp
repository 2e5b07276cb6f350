#pragma once
// A run's stopping rules, one small unit each, and the observers of its batches
// (Simulation::run_from). The loop asks the policies in a fixed order before and after every
// batch and records the first that stops the run as its stop_reason ("photons", "cancelled",
// "time", "accuracy", "decided"). Each unit sees only a BatchState and what it was built with,
// so it is tested alone by feeding it states (Tests/native/core/stop_policies_test.cpp).
//
// Processes (docs/cluster.md): a policy asked before a batch may read the clock or the user
// (time, cancel); its answer is rank 0's, broadcast with the batch size (SharedTracing::agree
// carries the index of the stopping policy). A policy asked after a batch reads only the
// tallies, which every process holds alike, so every process stops at the same batch without
// a message.
#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "lightsolver/solver.hpp"

namespace lightsolver::detail {

/// What a policy or observer sees between two batches.
struct BatchState {
  std::uint64_t photons = 0;    ///< traced so far, counted from the run's photon 0
  std::uint64_t requested = 0;  ///< the run's photon budget
  double elapsed_s = 0.0;       ///< seconds of tracing so far
};

/// One stopping rule; by default it never stops.
class StopPolicy {
 public:
  explicit StopPolicy(const char* reason) : reason_(reason) {}
  virtual ~StopPolicy() = default;
  /// The run's stop_reason (kStop*) when this policy ends it.
  const char* reason() const { return reason_; }
  /// Before the next batch: true ends the run (the clock and the user; rank 0's answer).
  virtual bool stop_before(const BatchState&) { return false; }
  /// After a batch: true ends the run (the tallies, alike on every process).
  virtual bool stop_after(const BatchState&) { return false; }

 private:
  const char* reason_;
};

/// The photon budget: every requested photon is traced ("photons").
class PhotonLimit final : public StopPolicy {
 public:
  PhotonLimit() : StopPolicy(kStopPhotons) {}
  bool stop_before(const BatchState& s) override { return s.photons >= s.requested; }
};

/// The cancel flag, or a progress callback that returned false ("cancelled"). Acted on before
/// the next batch, so the batch in flight completes.
class CancelPolicy final : public StopPolicy {
 public:
  explicit CancelPolicy(const std::atomic<bool>* flag) : StopPolicy(kStopCancelled), flag_(flag) {}
  /// The user asked to stop (the progress callback's false).
  void request() { requested_ = true; }
  bool stop_before(const BatchState&) override {
    return requested_ || (flag_ != nullptr && flag_->load());
  }

 private:
  const std::atomic<bool>* flag_;
  bool requested_ = false;
};

/// The time limit ("time"): checked before each batch once a photon is traced, and a batch
/// that would end well past it is shortened to end near it.
class TimeLimit final : public StopPolicy {
 public:
  explicit TimeLimit(std::optional<double> max_seconds)
      : StopPolicy(kStopTime), max_seconds_(max_seconds) {}
  bool stop_before(const BatchState& s) override {
    return max_seconds_ && s.photons > 0 && s.elapsed_s >= *max_seconds_;
  }
  /// Batch `n` shortened to what fits in the time left at `photons_per_second` (at least
  /// 2^14 photons; unchanged without a limit or a rate yet).
  std::uint64_t fit(std::uint64_t n, double photons_per_second, double elapsed_s) const;

 private:
  std::optional<double> max_seconds_;
};

/// An accuracy goal ("accuracy"): stops once the run's measure (the largest relative
/// half-width over targets or cells, infinite while one has no hit) is at most the goal.
/// Without a goal it never stops.
class AccuracyGoal final : public StopPolicy {
 public:
  using Width = std::function<double(const BatchState&)>;
  AccuracyGoal(std::optional<double> goal, Width width)
      : StopPolicy(kStopAccuracy), goal_(goal), width_(std::move(width)) {}
  bool stop_after(const BatchState& s) override { return goal_ && width_(s) <= *goal_; }

 private:
  std::optional<double> goal_;
  Width width_;
};

/// Decide ("decided"): the verdicts are looked at when the photons reach a power of two (a
/// bounded number of looks, each spending its share of alpha); stops when all are decided.
/// Disabled, it never looks.
class DecidePolicy final : public StopPolicy {
 public:
  /// `all_decided(photons, look)`: every verdict is decided at look number `look` (1, 2, ...).
  using Judge = std::function<bool(std::uint64_t photons, int look)>;
  DecidePolicy(bool enabled, Judge all_decided)
      : StopPolicy(kStopDecided), enabled_(enabled), all_decided_(std::move(all_decided)) {}
  bool stop_after(const BatchState& s) override;
  /// Looks taken so far (the forecast judges the open verdicts at the last one's confidence).
  int looks() const { return looks_; }

 private:
  bool enabled_;
  Judge all_decided_;
  int looks_ = 0;
};

/// The policies of a run, in the order they are asked. The order is fixed (every process
/// builds the same list), so an index names a policy across processes.
class StopPolicies {
 public:
  explicit StopPolicies(std::vector<StopPolicy*> policies) : policies_(std::move(policies)) {}
  /// 1 + the index of the first policy that stops before a batch; 0 when none does.
  std::uint64_t before(const BatchState& s) const;
  /// The same after a batch.
  std::uint64_t after(const BatchState& s) const;
  /// The stop reason of `stop` (as returned above; not 0).
  const char* reason(std::uint64_t stop) const { return policies_.at(stop - 1)->reason(); }

 private:
  std::vector<StopPolicy*> policies_;
};

/// Observer: the run's forecast, given once, after the first batch that ends past half a
/// second of tracing (the first batches include warm-up) while photons remain.
class ForecastObserver {
 public:
  using Emit = std::function<void(const BatchState&)>;
  explicit ForecastObserver(Emit emit = {}) : emit_(std::move(emit)), due_(bool(emit_)) {}
  void after_batch(const BatchState& s);

 private:
  Emit emit_;
  bool due_;
};

/// Observer: the progress callback after every batch; its false cancels the run before the
/// next batch (through `cancel`, together with the other processes).
class ProgressObserver {
 public:
  ProgressObserver(const ProgressFn& progress, CancelPolicy& cancel)
      : progress_(progress), cancel_(cancel) {}
  void after_batch(const BatchState& s) {
    if (progress_ && !progress_(s.photons, s.requested)) cancel_.request();
  }

 private:
  const ProgressFn& progress_;
  CancelPolicy& cancel_;
};

/// Observer: splits each batch at the requested checkpoints and reports each one reached.
/// Where a batch is split changes no tally (photon i is photon i).
class CheckpointSplitter {
 public:
  explicit CheckpointSplitter(std::span<const std::uint64_t> checkpoints)
      : checkpoints_(checkpoints) {}

  /// Traces photons [first, first + n) as `trace_range(from, count)` pieces, calling
  /// `reached(at)` after the piece that ends on checkpoint `at`. Checkpoints that are not
  /// ascending, or 0, are skipped.
  template <class TraceFn, class ReachedFn>
  void trace(std::uint64_t first, std::uint64_t n, TraceFn&& trace_range, ReachedFn&& reached) {
    std::uint64_t done = first;
    const std::uint64_t end = first + n;
    for (; next_ < checkpoints_.size() && checkpoints_[next_] <= end; ++next_) {
      const std::uint64_t at = checkpoints_[next_];
      if (at <= done) continue;  // not ascending, or 0: nothing new to report
      trace_range(done, at - done);
      done = at;
      reached(at);
    }
    if (done < end) trace_range(done, end - done);
  }

 private:
  std::span<const std::uint64_t> checkpoints_;
  std::size_t next_ = 0;
};

}  // namespace lightsolver::detail
