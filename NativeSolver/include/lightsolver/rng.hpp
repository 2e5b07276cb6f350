#pragma once
/// \file rng.hpp
/// Counter-based random numbers: every photon path owns an independent stream keyed by
/// (seed, photon index), so results do not depend on how photons are split between threads.
/// Philox4x32-10 (Salmon et al., SC'11) from Shaders/shared/philox.h, the text the Vulkan
/// shaders include too, so a seed means the same thing on every backend. Random123's
/// r123::Philox4x32 is the reference it is tested against (Tests/native/core/rng_test.cpp).

#include <array>
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "shared/philox.h"

namespace lightsolver {

/// Stream of uniform numbers for one photon path. Cheap to construct; not thread-shared.
class PathRng {
 public:
  /// \param seed     scene/run seed (64 bit)
  /// \param path_id  photon index in [0, N) within its stream
  /// \param stream   luminaire group: each group has its own photon stream (counter word 3);
  ///                 stream 0 is the stream of a scene with one group
  PathRng(std::uint64_t seed, std::uint64_t path_id, std::uint32_t stream = 0)
      : key_(static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)),
        ctr_(static_cast<std::uint32_t>(path_id), static_cast<std::uint32_t>(path_id >> 32), 0u,
             stream) {}

  /// Next uniform float in [0, 1): 24 random bits, never 1.0f.
  float uniform() { return shared::uniform_from_word(next_u32()); }

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

  /// Words a quasi-random point can supply at the start of a path (model/sobol.hpp).
  static constexpr unsigned kPrefixWords = 16;

  /// The stream's first kPrefixWords words become `words` (one coordinate of a quasi-random
  /// point each: uniform() reads one, uniform_double() two, the first the leading bits); the
  /// Philox words follow them. Call on a fresh stream, before any draw.
  void set_prefix(const std::array<std::uint32_t, kPrefixWords>& words) {
    prefix_ = words;
    prefix_blocks_ = kPrefixWords / 4;
  }

 private:
  void refill() {
    // A quasi-random prefix first (none in a random run: one test per four words drawn).
    if (prefix_blocks_ != 0) {
      const unsigned at = kPrefixWords - 4 * prefix_blocks_--;
      for (unsigned i = 0; i < 4; ++i) block_[i] = prefix_[at + i];
      index_ = 0;
      return;
    }
    const glm::uvec4 b = shared::philox4x32_10(ctr_, key_);
    block_ = {b.x, b.y, b.z, b.w};
    ++ctr_.z;  // word 2 counts blocks within the path; 2^32 blocks is far beyond any path
    index_ = 0;
  }

  glm::uvec2 key_;  // (seed lo, seed hi)
  glm::uvec4 ctr_;  // (path id lo, path id hi, block, stream)
  // A plain array, not a glm::uvec4: glm's operator[] is a switch over the index, a branch that
  // mispredicts every few words drawn (docs/BENCHMARKS.md, issue 23); an array is one load.
  std::array<std::uint32_t, 4> block_{};
  unsigned index_ = 4;
  unsigned prefix_blocks_ = 0;  // blocks of prefix_ not yet drawn
  std::array<std::uint32_t, kPrefixWords> prefix_{};
};

}  // namespace lightsolver
