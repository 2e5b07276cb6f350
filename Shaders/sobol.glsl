// Quasi-random photons on the GPU, as lightsolver::detail::SobolScramble::path_rng
// (src/model/sobol.hpp): photon i of a (seed, group) stream draws the coordinates of Sobol'
// point i first, each Owen-scrambled by Burley's hash with a seed per coordinate, then Philox.
// Bit for bit the CPU's: the same direction numbers (uploaded from sobol_directions()), the same
// integer scramble (shared/sobol.h, one text with the CPU), the same Philox-drawn scramble seeds.
#ifndef LIGHTSOLVER_SOBOL_GLSL
#define LIGHTSOLVER_SOBOL_GLSL

#include "shared/philox.h"
#include "shared/sobol.h"

// After rng_init: the path draws its point's 16 coordinates before Philox. Coordinates
// 4q .. 4q + 3: the reversed directions of the set bits of its index XORed (loops, not unrolled:
// their code is compiled once per pipeline; lavapipe's loop limit counts their at most 4 x 32
// iterations, and a path it cuts is traced again: trace.comp), then scrambled with the seeds
// SobolScramble draws: Philox block (q, 0, 2^32 - 1, group) under the run's seed.
void rng_start_quasi_random(uint64_t photon) {
  const uint index = uint(photon);  // 32-bit indices (kMaxSobolPoints)
  for (uint q = 0u; q < 4u; ++q) {
    uvec4 x = uvec4(0u);
    for (uint i = index; i != 0u; i &= i - 1u) x ^= sobol_directions[uint(findLSB(i)) * 4u + q];
    const uvec4 seeds = philox4x32_10(uvec4(q, 0u, 0xFFFFFFFFu, rng_ctr.w), rng_key);
    rng_prefix[q] = owen_scramble_reversed4(x, seeds);
  }
  rng_prefix_blocks = 4u;
}

#endif
