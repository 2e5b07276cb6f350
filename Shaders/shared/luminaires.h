// The luminaire types as the GPU sees them, one text for the shaders (trace_layout.glsl,
// emit.glsl) and the C++ (vulkan/gpu_layout.hpp, vulkan/gpu_scene.cpp, types/luminaire_rows.hpp):
// the packed record every luminaire becomes, the list of types, and each type's emission where
// both backends run the same text. Written in the subset of prelude.h.
//
// A type whose emission reads only the record's fields is one entry of LS_LUMINAIRE_TYPES and
// one LS_EMISSION function here; everything else of the GPU (its specialisation constant, its
// branch of emit(), its code check, its row in the host's tables) is generated from the entry
// (docs/solver.md, "Adding a luminaire type").
#ifndef LIGHTSOLVER_SHARED_LUMINAIRES_H
#define LIGHTSOLVER_SHARED_LUMINAIRES_H

#include "sampling.h"

// One entry per luminaire type: X(name, code, switch, emission).
// - name: its Luminaire::Type enumerator (C++ asserts code == the enumerator's value);
// - code: LuminaireGpu::type, 0, 1, 2, ... in order; its specialisation constant's id is
//   LS_SPEC_FIRST_LUMINAIRE + code (trace_bindings.h);
// - switch: the GLSL name of that constant (on when the scene has the type's emission effect);
// - emission: the GLSL function emit() calls, of the LS_EMISSION signature. Here for the types
//   both backends emit alike; the spot's (emit.glsl), the photometric's (photometric.glsl),
//   the sky's (sky.glsl) and the sun's portal choice (emit.glsl) differ from the CPU's on purpose (docs/solver.md, "Physics written
//   once").
// Function-like macros are the one form of code generation glslc's preprocessor and C++'s share.
#define LS_LUMINAIRE_TYPES(X)                          \
  X(Point, 0, HAS_POINT, emit_point)                   \
  X(Spot, 1, HAS_SPOT, emit_spot)                      \
  X(Area, 2, HAS_AREA, emit_area)                      \
  X(Directional, 3, HAS_DIRECTIONAL, emit_directional) \
  X(Photometric, 4, HAS_PHOTOMETRIC, emit_photometric) \
  X(Sun, 5, HAS_SUN, emit_sun_gpu)                     \
  X(Sky, 6, HAS_SKY, emit_sky)

