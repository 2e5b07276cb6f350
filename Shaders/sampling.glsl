// Mirrors NativeSolver/src/core/sampling.hpp operation by operation (same float formulas, same
// order of random draws). Transcendentals may differ in the last bits from the C++ library.
#ifndef LIGHTSOLVER_SAMPLING_GLSL
#define LIGHTSOLVER_SAMPLING_GLSL

const float kPi = 3.14159265358979;

// Wächter & Binder, Ray Tracing Gems ch. 6: offset by integer ULPs scaled to the coordinate.
vec3 offset_ray_origin(vec3 p, vec3 n) {
  const float kOrigin = 1.0 / 32.0, kFloatScale = 1.0 / 65536.0, kIntScale = 256.0;
  vec3 result;
  for (int i = 0; i < 3; ++i) {
    const int of = int(kIntScale * n[i]);  // truncates toward zero, like static_cast
    const int bits = floatBitsToInt(p[i]) + (p[i] < 0.0 ? -of : of);
    result[i] = abs(p[i]) < kOrigin ? p[i] + kFloatScale * n[i] : intBitsToFloat(bits);
  }
  return result;
}

// std::copysign(1.0f, x): keeps the sign of -0.0, unlike sign().
float copysign_one(float x) {
  return uintBitsToFloat((floatBitsToUint(x) & 0x80000000u) | 0x3f800000u);
}

// Duff et al. 2017 orthonormal basis.
void make_frame(vec3 n, out vec3 t, out vec3 b) {
  const float s = copysign_one(n.z);
  const float a = -1.0 / (s + n.z);
  const float c = n.x * n.y * a;
  t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
  b = vec3(c, s + n.y * n.y * a, -n.y);
}

vec3 to_world(vec3 v, vec3 n) {
  vec3 t, b;
  make_frame(n, t, b);
  return v.x * t + v.y * b + v.z * n;
}

vec3 sample_cosine(vec3 n) {
  const float u1 = rng_uniform();
  const float u2 = rng_uniform();
  const float r = sqrt(u1), phi = 2.0 * kPi * u2;
  const float z = sqrt(max(0.0, 1.0 - u1));
  return to_world(vec3(r * cos(phi), r * sin(phi), z), n);
}

vec3 sample_sphere() {
  const float z = 1.0 - 2.0 * rng_uniform();
  const float r = sqrt(max(0.0, 1.0 - z * z));
  const float phi = 2.0 * kPi * rng_uniform();
  return vec3(r * cos(phi), r * sin(phi), z);
}

vec3 reflect_dir(vec3 d, vec3 n) { return d - 2.0 * dot(d, n) * n; }

#endif
