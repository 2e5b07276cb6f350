// Surface interactions, mirroring NativeSolver/src/core/scatter.hpp: the photon keeps its power
// and survives by probability, so tallies stay integer counts.
#ifndef LIGHTSOLVER_SCATTER_GLSL
#define LIGHTSOLVER_SCATTER_GLSL

void fresnel_sp(float cos_i, float eta, out float rs, out float rp, out float cos_t) {
  const float sin2_t = eta * eta * max(0.0, 1.0 - cos_i * cos_i);
  if (sin2_t >= 1.0) {  // total internal reflection
    rs = rp = 1.0;
    cos_t = 0.0;
    return;
  }
  cos_t = sqrt(1.0 - sin2_t);
  const float s = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  const float p = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  rs = s * s;
  rp = p * p;
}

// Incoherent pane of two interfaces with internal transmittance tau.
void thin_slab(float r, float tau, out float reflect_p, out float transmit_p) {
  const float denom = 1.0 - r * r * tau * tau;
  reflect_p = r + (1.0 - r) * (1.0 - r) * tau * tau * r / denom;
  transmit_p = (1.0 - r) * (1.0 - r) * tau / denom;
}

vec3 sample_ggx_normal(float alpha) {
  const float u1 = rng_uniform();
  const float u2 = rng_uniform();
  const float tan2 = alpha * alpha * u1 / max(1e-12, 1.0 - u1);
  const float cos_t = 1.0 / sqrt(1.0 + tan2);
  const float sin_t = sqrt(max(0.0, 1.0 - cos_t * cos_t));
  const float phi = 2.0 * kPi * u2;
  return vec3(sin_t * cos(phi), sin_t * sin(phi), cos_t);
}

bool scatter_glossy(MaterialGpu m, vec3 facing, inout vec3 dir) {
  const uint u = rng_u24();
  if (u < m.p_first) {
    dir = sample_cosine(facing);
    return true;
  }
  if (u >= m.p_second) return false;
  const vec3 micro = m.alpha > 0.0 ? to_world(sample_ggx_normal(m.alpha), facing) : facing;
  if (dot(dir, micro) >= 0.0) return false;  // facet turned away from the photon
  dir = reflect_dir(dir, micro);
  return dot(dir, facing) > 0.0;  // below the surface: absorbed
}

bool scatter_glass(MaterialGpu m, float cos_in, vec3 facing, inout vec3 dir) {
  const float cos_i = abs(cos_in);
  const bool entering = cos_in < 0.0;
  const float eta = (m.thin != 0u || entering) ? 1.0 / m.ior : m.ior;
  float rs, rp, cos_t;
  fresnel_sp(cos_i, eta, rs, rp, cos_t);
  const float u = rng_uniform();
  if (m.thin != 0u) {
    float rs2, ts2, rp2, tp2;
    thin_slab(rs, m.tau, rs2, ts2);
    thin_slab(rp, m.tau, rp2, tp2);
    const float r = 0.5 * (rs2 + rp2), t = 0.5 * (ts2 + tp2);
    if (u < r) {
      dir = reflect_dir(dir, facing);
      return true;
    }
    return u < r + t;  // straight on: both refractions cancel in a parallel pane
  }
  const float r = 0.5 * (rs + rp);
  if (u < r) {
    dir = reflect_dir(dir, facing);
    return true;
  }
  dir = normalize(eta * dir + (eta * cos_i - cos_t) * facing);
  return !entering || rng_uniform() < m.tau;
}

// Updates dir for the photon leaving the surface; false when absorbed. n: unit front normal.
bool scatter(MaterialGpu m, vec3 n, inout vec3 dir) {
  const float cos_in = dot(dir, n);
  const vec3 facing = cos_in < 0.0 ? n : -n;
  if (HAS_DIFFUSE && m.type == kDiffuse) {
    if (rng_u24() >= m.p_first) return false;
    dir = sample_cosine(facing);
    return true;
  }
  if (HAS_MIRROR && m.type == kMirror) {
    if (rng_u24() >= m.p_first) return false;
    dir = reflect_dir(dir, facing);
    return true;
  }
  if (HAS_GLOSSY && m.type == kGlossy) return scatter_glossy(m, facing, dir);
  if (HAS_GLASS && m.type == kGlass) return scatter_glass(m, cos_in, facing, dir);
  return false;
}

#endif
