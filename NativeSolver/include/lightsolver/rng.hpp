#pragma once
/// \file rng.hpp
/// Counter-based random numbers: every photon path owns an independent stream keyed by
/// (seed, photon index), so results do not depend on how photons are split between threads.
/// Philox4x32-10 (Salmon et al., SC'11) from Random123; the Vulkan shaders implement the same
/// function so a seed means the same thing on every backend.

#include <Random123/philox.h>

#include <cstdint>

namespace lightsolver {

/// Stream of uniform numbers for one photon path. Cheap to construct; not thread-shared.
class PathRng {
 public:
  /// \param seed     scene/run seed (64 bit)
  /// \param path_id  photon index in [0, N) within its stream
  /// \param stream   luminaire group: each group has its own photon stream (counter word 3);
  ///                 stream 0 is the stream of a scene with one group
  PathRng(std::uint64_t seed, std::uint64_t path_id, std::uint32_t stream = 0) {
    key_ = {{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)}};
    ctr_ = {{static_cast<std::uint32_t>(path_id), static_cast<std::uint32_t>(path_id >> 32), 0u,
             stream}};
  }

  /// Next uniform float in [0, 1): 24 random bits, never 1.0f.
  float uniform() { return static_cast<float>(next_u32() >> 8) * 0x1p-24f; }

  /// Next uniform double in [0, 1) with 53 random bits (for CDF look-ups over many entries).
  double uniform_double() {
    const std::uint64_t hi = next_u32(), lo = next_u32();
    return static_cast<double>(((hi << 32) | lo) >> 11) * 0x1p-53;
  }

  /// Next raw 32-bit word.
  std::uint32_t next_u32() {
    if (index_ == 4) refill();
    return block_[index_++];
  }

 private:
  void refill() {
    block_ = r123::Philox4x32()(ctr_, key_);
    ++ctr_[2];  // word 2 counts blocks within the path; 2^32 blocks is far beyond any path
    index_ = 0;
  }

  r123::Philox4x32::key_type key_{};
  r123::Philox4x32::ctr_type ctr_{};
  r123::Philox4x32::ctr_type block_{};
  unsigned index_ = 4;
};

}  // namespace lightsolver
