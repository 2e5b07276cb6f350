// Photometric emission, mirroring lightsolver::PhotometricSampler (photometry/sampler.cpp) draw
// for draw: sample_origin (two 53-bit draws), then the cell (one draw), then rejection inside
// the cell (three draws per try). The cell pick is exact: photo_cdf53 holds, for each cell, the
// smallest 53-bit draw k for which the CPU's double product k 2^-53 * total reaches the cell's
// cumulative flux. Rejection and angles run in float (the CPU uses double): a decision flips
// only when a draw falls within float rounding (~1e-7 relative) of the threshold.
#ifndef LIGHTSOLVER_PHOTOMETRIC_GLSL
#define LIGHTSOLVER_PHOTOMETRIC_GLSL

const int kPhotoMaxTries = 1000;  // as the CPU sampler: only stops hostile tables from looping
const float kDegToRad = 0.017453292519943295;

// uniform_double() rounded to float: k * 2^-53 (the scale is exact).
float photo_uniform() { return float(rng_u53()) * 1.1102230246251565e-16; }

// lightsolver::to_world: the luminaire frame (gamma = 0 along -z, C0 along +x) to the world.
vec3 photo_to_world(vec3 local, vec3 aim, vec3 c0) {
  return local.x * c0 + local.y * cross(c0, aim) - local.z * aim;
}

vec3 photometric_origin(PhotoGpu p) {
  const float a = photo_uniform(), b = photo_uniform();
  if (p.round_opening != 0u) {  // uniform over the ellipse with axes length x width
    const float r = sqrt(a), phi = 2.0 * kPi * b;
    return vec3(0.5 * p.open_length * r * cos(phi), 0.5 * p.open_width * r * sin(phi), 0.0);
  }
  return vec3((a - 0.5) * p.open_length, (b - 0.5) * p.open_width, 0.0);
}

// std::upper_bound over the cell CDF, on integers.
uint photometric_cell(PhotoGpu p) {
  const uint64_t k = rng_u53();
  uint lo = 0u, hi = p.cell_count;
  while (lo < hi) {
    const uint mid = (lo + hi) / 2u;
    if (k < photo_cdf53[p.cell_off + mid]) hi = mid; else lo = mid + 1u;
  }
  return lo < p.cell_count ? lo : p.last_cell;
}

// The last proposal (s, u) tried. A private global, not a loop-carried local: see g_spot_sample
// in emit.glsl (lavapipe overwrote such locals for lanes that had left a divergent loop).
vec2 g_photo_su;

vec3 photometric_direction(PhotoGpu p) {
  const uint cell = photometric_cell(p);
  const uint nt = p.nt, i = cell / (nt - 1u), j = cell % (nt - 1u);
  const float p0 = photo_floats[p.plane_off + i], p1 = photo_floats[p.plane_off + i + 1u];
  const float t0 = photo_floats[p.polar_off + j], t1 = photo_floats[p.polar_off + j + 1u];
  const uint c = p.candela_off + i * nt + j;
  const float i00 = photo_floats[c], i01 = photo_floats[c + 1u];
  const float i10 = photo_floats[c + nt], i11 = photo_floats[c + nt + 1u];
  const float bound = photo_floats[p.bound_off + cell];
  g_photo_su = vec2(0.5);
  bool accepted = false;
  for (int attempt = 0; attempt < kPhotoMaxTries && !accepted; ++attempt) {
    const float s = photo_uniform();
    const float u = photo_uniform();
    g_photo_su = vec2(s, u);
    const float intensity =
        (1.0 - s) * (1.0 - u) * i00 + s * (1.0 - u) * i10 + (1.0 - s) * u * i01 + s * u * i11;
    const float weight = intensity * sin((t0 + u * (t1 - t0)) * kDegToRad);
    if (photo_uniform() * bound < weight) accepted = true;
  }
  const float a = (p0 + g_photo_su.x * (p1 - p0)) * kDegToRad;
  const float t = (t0 + g_photo_su.y * (t1 - t0)) * kDegToRad;
  return cos(t) * p.pole + sin(t) * (cos(a) * p.zero + sin(a) * p.ninety);
}

// types/luminaire_photometric.cpp emit_photometric: origin on the opening pushed off its plane,
// then direction.
LS_EMISSION(emit_photometric) {
  const PhotoGpu p = photometrics[l.photometric];
  const vec3 o = photo_to_world(photometric_origin(p), l.axis, p.c0);
  const vec3 d = photo_to_world(photometric_direction(p), l.axis, p.c0);
  origin = offset_ray_origin(l.position + o, l.axis);
  dir = normalize(d);
}

#endif
