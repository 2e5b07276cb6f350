#pragma once
// Rooms with holes, skies and the interval print-out shared by the sky's traced tests
// (sky_luminaire_test.cpp, sky_glazing_test.cpp).
#include <cstdio>
#include <string>

#include "scene_builders.hpp"

namespace lightsolver::test {

// One face corner + s e1 + t e2 (front e1 x e2) without the hole [s0, s1] x [t0, t1] (fractions).
inline void add_face_with_hole(Mesh& m, dvec3 c, dvec3 e1, dvec3 e2, double s0, double s1,
                               double t0, double t1) {
  auto quad = [&](double a0, double a1, double b0, double b1) {
    if (a1 <= a0 || b1 <= b0) return;
    const auto base = static_cast<std::uint32_t>(m.vertices.size());
    const dvec3 p = c + a0 * e1 + b0 * e2, a = (a1 - a0) * e1, b = (b1 - b0) * e2;
    m.vertices.insert(m.vertices.end(), {p, p + a, p + a + b, p + b});
    m.triangles.push_back({base, base + 1, base + 2});
    m.triangles.push_back({base, base + 2, base + 3});
  };
  quad(0, 1, 0, t0);
  quad(0, 1, t1, 1);
  quad(0, s0, t0, t1);
  quad(s1, 1, t0, t1);
}

struct Hole {
  double s0, s1, t0, t1;
};

// A room [lo, hi] facing in (as room_mesh), with a hole in the ceiling or in the wall y = lo.
inline Mesh room_with_hole(int material, dvec3 lo, dvec3 hi, bool in_ceiling, Hole h) {
  Mesh m;
  m.name = "room";
  m.material = material;
  const dvec3 d = hi - lo, X(d.x, 0, 0), Y(0, d.y, 0), Z(0, 0, d.z);
  const Hole none{0, 0, 0, 0};
  const Hole ceil = in_ceiling ? h : none, wall = in_ceiling ? none : h;
  add_face_with_hole(m, lo, X, Y, 0, 0, 0, 0);
  add_face_with_hole(m, lo + Z, Y, X, ceil.s0, ceil.s1, ceil.t0, ceil.t1);
  add_face_with_hole(m, lo, Z, X, wall.s0, wall.s1, wall.t0, wall.t1);
  add_face_with_hole(m, lo + Y, X, Z, 0, 0, 0, 0);
  add_face_with_hole(m, lo, Y, Z, 0, 0, 0, 0);
  add_face_with_hole(m, lo + X, Z, Y, 0, 0, 0, 0);
  return m;
}

inline Luminaire sky(const std::string& model, double zenith_luminance, double ground = 0.0) {
  Luminaire l;
  l.name = "sky";
  l.type = Luminaire::Type::Sky;
  l.sky.model = model;
  l.sky.zenith_luminance_cd_m2 = zenith_luminance;
  l.sky.ground_reflectance = ground;
  return l;
}

// The interval and the exact value, for the record (docs/daylight.md quotes them).
inline void report(const Estimate& e, double exact, const std::string& what) {
  std::printf("[ sky      ] %s: %.6g in [%.6g, %.6g] (half-width %.2f %%), exact %.6g\n",
              what.c_str(), e.mean, e.ci_low, e.ci_high, 50.0 * (e.ci_high - e.ci_low) / exact,
              exact);
}

}  // namespace lightsolver::test
