// Surface physics, one text for the CPU (NativeSolver/src/model/scatter.hpp) and the shaders
// (scatter.glsl): Fresnel reflectance, the thin pane, GGX microfacet normals, the glossy lobe's
// specular reflection and the whole dielectric (glass) interaction. Each keeps the photon's power
// and decides survival by probability; false means absorbed. Written in the subset of prelude.h.
// The choice between a material's lobes stays per language: the CPU compares a uniform float
// with the material's double probabilities, the GPU its 24 random bits with integer thresholds
// (vulkan/gpu_scene.cpp probability_threshold), which decides the same way for every draw.
#ifndef LIGHTSOLVER_SHARED_SCATTER_H
#define LIGHTSOLVER_SHARED_SCATTER_H

#include "sampling.h"

#ifdef __cplusplus
namespace lightsolver::shared {
#endif

// Fresnel reflectances of a dielectric interface for s and p polarisation. cos_i > 0 is the
// incidence cosine, eta = n_incident / n_transmitted; both are 1 on total internal reflection.
LS_FN void fresnel_sp(float cos_i, float eta, LS_OUT(float) rs, LS_OUT(float) rp,
                      LS_OUT(float) cos_t) {
  const float sin2_t = eta * eta * max(0.0f, 1.0f - cos_i * cos_i);
  if (sin2_t >= 1.0f) {  // total internal reflection
    rs = rp = 1.0f;
    cos_t = 0.0f;
    return;
  }
  cos_t = sqrt(1.0f - sin2_t);
  const float s = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const float p = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  rs = s * s;
  rp = p * p;
}

// Thin pane of two parallel interfaces with incoherent inter-reflection and internal
// transmittance tau, per polarisation: R' = R + (1-R)^2 tau^2 R / (1 - R^2 tau^2),
// T' = (1-R)^2 tau / (1 - R^2 tau^2).
LS_FN void thin_slab(float r, float tau, LS_OUT(float) reflect_p, LS_OUT(float) transmit_p) {
  const float denom = 1.0f - r * r * tau * tau;
  reflect_p = r + (1.0f - r) * (1.0f - r) * tau * tau * r / denom;
  transmit_p = (1.0f - r) * (1.0f - r) * tau / denom;
}

// GGX microfacet normal about +z with alpha (Walter et al. 2007), in local coordinates.
LS_FN vec3 sample_ggx_normal(float alpha LS_RNG_PARAM) {
  const float u1 = LS_UNIFORM();
  const float u2 = LS_UNIFORM();
  const float tan2 = alpha * alpha * u1 / max(1e-12f, 1.0f - u1);
  const float cos_t = 1.0f / sqrt(1.0f + tan2);
  const float sin_t = sqrt(max(0.0f, 1.0f - cos_t * cos_t));
  const float phi = 2.0f * kPi * u2;
  return vec3(sin_t * cos(phi), sin_t * sin(phi), cos_t);
}

// The glossy material's specular lobe: reflection about a GGX facet (the plain mirror direction
// for alpha = 0). `facing`: the normal on the photon's side. A facet turned away from the photon,
// or a reflection below the surface (a shadowed facet), absorbs it.
LS_FN bool reflect_ggx(float alpha, vec3 facing, LS_INOUT(vec3) dir LS_RNG_PARAM) {
  const vec3 micro = alpha > 0.0f ? to_world(sample_ggx_normal(alpha LS_RNG_ARG), facing) : facing;
  if (dot(dir, micro) >= 0.0f) return false;  // facet turned away from the photon
  dir = reflect_dir(dir, micro);
  return dot(dir, facing) > 0.0f;  // below the surface: absorbed
}

// Glass of index `ior` and internal transmittance `tau` of one pass through the body, applied at
// the start of every pass: on entry and after every internal reflection (Fresnel or total), so a
// thick slab transmits (1 - R)^2 tau / (1 - R^2 tau^2) as a thin pane does, and light caught by
// total internal reflection (a pane's edges against its frame) decays as in real glass instead
// of bouncing until max_bounces; `thin`: a pane of two interfaces. `cos_in`: dot(dir, n) with the front normal n (its sign says whether the photon
// enters); `facing`: the normal on the photon's side. Fresnel (mean of s and p) picks reflection;
// a thin pane then passes the photon straight on (both refractions cancel), a body refracts it.
LS_FN bool scatter_dielectric(float ior, float tau, bool thin, float cos_in, vec3 facing,
                              LS_INOUT(vec3) dir LS_RNG_PARAM) {
  const float cos_i = abs(cos_in);
  const bool entering = cos_in < 0.0f;
  const float eta = (thin || entering) ? 1.0f / ior : ior;
  float rs, rp, cos_t;
  fresnel_sp(cos_i, eta, rs, rp, cos_t);
  const float u = LS_UNIFORM();
  if (thin) {
    float rs2, ts2, rp2, tp2;
    thin_slab(rs, tau, rs2, ts2);
    thin_slab(rp, tau, rp2, tp2);
    const float r = 0.5f * (rs2 + rp2), t = 0.5f * (ts2 + tp2);
    if (u < r) {
      dir = reflect_dir(dir, facing);
      return true;
    }
    return u < r + t;
  }
  const float r = 0.5f * (rs + rp);
  if (u < r) {
    dir = reflect_dir(dir, facing);
    // Reflected inside: another pass through the body (clear glass draws nothing, so its paths
    // keep their random streams).
    return entering || tau >= 1.0f || LS_UNIFORM() < tau;
  }
  // Refraction (Snell); entering starts a pass through the body.
  dir = normalize(eta * dir + (eta * cos_i - cos_t) * facing);
  return !entering || LS_UNIFORM() < tau;
}

#ifdef __cplusplus
}  // namespace lightsolver::shared
#endif

#endif
