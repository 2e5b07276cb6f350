#pragma once
// Surface interactions. Every branch keeps the photon's power unchanged and decides survival by
// probability (Russian roulette with survival = albedo), so all photons carry equal power and
// tallies stay integer counts; absorption ends the path without bias.
#include <glm/geometric.hpp>

#include "model/sampling.hpp"
#include "lightsolver/scene.hpp"
#include "shared/scatter.h"

namespace lightsolver::detail {

// Fresnel, the thin pane, GGX normals, the glossy specular lobe and glass: one text with the
// shaders (Shaders/shared/scatter.h).
using shared::fresnel_sp;
using shared::reflect_ggx;
using shared::sample_ggx_normal;
using shared::scatter_dielectric;
using shared::thin_slab;

// One function per material kind; `facing` is the normal on the side the photon arrived from.
// Each keeps the photon's power and returns false when it is absorbed.
inline bool scatter_diffuse(const Material& m, const vec3& facing, vec3& dir, PathRng& rng) {
  if (rng.uniform() >= m.reflectance) return false;
  dir = sample_cosine(facing, rng);
  return true;
}

inline bool scatter_mirror(const Material& m, const vec3& facing, vec3& dir, PathRng& rng) {
  if (rng.uniform() >= m.reflectance) return false;
  dir = reflect_dir(dir, facing);
  return true;
}

inline bool scatter_glossy(const Material& m, const vec3& facing, vec3& dir, PathRng& rng) {
  const float u = rng.uniform();
  if (u < m.reflectance) {
    dir = sample_cosine(facing, rng);
    return true;
  }
  if (u >= m.reflectance + m.specular) return false;
  return reflect_ggx(static_cast<float>(m.roughness * m.roughness), facing, dir, rng);
}

// `cos_in`: dot(dir, n) with the front normal n (its sign says whether the photon enters).
inline bool scatter_glass(const Material& m, float cos_in, const vec3& facing, vec3& dir,
                          PathRng& rng) {
  return scatter_dielectric(static_cast<float>(m.ior), static_cast<float>(m.transmittance), m.thin,
                            cos_in, facing, dir, rng);
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
