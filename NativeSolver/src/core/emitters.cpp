#include "core/emitters.hpp"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/sampling.hpp"
#include "lightsolver/photometry.hpp"

namespace lightsolver {
namespace {

// Relative spot intensity: piecewise linear in angle through (0, 1), (beam/2, 0.5),
// (field/2, 0.1), and 0 beyond field/2.
double spot_profile(double theta, double half_beam, double half_field) {
  if (theta <= half_beam) return 1.0 - 0.5 * theta / half_beam;
  if (theta <= half_field) return 0.5 - 0.4 * (theta - half_beam) / (half_field - half_beam);
  return 0.0;
}

// Exact integral of (a + b*theta) sin(theta) over [t0, t1].
double linear_times_sin(double a, double b, double t0, double t1) {
  auto F = [&](double t) { return -a * std::cos(t) + b * (std::sin(t) - t * std::cos(t)); };
  return F(t1) - F(t0);
}

}  // namespace

double spot_relative_intensity(const Luminaire& l, double angle_rad) {
  return spot_profile(angle_rad, glm::radians(0.5 * l.beam_angle_deg),
                      glm::radians(0.5 * l.field_angle_deg));
}

double spot_peak_intensity_cd(const Luminaire& l) {
  const double hb = glm::radians(0.5 * l.beam_angle_deg);
  const double hf = glm::radians(0.5 * l.field_angle_deg);
  // Solid-angle integral of the profile: 2*pi * sum over both linear pieces.
  const double inner = linear_times_sin(1.0, -0.5 / hb, 0.0, hb);
  const double slope = -0.4 / (hf - hb);
  const double outer = linear_times_sin(0.5 - slope * hb, slope, hb, hf);
  return l.flux_lm / (2.0 * std::numbers::pi * (inner + outer));
}

namespace detail {

std::size_t pick_luminaire(const PreparedScene& s, PathRng& rng) {
  const double u = rng.uniform_double();
  const auto it = std::upper_bound(s.luminaire_cdf.begin(), s.luminaire_cdf.end(), u);
  return std::min<std::size_t>(it - s.luminaire_cdf.begin(), s.luminaire_cdf.size() - 1);
}

namespace {

vec3 point_on_parallelogram(const PreparedLuminaire& l, PathRng& rng) {
  const float s = rng.uniform(), t = rng.uniform();
  return l.corner + s * l.edge1 + t * l.edge2;
}

// Rejection sampling of the spot profile inside the field cone: uniform in solid angle over
// the cone, accepted with probability equal to the relative intensity. Exact, and the
// acceptance rate stays above 0.2 for any valid beam/field pair.
vec3 sample_spot(const PreparedLuminaire& l, PathRng& rng) {
  for (;;) {
    const float cos_t = 1.0f - rng.uniform() * (1.0f - l.cos_half_field);
    const float phi = 2.0f * std::numbers::pi_v<float> * rng.uniform();
    const float theta = std::acos(std::clamp(cos_t, -1.0f, 1.0f));
    const double f = spot_profile(theta, l.half_beam_rad, l.half_field_rad);
    if (rng.uniform() < f) {
      const float sin_t = std::sqrt(std::max(0.0f, 1.0f - cos_t * cos_t));
      return to_world(vec3(sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t), l.axis);
    }
  }
}

// Direction and opening point drawn exactly from the file's distribution (equal power per
// photon), mapped from the luminaire frame (gamma = 0 along -z, C0 along +x) to the world.
// The origin is pushed off the opening's plane so a recessed or flush luminaire is not
// blocked by the ceiling it sits in.
EmittedRay emit_photometric(const PreparedLuminaire& l, PathRng& rng) {
  const PhotometricSampler& sampler = *l.source->sampler;
  const glm::dvec3 aim(l.axis), c0(l.c0);
  const glm::dvec3 o = lightsolver::to_world(sampler.sample_origin(rng), aim, c0);
  const glm::dvec3 d = lightsolver::to_world(sampler.sample_direction(rng), aim, c0);
  return {offset_ray_origin(l.position + vec3(o), l.axis), glm::normalize(vec3(d))};
}

}  // namespace

EmittedRay emit(const PreparedLuminaire& l, PathRng& rng) {
  switch (l.type) {
    case Luminaire::Type::Point:
      return {l.position, sample_sphere(rng)};
    case Luminaire::Type::Spot:
      return {l.position, sample_spot(l, rng)};
    case Luminaire::Type::Area: {
      // Offset so an emitter flush with a ceiling is not blocked by the ceiling itself.
      const vec3 p = offset_ray_origin(point_on_parallelogram(l, rng), l.axis);
      return {p, sample_cosine(l.axis, rng)};
    }
    case Luminaire::Type::Directional: {
      const vec3 p = offset_ray_origin(point_on_parallelogram(l, rng), l.axis);
      return {p, l.axis};
    }
    case Luminaire::Type::Photometric:
      return emit_photometric(l, rng);
  }
  return {l.position, sample_sphere(rng)};  // unreachable: every type is handled above
}

}  // namespace detail
}  // namespace lightsolver
