// Sky emission (types/luminaire_sky.cpp, daylight/sky_sampler.hpp): the same method as the CPU's
// SkyEmitter, in float, from the sky's record in photo_floats[] at LuminaireGpu::photometric
// (packed by vulkan/gpu_scene.cpp, pack_sky): a portal chosen by flux, a cell of its direction
// table by the 53-bit thresholds in photo_cdf53[], a point uniform in solid angle inside the
// cell accepted with probability w / majorant (w = the sky's luminance, times the cosine to the
// portal). Accepted directions have density w / ∫w exactly, as on the CPU; the draws differ.
#ifndef LIGHTSOLVER_SKY_GLSL
#define LIGHTSOLVER_SKY_GLSL

#include "shared/glazing.h"

// Header floats (uints stored as their bits): 0..6 a b m c d e k, 7 scale (cd/m² per raw unit),
// 8..10 the sun, 11 ground luminance, 12 portals (0: the disc), 13 bands, 14 sectors,
// 15 the portals' thresholds in photo_cdf53[], 16..18 the site's centre (local), 19 its radius,
// 20 the floor of cos Z where b > 0, 21..24 the region (a sky patch: altitude0, its span, azimuth0,
// its span, radians), 25 1 for a region (0: the whole sphere). Then per portal (or the disc) 20 floats: 0..2 corner (local),
// 3..5 edge1, 6..8 edge2, 9..11 the outward normal (toward the sky; 0 for the disc),
// 12 majorants in photo_floats[], 13 thresholds in photo_cdf53[], 14 cells, 15 the last cell
// with light, 16 the glazing's scale τv / T(0), 17 its panes (0: none; shared/glazing.h).
const uint kSkyHeader = 28u;
const uint kSkyPortal = 20u;
const int kSkyMaxTries = 1000;  // acceptance is ~1/2 or better: only stops a broken table

float sky_f(uint at) { return photo_floats[at]; }
uint sky_u(uint at) { return floatBitsToUint(photo_floats[at]); }
vec3 sky_v(uint at) { return vec3(photo_floats[at], photo_floats[at + 1u], photo_floats[at + 2u]); }

// daylight::Sky::luminance: the general sky form above the horizon, the ground below.
float sky_luminance(uint base, vec3 w) {
  if (!(w.z > 0.0)) return sky_f(base + 11u);
  const float a = sky_f(base), b = sky_f(base + 1u), m = sky_f(base + 2u);
  const float c = sky_f(base + 3u), d = sky_f(base + 4u), e = sky_f(base + 5u);
  float phi = 1.0 + m * w.z;
  if (a != 0.0) phi += a * exp(b / (b > 0.0 ? max(w.z, sky_f(base + 20u)) : w.z));
  float f = 1.0;
  if (c != 0.0 || e != 0.0) {
    const vec3 sun = sky_v(base + 8u);
    const float cchi = clamp(dot(w, sun), -1.0, 1.0);
    const float chi = atan(length(cross(w, sun)), cchi);  // acos is imprecise near the sun
    f += c * (exp(d * chi) - sky_f(base + 6u)) + e * cchi * cchi;
  }
  return sky_f(base + 7u) * max(0.0, phi * f);
}

// sin of band edge k (SkyDirections: the middle edge exactly 0, the ends -1 and 1; a region's
// bands cut its altitudes evenly).
float sky_band_u(uint base, uint k, uint bands) {
  if (sky_u(base + 25u) != 0u) {
    const float a = sky_f(base + 21u) + sky_f(base + 22u) * float(k) / float(bands);
    return abs(a) < 1e-7 ? 0.0 : clamp(sin(a), -1.0, 1.0);
  }
  if (k == 0u) return -1.0;
  if (k == bands) return 1.0;
  if (2u * k == bands) return 0.0;
  return sin(-0.5 * kPi + kPi * float(k) / float(bands));
}

// upper_bound over n thresholds from `off`: the first with rng_u53() < threshold.
uint sky_pick(uint off, uint n, uint last) {
  const uint64_t k = rng_u53();
  uint lo = 0u, hi = n;
  while (lo < hi) {
    const uint mid = (lo + hi) / 2u;
    if (k < photo_cdf53[off + mid]) hi = mid; else lo = mid + 1u;
  }
  return lo < n ? lo : last;
}

// The push off the opening of the photon just emitted (trace.comp's blocked_outside; zero: none).
vec3 g_opening_push;

// The last proposal tried: a private global, not a loop-carried local (g_spot_sample, emit.glsl).
vec3 g_sky_dir;

vec3 sky_direction(uint base, uint p) {
  const uint bands = sky_u(base + 13u), sectors = sky_u(base + 14u);
  const vec3 out_n = sky_v(p + 9u);
  const bool portal = dot(out_n, out_n) > 0.0;
  const uint bound_off = sky_u(p + 12u);
  g_sky_dir = vec3(0.0, 0.0, 1.0);
  bool accepted = false;
  for (int attempt = 0; attempt < kSkyMaxTries && !accepted; ++attempt) {
    const uint cell = sky_pick(sky_u(p + 13u), sky_u(p + 14u), sky_u(p + 15u));
    const uint band = cell / sectors, sector = cell % sectors;
    const float u0 = sky_band_u(base, band, bands), u1 = sky_band_u(base, band + 1u, bands);
    const float u = u0 + rng_uniform() * (u1 - u0);
    const bool region = sky_u(base + 25u) != 0u;
    const float span = region ? sky_f(base + 24u) : 2.0 * kPi;
    const float az = (region ? sky_f(base + 23u) : 0.0) +
                     (float(sector) + rng_uniform()) * (span / float(sectors));
    const float s = sqrt(max(0.0, 1.0 - u * u));
    const vec3 w = vec3(s * cos(az), s * sin(az), u);
    float weight = sky_luminance(base, w);
    if (portal) {
      const float cos_out = max(0.0, dot(w, out_n));
      weight *= cos_out * glazing_transmittance(cos_out, sky_f(p + 16u), sky_u(p + 17u));
    }
    g_sky_dir = w;
    if (rng_uniform() * photo_floats[bound_off + cell] < weight) accepted = true;
  }
  return g_sky_dir;
}

LS_EMISSION(emit_sky) {
  const uint base = l.photometric;
  const uint portals = sky_u(base + 12u);
  uint k = 0u;
  if (portals > 1u) k = sky_pick(sky_u(base + 15u), portals, portals - 1u);
  const uint p = base + kSkyHeader + k * kSkyPortal;
  const vec3 toward = sky_direction(base, p);
  dir = -toward;
  const float s = rng_uniform(), t = rng_uniform();
  if (portals > 0u) {
    const vec3 at = sky_v(p) + s * sky_v(p + 3u) + t * sky_v(p + 6u);
    g_opening_push = -sky_v(p + 9u);
    origin = offset_ray_origin(at, g_opening_push);
    return;
  }
  // The disc of the site's radius across `toward`, that radius beyond the centre.
  const float radius = sky_f(base + 19u);
  const vec3 helper = abs(toward.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
  const vec3 e1 = normalize(cross(helper, toward));
  const vec3 e2 = cross(toward, e1);
  const float r = radius * sqrt(s), phi = 2.0 * kPi * t;
  origin = sky_v(base + 16u) + radius * toward + r * (cos(phi) * e1 + sin(phi) * e2);
}

#endif
