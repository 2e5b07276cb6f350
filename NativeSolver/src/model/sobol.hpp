#pragma once
// Quasi-random photons (docs/statistics.md, "Quasi-random photons"): the first
// PathRng::kPrefixWords draws of a path are the coordinates of an Owen-scrambled Sobol' point,
// photon i of a (replicate, group) stream being point i; the Philox stream follows. Each
// replicate scrambles with its own seed, so replicates are independent randomisations and their
// spread gives the interval (estimate/replicates.hpp).
//
// Sobol' points: Joe & Kuo's direction numbers (new-joe-kuo-6.21201), Boost.Random's table
// (boost/random/detail/sobol_table.hpp). Scrambling: Burley's hash-based nested uniform
// scrambling ("Practical Hash-based Owen Scrambling", JCGT 9(4), 2020) with an independent
// seed per dimension. Each scrambled coordinate is uniform over the 2^32 grid (x + seed with a
// uniform seed is uniform, and the rest are bijections), so every point is uniform in the
// unit cube and a replicate's estimate is unbiased; the scramble flips each digit depending on
// the digits before it only, so the points keep their (t, m, s)-net structure.
#include <array>
#include <cstdint>

#include "lightsolver/rng.hpp"
#include "shared/sobol.h"

namespace lightsolver::detail {

/// Coordinates of a Sobol' point a path draws before its Philox stream.
inline constexpr unsigned kSobolDims = PathRng::kPrefixWords;
static_assert(kSobolDims % 4 == 0, "scrambled four coordinates at a time");

/// Direction numbers by index bit, bit-reversed: directions()[j][d] is XORed into coordinate
/// d for bit j of the point's index, and bit 0 of a stored number is the 1/2 digit (the
/// scramble works on reversed bits: building the point reversed saves a reversal per draw).
using SobolDirections = std::array<std::array<std::uint32_t, kSobolDims>, 32>;
const SobolDirections& sobol_directions();

inline std::uint32_t reverse_bits(std::uint32_t x) {
  x = __builtin_bswap32(x);
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  return ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
}

/// The unscrambled Sobol' point `index`, each coordinate's 32-bit fraction bit-reversed.
inline std::array<std::uint32_t, kSobolDims> sobol_point_reversed(std::uint32_t index) {
  const SobolDirections& v = sobol_directions();
  std::array<std::uint32_t, kSobolDims> x{};
  for (std::uint32_t i = index; i != 0; i &= i - 1) {
    const auto& column = v[__builtin_ctz(i)];
    for (unsigned d = 0; d < kSobolDims; ++d) x[d] ^= column[d];
  }
  return x;
}

/// The unscrambled Sobol' point `index` (all kSobolDims coordinates, 32-bit fractions).
inline std::array<std::uint32_t, kSobolDims> sobol_point(std::uint32_t index) {
  std::array<std::uint32_t, kSobolDims> x = sobol_point_reversed(index);
  for (std::uint32_t& c : x) c = reverse_bits(c);
  return x;
}

/// Burley's nested uniform scramble of a bit-reversed fraction `y`, returned as a fraction
/// (Shaders/shared/sobol.h, the text the shaders include too).
inline std::uint32_t owen_scramble_reversed(std::uint32_t y, std::uint32_t seed) {
  return shared::owen_scramble_reversed4(shared::uvec4(y), shared::uvec4(seed)).x;
}

/// The scramble of a fraction `x` (owen_scramble_reversed of its reversed bits).
inline std::uint32_t owen_scramble(std::uint32_t x, std::uint32_t seed) {
  return owen_scramble_reversed(reverse_bits(x), seed);
}

/// One (replicate, group) stream's scramble: a seed per dimension, drawn from Philox keyed by
/// the replicate's seed at counters no path uses (block 2^32 - 1).
struct SobolScramble {
  std::array<std::uint32_t, kSobolDims> seeds{};

  SobolScramble(std::uint64_t seed, std::uint32_t stream);

  /// Photon `index` of the stream: its PathRng, the scrambled point `index` first.
  PathRng path_rng(std::uint64_t seed, std::uint64_t index, std::uint32_t stream) const {
    PathRng rng(seed, index, stream);
    std::array<std::uint32_t, kSobolDims> x =
        sobol_point_reversed(static_cast<std::uint32_t>(index));
    for (unsigned q = 0; q < kSobolDims; q += 4) {
      const shared::uvec4 y = shared::owen_scramble_reversed4(
          shared::uvec4(x[q], x[q + 1], x[q + 2], x[q + 3]),
          shared::uvec4(seeds[q], seeds[q + 1], seeds[q + 2], seeds[q + 3]));
      for (unsigned k = 0; k < 4; ++k) x[q + k] = y[k];
    }
    rng.set_prefix(x);
    return rng;
  }
};

/// Largest photon index of one stream with a Sobol' point of its own (32-bit indices).
inline constexpr std::uint64_t kMaxSobolPoints = std::uint64_t(1) << 32;

}  // namespace lightsolver::detail
