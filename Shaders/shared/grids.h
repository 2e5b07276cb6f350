// Virtual grids (work planes, observers' squares), one text for the CPU
// (NativeSolver/src/model/path_deposits.hpp) and the shaders (deposits.glsl): where a ray segment
// crosses a grid. What is done with the crossing (per-path deposit counts) stays per language.
// Written in the subset of prelude.h.
#ifndef LIGHTSOLVER_SHARED_GRIDS_H
#define LIGHTSOLVER_SHARED_GRIDS_H

#include "prelude.h"

#ifdef __cplusplus
namespace lightsolver::shared {
#endif

// How far along a segment of length t_max grids count crossings: extended by a relative 1e-5
// (and 1e-6 absolute) so a grid lying on a surface still counts the photons arriving there
// despite the float error in t_max.
LS_FN float grid_reach(float t_max) { return t_max * (1.0f + 1e-5f) + 1e-6f; }

// True when o + t d, 0 <= t <= t_end, crosses the grid (corner, unit normal, dual vectors du and
// dv of its edges, nu x nv cells) from its front; `cell` is then iv * nu + iu. The vectors are
// LS_IN: by reference, the C++ loop over grids reads a grid's corner and edges only once its
// normal faces the segment (by value, every grid's 12 floats were loaded for every segment:
// docs/BENCHMARKS.md, issue 23).
LS_FN bool grid_crossing(LS_IN(vec3) o, LS_IN(vec3) d, float t_end, LS_IN(vec3) corner,
                         LS_IN(vec3) normal, LS_IN(vec3) du, LS_IN(vec3) dv, uint nu, uint nv,
                         LS_OUT(uint) cell) {
  const float denom = dot(d, normal);
  if (!(denom < 0.0f)) return false;  // parallel, or crossing from behind
  const float t = dot(corner - o, normal) / denom;
  if (!(t >= 0.0f && t <= t_end)) return false;
  const vec3 rel = o + t * d - corner;
  const float a = dot(rel, du), b = dot(rel, dv);
  if (!(a >= 0.0f && a < 1.0f && b >= 0.0f && b < 1.0f)) return false;
  const uint iu = min(uint(a * float(nu)), nu - 1u);
  const uint iv = min(uint(b * float(nv)), nv - 1u);
  cell = iv * nu + iu;
  return true;
}

#ifdef __cplusplus
}  // namespace lightsolver::shared
#endif

#endif
