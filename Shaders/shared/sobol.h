// Burley's nested uniform scramble of Sobol' coordinates ("Practical Hash-based Owen
// Scrambling", JCGT 9(4), 2020), four coordinates at once: one text for the CPU's
// SobolScramble (src/model/sobol.hpp) and the shaders (sobol.glsl), so Embree and Vulkan trace
// the same quasi-random paths bit for bit. Integer arithmetic only.
#ifndef LIGHTSOLVER_SHARED_SOBOL_H
#define LIGHTSOLVER_SHARED_SOBOL_H

#include "prelude.h"

#ifdef __cplusplus
namespace lightsolver::shared {
#endif

// Bit-reversed fractions `y` scrambled with one seed each, returned as fractions: each step
// changes a bit of y depending on lower ones only (an add; XOR with a product by an even
// constant), i.e. each digit of the fraction depending on the digits before it.
LS_FN uvec4 owen_scramble_reversed4(uvec4 y, uvec4 seed) {
  y += seed;
  y ^= y * 0x6c50b47cu;
  y ^= y * 0xb82f1e52u;
  y ^= y * 0xc7afe638u;
  y ^= y * 0x8d22f6e6u;
  return bitfieldReverse(y);
}

#ifdef __cplusplus
}  // namespace lightsolver::shared
#endif

#endif
