// Photon emission, drawing as the C++ emitters (types/luminaire_types.cpp) draw for draw: the
// luminaire choice, then emit(), one branch per type generated from LS_LUMINAIRE_TYPES. The
// point, area and directional emissions are shared/luminaires.h, which the CPU runs too; the spot
// profile is shared/spot.h (float here, double there). The spot's rejection loop stays here:
// theta comes from atan (acos is imprecise near 1 on some drivers) and the accepted sample lives
// in a private global (lavapipe, below). The photometric emission is photometric.glsl, the
// sky's sky.glsl.
#ifndef LIGHTSOLVER_EMIT_GLSL
#define LIGHTSOLVER_EMIT_GLSL

#include "photometric.glsl"
#include "sky.glsl"
#include "shared/luminaires.h"
#include "shared/spot.h"

// upper_bound over the group's cumulative flux, on integers so the pick equals the CPU's double
// compare. The group's luminaires are luminaires[first .. first + count) (packed group by group).
uint pick_luminaire() {
  const uint64_t u = rng_u53();  // always drawn: keeps the random stream aligned with the CPU
  if (!MANY_LUMINAIRES) return 0u;
  const uint end = pc.luminaire_first + pc.luminaire_count;
  uint lo = pc.luminaire_first, hi = end;
  while (lo < hi) {
    const uint mid = (lo + hi) / 2u;
    if (u < cdf53[mid]) hi = mid; else lo = mid + 1u;
  }
  return min(lo, end - 1u);
}

// The accepted (cos theta, phi). A private global rather than a loop-carried local: lavapipe
// (Mesa 22.3) lets SIMD lanes that already left a divergent loop have their loop-carried locals
// overwritten by later iterations of other lanes; stores to private variables stay masked.
vec2 g_spot_sample;

// Uniform in solid angle over the field cone, accepted with the relative intensity.
vec3 sample_spot(LuminaireGpu l) {
  bool accepted = false;
  while (!accepted) {
    const float cos_t = 1.0 - rng_uniform() * (1.0 - l.cos_half_field);
    const float phi = 2.0 * kPi * rng_uniform();
    // acos() is imprecise near 1 on some drivers; atan2 of the cancellation-free sine is not.
    const float w = 1.0 - clamp(cos_t, -1.0, 1.0);
    const float theta = atan(sqrt(max(0.0, w * (2.0 - w))), 1.0 - w);
    if (rng_uniform() < spot_profile(theta, l.half_beam_rad, l.half_field_rad)) {
      g_spot_sample = vec2(cos_t, phi);
      accepted = true;
    }
  }
  return cone_direction(g_spot_sample.x, g_spot_sample.y, l.axis);
}

// The sun (its entry in LS_LUMINAIRE_TYPES names it): emit_sun through its own opening
// (`photometric` kSunOwnOpening), or through a portal chosen by flux from its record in
// photo_floats (types/luminaire_sun.cpp, pack_sun_record): the portal count, its thresholds'
// offset in photo_cdf53[], then per portal facing the sun corner, edge1, edge2 (local), u,
// n·d and 1 − sin θ cos α (the fields emit_sun reads). The choice draws as the CPU's.
const uint kSunOwnOpening = 0xFFFFFFFFu;
const uint kSunPortal = 14u;
LS_EMISSION(emit_sun_gpu) {
  if (l.photometric != kSunOwnOpening) {
    const uint base = l.photometric, portals = sky_u(base);
    const uint p = base + 2u + kSunPortal * sky_pick(sky_u(base + 1u), portals, portals - 1u);
    l.corner = sky_v(p);
    l.edge1 = sky_v(p + 3u);
    l.edge2 = sky_v(p + 6u);
    l.position = sky_v(p + 9u);
    l.half_field_rad = sky_f(p + 12u);
    l.cos_half_field = sky_f(p + 13u);
  }
  emit_sun(l, origin, dir);
  g_opening_push = l.axis;  // its way out is tested (trace.comp, blocked_outside)
}

// The spot's emission (its entry in LS_LUMINAIRE_TYPES names it): from its position.
LS_EMISSION(emit_spot) {
  origin = l.position;
  dir = sample_spot(l);
}

// One branch per luminaire type, each behind its HAS_* switch (on when the scene has the type:
// vulkan/gpu_scene.cpp), so a scene's pipeline keeps only the emitters it uses. Generated from
// the list: `if (HAS_POINT && l.type == 0) emit_point(l, origin, dir); else ...`.
#define LS_EMIT_BRANCH(name, code, has, emission) \
  if (has && l.type == code) emission(l, origin, dir); else
void emit(LuminaireGpu l, out vec3 origin, out vec3 dir) {
  LS_LUMINAIRE_TYPES(LS_EMIT_BRANCH) {  // no such type: packing rejects it (gpu_luminaire_type)
    origin = l.position;
    dir = l.axis;
  }
}
#undef LS_EMIT_BRANCH

#endif
