#pragma once
// A run's batches shared among processes (lightsolver/process_group.hpp). Alone, a process
// traces every batch straight into the run's tallies. In a group, each traces its slice of
// the batch into a scratch block; the blocks are summed exactly over the group and added, so
// every process holds the same tallies as a lone process would (photon i is photon i, tallies
// are integer sums) and takes the same tally-based decisions (accuracy, decide, checkpoints).
// Decisions that depend on the clock or the user are rank 0's: agree() broadcasts them.
#include <cstdint>
#include <vector>

#include "model/backend.hpp"
#include "lightsolver/process_group.hpp"

namespace lightsolver::detail {

class SharedTracing {
 public:
  SharedTracing(ProcessGroup* group, std::size_t bins) : group_(group), bins_(bins) {}

  /// Traces photons [first, first + count): `trace(first, count, into)` traces a range into a
  /// TallyBlock; the group's sum lands in `tallies`.
  template <class TraceFn>
  void trace(std::uint64_t first, std::uint64_t count, TallyBlock& tallies, TraceFn&& trace) {
    if (group_ == nullptr) {
      trace(first, count, tallies);
      return;
    }
    TallyBlock mine(bins_);
    const PhotonRange part = split_photons(first, count, group_->rank(), group_->size());
    if (part.count > 0) trace(part.first, part.count, mine);
    std::vector<std::uint64_t> packed = pack(mine);
    group_->sum(packed);
    tallies.add(unpack(packed));
  }

  /// Rank 0's batch size and stop decision (StopPolicies::before: 0, or which policy stops
  /// the run), on every process.
  void agree(std::uint64_t& batch, std::uint64_t& stop) const {
    if (group_ == nullptr) return;
    std::uint64_t words[2] = {batch, stop};
    group_->broadcast(words);
    batch = words[0];
    stop = words[1];
  }

 private:
  std::vector<std::uint64_t> pack(const TallyBlock& t) const {
    std::vector<std::uint64_t> out;
    out.reserve(2 * bins_ + 7);
    for (const Tally& b : t.bins) {
      out.push_back(b.sum);
      out.push_back(b.sum_sq);
    }
    out.insert(out.end(), {t.ray_segments, t.capped_paths, t.cut_paths, t.retried_paths,
                           t.opening_photons, t.opening_blocked, t.opening_glass});
    return out;
  }

  TallyBlock unpack(const std::vector<std::uint64_t>& in) const {
    TallyBlock t(bins_);
    for (std::size_t i = 0; i < bins_; ++i) t.bins[i] = {in[2 * i], in[2 * i + 1]};
    const std::size_t at = 2 * bins_;
    t.ray_segments = in[at];
    t.capped_paths = in[at + 1];
    t.cut_paths = in[at + 2];
    t.retried_paths = in[at + 3];
    t.opening_photons = in[at + 4];
    t.opening_blocked = in[at + 5];
    t.opening_glass = in[at + 6];
    return t;
  }

  ProcessGroup* group_;
  std::size_t bins_;
};

}  // namespace lightsolver::detail
