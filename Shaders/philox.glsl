// The path's random stream, as lightsolver::PathRng (rng.hpp): Philox4x32-10 from
// shared/philox.h (the block function both include) with key = seed and counter = (path id lo,
// path id hi, block, group). The state is per-invocation private globals because GLSL has no
// references.
#ifndef LIGHTSOLVER_PHILOX_GLSL
#define LIGHTSOLVER_PHILOX_GLSL

#include "shared/philox.h"

uvec2 rng_key;
uvec4 rng_ctr;
uvec4 rng_block;
uint rng_index;
// Quasi-random photons (trace.comp defines LS_SOBOL_PREFIX and includes sobol.glsl): the
// path's scrambled Sobol' point, made once at its start, and its blocks still to be drawn before
// Philox, as PathRng's prefix. Only this copy sits in rng_u32: the compiler inlines rng_u32 at
// every draw, and the point's making there made lavapipe's shader compile several times slower.
uint rng_prefix_blocks = 0u;
#ifdef LS_SOBOL_PREFIX
uvec4 rng_prefix[4];
#endif

// `stream`: the luminaire group (counter word 3), PathRng's third argument.
void rng_init(uint64_t seed, uint64_t path_id, uint stream) {
  rng_key = unpackUint2x32(seed);
  rng_ctr = uvec4(unpackUint2x32(path_id), 0u, stream);
  rng_index = 4u;
  rng_prefix_blocks = 0u;
}

uint rng_u32() {
#ifdef LS_SOBOL_PREFIX
  if (rng_index == 4u && rng_prefix_blocks != 0u) {
    rng_block = rng_prefix[4u - rng_prefix_blocks];
    --rng_prefix_blocks;
    rng_index = 0u;
  }
#endif
  if (rng_index == 4u) {
    rng_block = philox4x32_10(rng_ctr, rng_key);
    rng_ctr.z += 1u;  // word 2 counts blocks within the path
    rng_index = 0u;
  }
  return rng_block[rng_index++];
}

// The 24 bits behind PathRng::uniform(): uniform() == float(rng_u24()) * 2^-24 exactly, so
// probabilities stored as integer thresholds compare exactly like the CPU's double compares.
uint rng_u24() { return rng_u32() >> 8; }

float rng_uniform() { return uniform_from_word(rng_u32()); }

// The 53-bit integer behind PathRng::uniform_double() (first word is the high half).
uint64_t rng_u53() {
  const uint hi = rng_u32();
  const uint lo = rng_u32();
  return packUint2x32(uvec2(lo, hi)) >> 11;
}

#endif
