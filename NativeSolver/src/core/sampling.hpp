#pragma once
// Small geometric and sampling helpers used on every photon bounce (header-only so they inline).
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "lightsolver/rng.hpp"

namespace lightsolver::detail {

using glm::vec3;

// Moves a surface point off its surface along n by a few float ULPs scaled to the coordinate's
// magnitude (Wächter & Binder, Ray Tracing Gems ch. 6). Unlike a fixed epsilon this neither
// misses thin gaps near the origin nor re-hits the surface at large coordinates.
inline vec3 offset_ray_origin(const vec3& p, const vec3& n) {
  constexpr float kOrigin = 1.0f / 32.0f, kFloatScale = 1.0f / 65536.0f, kIntScale = 256.0f;
  vec3 out;
  for (int i = 0; i < 3; ++i) {
    const auto of = static_cast<std::int32_t>(kIntScale * n[i]);
    const auto bits = std::bit_cast<std::int32_t>(p[i]) + (p[i] < 0 ? -of : of);
    out[i] = std::abs(p[i]) < kOrigin ? p[i] + kFloatScale * n[i] : std::bit_cast<float>(bits);
  }
  return out;
}

// Orthonormal basis around a unit vector (Duff et al. 2017, branchless, no singularity).
inline void make_frame(const vec3& n, vec3& t, vec3& b) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float c = n.x * n.y * a;
  t = vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = vec3(c, sign + n.y * n.y * a, -n.y);
}

inline vec3 to_world(const vec3& local, const vec3& n) {
  vec3 t, b;
  make_frame(n, t, b);
  return local.x * t + local.y * b + local.z * n;
}

// Cosine-weighted direction about n (Lambertian emission and reflection).
inline vec3 sample_cosine(const vec3& n, PathRng& rng) {
  const float u1 = rng.uniform(), u2 = rng.uniform();
  const float r = std::sqrt(u1), phi = 2.0f * std::numbers::pi_v<float> * u2;
  const float z = std::sqrt(std::max(0.0f, 1.0f - u1));
  return to_world(vec3(r * std::cos(phi), r * std::sin(phi), z), n);
}

// Uniform direction on the sphere.
inline vec3 sample_sphere(PathRng& rng) {
  const float z = 1.0f - 2.0f * rng.uniform();
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = 2.0f * std::numbers::pi_v<float> * rng.uniform();
  return vec3(r * std::cos(phi), r * std::sin(phi), z);
}

inline vec3 reflect(const vec3& d, const vec3& n) { return d - 2.0f * glm::dot(d, n) * n; }

}  // namespace lightsolver::detail
