// lightsolver::PathRng runs Philox4x32-10 from Shaders/shared/philox.h, the text the shaders
// include too. Random123's r123::Philox4x32 (Salmon et al.'s own implementation) is the reference:
// the stream of every (seed, path, group) must be its blocks word for word, and uniform() the top
// 24 bits of each word times 2^-24, or a seed would trace other photons than it did before.
#include "lightsolver/rng.hpp"

#include <Random123/philox.h>
#include <gtest/gtest.h>

#include <cstdint>

namespace lightsolver {
namespace {

// Word k of PathRng(seed, path, stream) by Random123: block k / 4 of counter (path, k / 4, stream).
std::uint32_t reference_word(std::uint64_t seed, std::uint64_t path, std::uint32_t stream,
                             std::uint32_t k) {
  const r123::Philox4x32::key_type key = {
      {static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)}};
  const r123::Philox4x32::ctr_type ctr = {
      {static_cast<std::uint32_t>(path), static_cast<std::uint32_t>(path >> 32), k / 4, stream}};
  return r123::Philox4x32()(ctr, key)[k % 4];
}

TEST(PathRng, EqualsRandom123WordForWord) {
  int mismatches = 0, words = 0;
  for (const std::uint64_t seed : {0ull, 1ull, 7ull, 0xDEADBEEFCAFEF00Dull, ~0ull}) {
    for (const std::uint64_t path : {0ull, 1ull, 12345ull, (1ull << 32) - 1, 1ull << 32, ~0ull}) {
      for (const std::uint32_t stream : {0u, 1u, 3u, 0xFFFFFFFFu}) {
        PathRng rng(seed, path, stream);
        for (std::uint32_t k = 0; k < 41; ++k, ++words) {  // 41 words: 11 blocks
          mismatches += rng.next_u32() != reference_word(seed, path, stream, k);
        }
      }
    }
  }
  EXPECT_EQ(mismatches, 0) << "of " << words << " words";
}

TEST(PathRng, UniformsAreTheWordsTopBits) {
  PathRng words(42, 9, 2), floats(42, 9, 2), doubles(42, 9, 2);
  for (int i = 0; i < 1000; ++i) {
    const std::uint32_t w = words.next_u32();
    EXPECT_EQ(floats.uniform(), static_cast<float>(w >> 8) * 0x1p-24f);
  }
  PathRng again(42, 9, 2);
  for (int i = 0; i < 1000; ++i) {
    const std::uint64_t hi = again.next_u32(), lo = again.next_u32();
    EXPECT_EQ(doubles.uniform_double(), static_cast<double>(((hi << 32) | lo) >> 11) * 0x1p-53);
  }
}

TEST(PathRng, UniformStaysBelowOne) {
  EXPECT_EQ(shared::uniform_from_word(0u), 0.0f);
  EXPECT_LT(shared::uniform_from_word(0xFFFFFFFFu), 1.0f);
  EXPECT_EQ(shared::uniform_from_word(0xFFFFFFFFu), 1.0f - 0x1p-24f);
}

}  // namespace
}  // namespace lightsolver
