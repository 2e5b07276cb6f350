// Sampling and geometry: Shaders/shared/sampling.h, the text the CPU includes too
// (NativeSolver/src/model/sampling.hpp), so both trace with the same float formulas and the same
// order of random draws. Needs rng_uniform() (philox.glsl) included before.
#ifndef LIGHTSOLVER_SAMPLING_GLSL
#define LIGHTSOLVER_SAMPLING_GLSL

#include "shared/sampling.h"

#endif
