#pragma once
// Surface interactions. Every branch keeps the photon's power unchanged and decides survival by
// probability (Russian roulette with survival = albedo), so all photons carry equal power and
// tallies stay integer counts; absorption ends the path without bias.
#include <algorithm>
#include <cmath>

#include "core/sampling.hpp"
#include "lightsolver/scene.hpp"

namespace lightsolver::detail {

// Unpolarised Fresnel reflectance of a dielectric interface: the mean of s and p.
// cos_i > 0 is the incidence cosine, eta = n_incident / n_transmitted. Returns 1 on TIR.
inline void fresnel_sp(float cos_i, float eta, float& rs, float& rp, float& cos_t) {
  const float sin2_t = eta * eta * std::max(0.0f, 1.0f - cos_i * cos_i);
  if (sin2_t >= 1.0f) {
    rs = rp = 1.0f;
    cos_t = 0.0f;
    return;
  }
  cos_t = std::sqrt(1.0f - sin2_t);
  const float s = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const float p = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  rs = s * s;
  rp = p * p;
}

// Thin pane of two parallel interfaces with incoherent inter-reflection and internal
// transmittance tau, per polarisation: R' = R + (1-R)^2 tau^2 R / (1 - R^2 tau^2),
// T' = (1-R)^2 tau / (1 - R^2 tau^2).
inline void thin_slab(float r, float tau, float& reflect, float& transmit) {
  const float denom = 1.0f - r * r * tau * tau;
  reflect = r + (1.0f - r) * (1.0f - r) * tau * tau * r / denom;
  transmit = (1.0f - r) * (1.0f - r) * tau / denom;
}

// GGX microfacet normal about +z with alpha (Walter et al. 2007), in local coordinates.
inline vec3 sample_ggx_normal(float alpha, PathRng& rng) {
  const float u1 = rng.uniform(), u2 = rng.uniform();
  const float tan2 = alpha * alpha * u1 / std::max(1e-12f, 1.0f - u1);
  const float cos_t = 1.0f / std::sqrt(1.0f + tan2);
  const float sin_t = std::sqrt(std::max(0.0f, 1.0f - cos_t * cos_t));
  const float phi = 2.0f * std::numbers::pi_v<float> * u2;
  return vec3(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t);
}

// One function per material kind; `facing` is the normal on the side the photon arrived from.
// Each keeps the photon's power and returns false when it is absorbed.
inline bool scatter_diffuse(const Material& m, const vec3& facing, vec3& dir, PathRng& rng) {
  if (rng.uniform() >= m.reflectance) return false;
  dir = sample_cosine(facing, rng);
  return true;
}

inline bool scatter_mirror(const Material& m, const vec3& facing, vec3& dir, PathRng& rng) {
  if (rng.uniform() >= m.reflectance) return false;
  dir = reflect(dir, facing);
  return true;
}

inline bool scatter_glossy(const Material& m, const vec3& facing, vec3& dir, PathRng& rng) {
  const float u = rng.uniform();
  if (u < m.reflectance) {
    dir = sample_cosine(facing, rng);
    return true;
  }
  if (u >= m.reflectance + m.specular) return false;
  const float alpha = static_cast<float>(m.roughness * m.roughness);
  const vec3 micro = alpha > 0.0f ? to_world(sample_ggx_normal(alpha, rng), facing) : facing;
  if (glm::dot(dir, micro) >= 0.0f) return false;  // facet turned away from the photon
  dir = reflect(dir, micro);
  return glm::dot(dir, facing) > 0.0f;  // below the surface: absorbed (shadowed facet)
}

// `cos_in`: dot(dir, n) with the front normal n (its sign says whether the photon enters).
inline bool scatter_glass(const Material& m, float cos_in, const vec3& facing, vec3& dir,
                          PathRng& rng) {
  const float cos_i = std::abs(cos_in);
  const bool entering = cos_in < 0.0f;
  const float ior = static_cast<float>(m.ior), tau = static_cast<float>(m.transmittance);
  const float eta = m.thin || entering ? 1.0f / ior : ior;
  float rs, rp, cos_t;
  fresnel_sp(cos_i, eta, rs, rp, cos_t);
  const float u = rng.uniform();
  if (m.thin) {
    float rs2, ts2, rp2, tp2;
    thin_slab(rs, tau, rs2, ts2);
    thin_slab(rp, tau, rp2, tp2);
    const float r = 0.5f * (rs2 + rp2), t = 0.5f * (ts2 + tp2);
    if (u < r) {
      dir = reflect(dir, facing);
      return true;
    }
    return u < r + t;  // passes straight on: both refractions cancel in a parallel pane
  }
  const float r = 0.5f * (rs + rp);
  if (u < r) {
    dir = reflect(dir, facing);
    return true;
  }
  // Refraction (Snell), then the body's internal transmittance decides survival on entry.
  dir = glm::normalize(eta * dir + (eta * cos_i - cos_t) * facing);
  return !entering || rng.uniform() < tau;
}

// Updates `dir` for the photon leaving the surface; returns false when it is absorbed.
// `n` is the unit normal of the triangle's front (counter-clockwise) side. Every material kind
// (the Embree backend's general kernel; embree/path_kernel.hpp leaves out unused kinds).
inline bool scatter(const Material& m, const vec3& n, vec3& dir, PathRng& rng) {
  const float cos_in = glm::dot(dir, n);
  const vec3 facing = cos_in < 0.0f ? n : -n;  // the side the photon arrived from
  switch (m.type) {
    case Material::Type::Diffuse:
      return scatter_diffuse(m, facing, dir, rng);
    case Material::Type::Mirror:
      return scatter_mirror(m, facing, dir, rng);
    case Material::Type::Glossy:
      return scatter_glossy(m, facing, dir, rng);
    case Material::Type::Glass:
      break;
  }
  return scatter_glass(m, cos_in, facing, dir, rng);
}

}  // namespace lightsolver::detail