#ifdef __cplusplus
namespace lightsolver::shared {
#endif

// A luminaire as trace.comp reads it (std430: each vec3 is followed by a 4-byte field, so C++'s
// glm::vec3 lands on the same offsets; vulkan/gpu_layout.hpp asserts them). The fields carry
// PreparedLuminaire's names, so an emission below reads either the same way; packing copies
// them whatever the type (vulkan/gpu_scene.cpp).
struct LuminaireGpu {
  vec3 position;
  uint type;  // its code in LS_LUMINAIRE_TYPES
  vec3 axis;
  float half_beam_rad;
  vec3 corner;
  float half_field_rad;
  vec3 edge1;
  float cos_half_field;
  vec3 edge2;
  uint photometric;  // photometric: index into photometrics[]; sky: its record in photo_floats[]
};

// Every emission has this signature: from luminaire l, a photon's origin and direction, drawn
// from the path's stream. In C++ it takes any luminaire with the record's fields (the CPU's
// PreparedLuminaire); in GLSL the record.
#ifdef __cplusplus
#define LS_EMISSION(name) \
  template <class Lum>    \
  inline void name(const Lum& l, vec3& origin, vec3& dir, PathRng& rng)
#else
#define LS_EMISSION(name) void name(LuminaireGpu l, out vec3 origin, out vec3 dir)
#endif

// Isotropic from a point.
LS_EMISSION(emit_point) {
  origin = l.position;
  dir = sample_sphere(LS_RNG_ONLY_ARG);
}

// A daylight opening's way out (docs/daylight.md, "Portals and outside obstructions"): a photon
// that started at `start`, pushed off its opening's plane along `push` (into the room), is kept
// only if the ray from the opening against its direction escapes the scene. That ray starts as
// far outside the plane as the photon inside it (offset_ray_origin undone, then done outward),
// so neither meets the wall the opening is cut in, nor a surface lying in the opening's plane.
LS_FN vec3 opening_escape_origin(vec3 start, vec3 push) {
  return offset_ray_origin(offset_ray_origin(start, -push), -push);
}

// Lambertian from a parallelogram (axis: edge1 x edge2, normalised), pushed off the opening's
// plane so that an emitter flush with a ceiling is not blocked by the ceiling itself.
LS_EMISSION(emit_area) {
  origin = offset_ray_origin(point_on_parallelogram(l.corner, l.edge1, l.edge2 LS_RNG_ARG), l.axis);
  dir = sample_cosine(l.axis LS_RNG_ARG);
}

// A parallel beam (sunlight) along the axis through a parallelogram opening.
LS_EMISSION(emit_directional) {
  origin = offset_ray_origin(point_on_parallelogram(l.corner, l.edge1, l.edge2 LS_RNG_ARG), l.axis);
  dir = l.axis;
}

// The sun: the directional beam through its opening, its directions spread over the solar disc
// (uniform radiance over the cap of angular radius α about the axis d), as many photons per
// direction as the opening's area across it, |n·ω|. That density is uniform in the disc's
// projection onto the opening's plane (projected solid angle), an ellipse: centre cos α sin θ u,
// semi-axes sin α cos θ along u and sin α along w = n × u (cos θ = n·d, n turned toward d).
// Drawn there, then lifted back onto the sphere: exact, no rejection loop. The record
// (types/luminaire_sun.cpp): axis d, position u, half_beam_rad sin α, half_field_rad n·d (its
// sign says which way n = edge1 × edge2 turns), cos_half_field 1 − sin θ cos α. Its flux
// E·A·|n·d| is then exact: the cap projects to π sin²α cos θ, to π sin²α across the beam.
LS_FN vec3 sun_cross(vec3 a, vec3 b) {
  return vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

// The disc straddling the opening's plane (|n·d| < sin α; docs/daylight.md, "The sun as a
// luminaire"): only its part in front (n·ω > 0, n = edge1 × edge2 into the room) passes, again
// uniform in projected solid angle. In the opening's elevation e (sin e = n·ω) and azimuth ψ from
// u, that measure is sin e cos e de dψ = q dq dψ (q = sin e): q is drawn ∝ q on [0, sin(e_c + α)]
// (e_c the centre's elevation, sin e_c = n·d) and ψ uniform in [−ψ_h, ψ_h], the cap's widest
// azimuth at e ≥ 0, and a point outside the cap is drawn again. The bounding box holds at least
// half of it (acceptance ≥ 0.53 over the whole straddling range), so 64 tries fail with
// probability < 10⁻¹⁷. The test 1 − ω·d ≤ 1 − cos α is written in small quantities (haversines,
// sin(e − e_c)), free of float cancellation. The record: half_field_rad n·d (n = +edge1 × edge2),
// cos_half_field −sin(e_c + α) (negative: this mode), from the host in double.
LS_FN void emit_sun_straddling(vec3 u, vec3 n, float t, float q_hi, float r,
                               LS_OUT(vec3) dir LS_RNG_PARAM) {
  const float cos_c = sqrt(1.0f - t * t), cos_a = sqrt(1.0f - r * r);
  const float one_minus_cos_a = r * r / (1.0f + cos_a);
  // ψ_h = asin(x) (e_c ≥ 0: the cap's widest azimuth) or 2 asin(x) (e_c < 0: its width at e = 0,
  // cos ψ = cos α / cos e_c), bounded above by x (1 + x²/5) for x < 0.01, with a 10⁻⁴ margin.
  float psi_h;
  if (t >= 0.0f) {
    const float x = r / cos_c;
    psi_h = x * (1.0f + 0.2f * x * x);
  } else {
    const float s_minus = r * cos_c - cos_a * t;  // sin(α − e_c), no cancellation (t < 0)
    const float h_plus = q_hi / sqrt(2.0f * (1.0f + sqrt(1.0f - q_hi * q_hi)));
    const float h_minus = s_minus / sqrt(2.0f * (1.0f + sqrt(1.0f - s_minus * s_minus)));
    const float x = sqrt(h_plus * h_minus / cos_c);
    psi_h = 2.0f * x * (1.0f + 0.2f * x * x);
  }
  psi_h *= 1.0001f;
  const vec3 w = sun_cross(n, u);
  dir = q_hi * n + sqrt(1.0f - q_hi * q_hi) * u;  // not reached in practice (see above)
  for (int i = 0; i < 64; ++i) {
    const float q = q_hi * sqrt(LS_UNIFORM());
    const float psi = psi_h * (2.0f * LS_UNIFORM() - 1.0f);
    const float cos_e = sqrt(1.0f - q * q), hs = sin(0.5f * psi);
    const float delta = q * cos_c - t * cos_e;  // sin(e − e_c)
    const float off =
        delta * delta / (1.0f + cos_e * cos_c + q * t) + 2.0f * cos_c * cos_e * hs * hs;
    if (off <= one_minus_cos_a) {
      dir = normalize(cos_e * cos(psi) * u + cos_e * sin(psi) * w + q * n);
      break;
    }
  }
}

LS_EMISSION(emit_sun) {
  origin = offset_ray_origin(point_on_parallelogram(l.corner, l.edge1, l.edge2 LS_RNG_ARG), l.axis);
  if (l.cos_half_field < 0.0f) {
    emit_sun_straddling(l.position, normalize(sun_cross(l.edge1, l.edge2)), l.half_field_rad,
                        -l.cos_half_field, l.half_beam_rad, dir LS_RNG_ARG);
    return;
  }
  const float rho = sqrt(LS_UNIFORM());
  const float phi = 2.0f * kPi * LS_UNIFORM();
  const float x = rho * cos(phi), y = rho * sin(phi);
  const float cos_t = abs(l.half_field_rad), r = l.half_beam_rad;
  const vec3 n = (l.half_field_rad < 0.0f ? -1.0f : 1.0f) * normalize(sun_cross(l.edge1, l.edge2));
  // a: the point's coordinate along u, 1 − a kept apart so that 1 − a² does not cancel.
  const float one_minus_a = l.cos_half_field - r * cos_t * x;
  const float a = 1.0f - one_minus_a, b = r * y;
  const float h = sqrt(max(0.0f, one_minus_a * (1.0f + a) - b * b));
  dir = normalize(a * l.position + b * sun_cross(n, l.position) + h * n);
}

#ifdef __cplusplus
}  // namespace lightsolver::shared
#endif

#endif
