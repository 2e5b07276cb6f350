// Philox4x32-10 (Salmon et al., SC'11): the block function behind every photon path's random
// stream, one text for lightsolver::PathRng (rng.hpp) and the shaders (philox.glsl). Integer
// arithmetic only, so both sides agree bit for bit; Random123's r123::Philox4x32 is the reference
// both are tested against (core rng_test, vulkan philox_test).
#ifndef LIGHTSOLVER_SHARED_PHILOX_H
#define LIGHTSOLVER_SHARED_PHILOX_H

#include "prelude.h"

#ifdef __cplusplus
namespace lightsolver::shared {
#endif

LS_FN uvec4 philox_round(uvec4 ctr, uvec2 key) {
  uint hi0, lo0, hi1, lo1;
  umulExtended(0xD2511F53u, ctr.x, hi0, lo0);
  umulExtended(0xCD9E8D57u, ctr.z, hi1, lo1);
  return uvec4(hi1 ^ ctr.y ^ key.x, lo1, hi0 ^ ctr.w ^ key.y, lo0);
}

// Rounds written out rather than looped: lavapipe (Mesa 22.3) miscompiled the round loop when
// it sat inside another loop (spot rejection sampling drew numbers that are not in the stream).
LS_FN uvec4 philox4x32_10(uvec4 ctr, uvec2 key) {
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

// A uniform float in [0, 1) from one 32-bit word: its top 24 bits times 2^-24 (exact, never 1).
// A probability p stored as the integer threshold of these 24 bits compares exactly like u < p.
LS_FN float uniform_from_word(uint word) { return float(word >> 8) * 5.9604644775390625e-8f; }

#ifdef __cplusplus
}  // namespace lightsolver::shared
#endif

#endif
