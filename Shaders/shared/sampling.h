// Geometry and direction sampling used on every photon bounce, one text for the CPU
// (NativeSolver/src/model/sampling.hpp) and the shaders (sampling.glsl): same float formulas, same
// order of random draws. Written in the subset of prelude.h.
#ifndef LIGHTSOLVER_SHARED_SAMPLING_H
#define LIGHTSOLVER_SHARED_SAMPLING_H

#include "prelude.h"

#ifdef __cplusplus
#include "lightsolver/rng.hpp"

namespace lightsolver::shared {
#endif

// pi rounded to float (std::numbers::pi_v<float>).
const float kPi = 3.14159265358979f;

// Moves a surface point off its surface along n by a few float ULPs scaled to the coordinate's
// magnitude (Wächter & Binder, Ray Tracing Gems ch. 6). Unlike a fixed epsilon this neither
// misses thin gaps near the origin nor re-hits the surface at large coordinates.
LS_FN vec3 offset_ray_origin(vec3 p, vec3 n) {
  const float kOrigin = 1.0f / 32.0f, kFloatScale = 1.0f / 65536.0f, kIntScale = 256.0f;
  vec3 result;
  for (int i = 0; i < 3; ++i) {
    const int of = int(kIntScale * n[i]);  // truncates toward zero
    const int bits = floatBitsToInt(p[i]) + (p[i] < 0.0f ? -of : of);
    result[i] = abs(p[i]) < kOrigin ? p[i] + kFloatScale * n[i] : intBitsToFloat(bits);
  }
  return result;
}

// copysign(1.0f, x): keeps the sign of -0.0, unlike sign().
LS_FN float copysign_one(float x) {
  return uintBitsToFloat((floatBitsToUint(x) & 0x80000000u) | 0x3f800000u);
}

// Orthonormal basis around a unit vector (Duff et al. 2017, branchless, no singularity).
LS_FN void make_frame(vec3 n, LS_OUT(vec3) t, LS_OUT(vec3) b) {
  const float s = copysign_one(n.z);
  const float a = -1.0f / (s + n.z);
  const float c = n.x * n.y * a;
  t = vec3(1.0f + s * n.x * n.x * a, s * c, -s * n.x);
  b = vec3(c, s + n.y * n.y * a, -n.y);
}

// `local` in the frame of make_frame(n), with local z along n.
LS_FN vec3 to_world(vec3 local, vec3 n) {
  vec3 t, b;
  make_frame(n, t, b);
  return local.x * t + local.y * b + local.z * n;
}

// Cosine-weighted direction about n (Lambertian emission and reflection).
LS_FN vec3 sample_cosine(vec3 n LS_RNG_PARAM) {
  const float u1 = LS_UNIFORM();
  const float u2 = LS_UNIFORM();
  const float r = sqrt(u1), phi = 2.0f * kPi * u2;
  const float z = sqrt(max(0.0f, 1.0f - u1));
  return to_world(vec3(r * cos(phi), r * sin(phi), z), n);
}

// Uniform direction on the sphere.
LS_FN vec3 sample_sphere(LS_RNG_ONLY) {
  const float z = 1.0f - 2.0f * LS_UNIFORM();
  const float r = sqrt(max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * kPi * LS_UNIFORM();
  return vec3(r * cos(phi), r * sin(phi), z);
}

// Mirror direction of d about the unit normal n (GLSL's reflect() is left to the driver).
LS_FN vec3 reflect_dir(vec3 d, vec3 n) { return d - 2.0f * dot(d, n) * n; }

// Uniform point on the parallelogram corner + s edge1 + t edge2 (s drawn first).
LS_FN vec3 point_on_parallelogram(vec3 corner, vec3 edge1, vec3 edge2 LS_RNG_PARAM) {
  const float s = LS_UNIFORM();
  const float t = LS_UNIFORM();
  return corner + s * edge1 + t * edge2;
}

// The direction at polar angle acos(cos_t) and azimuth phi about `axis`.
LS_FN vec3 cone_direction(float cos_t, float phi, vec3 axis) {
  const float sin_t = sqrt(max(0.0f, 1.0f - cos_t * cos_t));
  return to_world(vec3(sin_t * cos(phi), sin_t * sin(phi), cos_t), axis);
}

#ifdef __cplusplus
}  // namespace lightsolver::shared
#endif

#endif
