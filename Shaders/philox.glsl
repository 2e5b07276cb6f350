// Philox4x32-10 (Salmon et al., SC'11), bit-identical to Random123's r123::Philox4x32 as used by
// lightsolver::PathRng (rng.hpp): key = seed, counter = (path id lo, path id hi, block, 0).
// The state is per-invocation private globals because GLSL has no references.
#ifndef LIGHTSOLVER_PHILOX_GLSL
#define LIGHTSOLVER_PHILOX_GLSL

uvec4 philox_round(uvec4 ctr, uvec2 key) {
  uint hi0, lo0, hi1, lo1;
  umulExtended(0xD2511F53u, ctr.x, hi0, lo0);
  umulExtended(0xCD9E8D57u, ctr.z, hi1, lo1);
  return uvec4(hi1 ^ ctr.y ^ key.x, lo1, hi0 ^ ctr.w ^ key.y, lo0);
}

// Rounds written out rather than looped: lavapipe (Mesa 22.3) miscompiled the round loop when
// it sat inside another loop (spot rejection sampling drew numbers that are not in the stream).
uvec4 philox4x32_10(uvec4 ctr, uvec2 key) {
  const uvec2 weyl = uvec2(0x9E3779B9u, 0xBB67AE85u);  // key schedule
  ctr = philox_round(ctr, key);
  ctr = philox_round(ctr, key + 1u * weyl);
  ctr = philox_round(ctr, key + 2u * weyl);
  ctr = philox_round(ctr, key + 3u * weyl);
  ctr = philox_round(ctr, key + 4u * weyl);
  ctr = philox_round(ctr, key + 5u * weyl);
  ctr = philox_round(ctr, key + 6u * weyl);
  ctr = philox_round(ctr, key + 7u * weyl);
  ctr = philox_round(ctr, key + 8u * weyl);
  return philox_round(ctr, key + 9u * weyl);
}

uvec2 rng_key;
uvec4 rng_ctr;
uvec4 rng_block;
uint rng_index;

// `stream`: the luminaire group (counter word 3), PathRng's third argument.
void rng_init(uint64_t seed, uint64_t path_id, uint stream) {
  rng_key = unpackUint2x32(seed);
  rng_ctr = uvec4(unpackUint2x32(path_id), 0u, stream);
  rng_index = 4u;
}

uint rng_u32() {
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

float rng_uniform() { return float(rng_u24()) * 5.9604644775390625e-8; }

// The 53-bit integer behind PathRng::uniform_double() (first word is the high half).
uint64_t rng_u53() {
  const uint hi = rng_u32();
  const uint lo = rng_u32();
  return packUint2x32(uvec2(lo, hi)) >> 11;
}

#endif
