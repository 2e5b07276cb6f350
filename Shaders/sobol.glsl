// Quasi-random photons on the GPU, as lightsolver::detail::SobolScramble::path_rng
// (src/model/sobol.hpp): photon i of a (seed, group) stream draws the coordinates of Sobol'
// point i first, each Owen-scrambled by Burley's hash with a seed per coordinate, then Philox.
// Bit for bit the CPU's: the same direction numbers (uploaded from sobol_directions()), the same
// integer scramble, the same Philox-drawn scramble seeds.
#ifndef LIGHTSOLVER_SOBOL_GLSL
#define LIGHTSOLVER_SOBOL_GLSL

#include "shared/philox.h"

uint rng_sobol_index;  // the path's photon index in its stream (its Sobol' point)

// owen_scramble_reversed of sobol.hpp, four coordinates at once.
uvec4 owen_scramble_reversed4(uvec4 y, uvec4 seed) {
  y += seed;
  y ^= y * 0x6c50b47cu;
  y ^= y * 0xb82f1e52u;
  y ^= y * 0xc7afe638u;
  y ^= y * 0x8d22f6e6u;
  return bitfieldReverse(y);
}

// Coordinates 4q .. 4q + 3 of the path's scrambled point: the reversed directions of the set
// bits of its index XORed (unrolled: lavapipe's loop limit never sees it), then scrambled with
// the seeds SobolScramble draws: Philox block (q, 0, 2^32 - 1, group) under the run's seed.
uvec4 sobol_prefix_block(uint q) {
  uvec4 x = uvec4(0u);
  [[unroll]] for (uint j = 0u; j < 32u; ++j) {
    if (((rng_sobol_index >> j) & 1u) != 0u) x ^= sobol_directions[j * 4u + q];
  }
  const uvec4 seeds = philox4x32_10(uvec4(q, 0u, 0xFFFFFFFFu, rng_ctr.w), rng_key);
  return owen_scramble_reversed4(x, seeds);
}

// After rng_init: the path draws its point's 16 coordinates before Philox.
void rng_start_quasi_random(uint64_t photon) {
  rng_sobol_index = uint(photon);  // 32-bit indices (kMaxSobolPoints)
  rng_prefix_blocks = 4u;
}

#endif
