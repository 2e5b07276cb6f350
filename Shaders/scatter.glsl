// Surface interactions: the physics is shared/scatter.h, the text NativeSolver/src/model/scatter.hpp
// includes too; here only the choice of lobe on the packed material (integer thresholds of the
// 24 random bits, which decide as the CPU's double compares) and the switch over material kinds.
// The photon keeps its power and survives by probability, so tallies stay integer counts.
#ifndef LIGHTSOLVER_SCATTER_GLSL
#define LIGHTSOLVER_SCATTER_GLSL

#include "shared/scatter.h"

bool scatter_glossy(MaterialGpu m, vec3 facing, inout vec3 dir) {
  const uint u = rng_u24();
  if (u < m.p_first) {
    dir = sample_cosine(facing);
    return true;
  }
  if (u >= m.p_second) return false;
  return reflect_ggx(m.alpha, facing, dir);
}

bool scatter_glass(MaterialGpu m, float cos_in, vec3 facing, inout vec3 dir) {
  return scatter_dielectric(m.ior, m.tau, m.thin != 0u, cos_in, facing, dir);
}

// Updates dir for the photon leaving the surface; false when absorbed. n: unit front normal.
bool scatter(MaterialGpu m, vec3 n, inout vec3 dir) {
  const float cos_in = dot(dir, n);
  const vec3 facing = cos_in < 0.0 ? n : -n;
  if (HAS_DIFFUSE && m.type == kDiffuse) {
    if (rng_u24() >= m.p_first) return false;
    dir = sample_cosine(facing);
    return true;
  }
  if (HAS_MIRROR && m.type == kMirror) {
    if (rng_u24() >= m.p_first) return false;
    dir = reflect_dir(dir, facing);
    return true;
  }
  if (HAS_GLOSSY && m.type == kGlossy) return scatter_glossy(m, facing, dir);
  if (HAS_GLASS && m.type == kGlass) return scatter_glass(m, cos_in, facing, dir);
  return false;
}

#endif
