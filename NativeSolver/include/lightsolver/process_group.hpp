#pragma once
/// \file process_group.hpp
/// Several processes sharing one run (MPI ranks; docs/cluster.md). Every batch's photon range
/// is split across the processes and their integer tallies are summed exactly, so a run gives
/// bit-identical results whatever the number of processes. Decisions that depend on the clock
/// or the user (batch sizes, time limits, cancel) are rank 0's, broadcast to the others.
/// The core knows only this interface; the MPI implementation is lightsolver/mpi.hpp.

#include <cstdint>
#include <memory>
#include <span>

namespace lightsolver {

class ProcessGroup {
 public:
  virtual ~ProcessGroup() = default;
  /// This process's place in the group, 0 .. size() - 1; rank 0 prints and writes files.
  virtual int rank() const = 0;
  virtual int size() const = 0;
  /// Element-wise sum over every process, in place, exact (integers). Every process calls it
  /// with the same length. Throws std::runtime_error when another process has failed or does
  /// not answer in time.
  virtual void sum(std::span<std::uint64_t> values) = 0;
  /// Rank 0's `values` on every process (same length everywhere). Throws like sum().
  virtual void broadcast(std::span<std::uint64_t> values) = 0;
};

/// Photons [first, first + count) of process `rank` of `size`: contiguous, in rank order,
/// sizes differing by at most one; their union is the whole range for any size >= 1.
struct PhotonRange {
  std::uint64_t first = 0, count = 0;
};
inline PhotonRange split_photons(std::uint64_t first, std::uint64_t count, int rank, int size) {
  const auto r = static_cast<std::uint64_t>(rank), k = static_cast<std::uint64_t>(size);
  const std::uint64_t base = count / k, extra = count % k;
  const std::uint64_t begin = first + r * base + (r < extra ? r : extra);
  return {begin, base + (r < extra ? 1u : 0u)};
}

}  // namespace lightsolver
