#pragma once
// Scenes for the closed-form tests, built in code so each test states its geometry exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "lightsolver/backends.hpp"
#include "lightsolver/error.hpp"
#include "lightsolver/scene.hpp"
#include "lightsolver/scene_io.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver::test {

using glm::dvec3;

inline int add_material(Scene& s, const std::string& name, Material::Type type, double refl) {
  Material m;
  m.name = name;
  m.type = type;
  m.reflectance = refl;
  s.materials.push_back(m);
  return static_cast<int>(s.materials.size() - 1);
}

// Parallelogram corner + s*e1 + t*e2 as two triangles; front = e1 x e2.
inline Mesh quad_mesh(const std::string& name, int material, dvec3 corner, dvec3 e1, dvec3 e2) {
  Mesh m;
  m.name = name;
  m.material = material;
  m.vertices = {corner, corner + e1, corner + e1 + e2, corner + e2};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

// The quadrilateral a, b, c, d (corners in order; front by the right-hand rule), named "quad":
// for corners that need not form a parallelogram.
inline Mesh corner_quad(dvec3 a, dvec3 b, dvec3 c, dvec3 d, int material = 0) {
  Mesh m;
  m.name = "quad";
  m.material = material;
  m.vertices = {a, b, c, d};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

// Axis-aligned box [lo, hi] with faces whose fronts point INTO the box (a room), each face
// split into n x n quads so walls share many edges (a watertightness test).
inline Mesh room_mesh(const std::string& name, int material, dvec3 lo, dvec3 hi, int n = 1) {
  Mesh m;
  m.name = name;
  m.material = material;
  auto face = [&](dvec3 c, dvec3 e1, dvec3 e2) {
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        const auto base = static_cast<std::uint32_t>(m.vertices.size());
        const dvec3 p = c + (double(i) / n) * e1 + (double(j) / n) * e2;
        const dvec3 a = e1 / double(n), b = e2 / double(n);
        m.vertices.insert(m.vertices.end(), {p, p + a, p + a + b, p + b});
        m.triangles.push_back({base, base + 1, base + 2});
        m.triangles.push_back({base, base + 2, base + 3});
      }
    }
  };
  const dvec3 d = hi - lo;
  const dvec3 X(d.x, 0, 0), Y(0, d.y, 0), Z(0, 0, d.z);
  face(lo, X, Y);      // floor, front X x Y = +z
  face(lo + Z, Y, X);  // ceiling, front -z
  face(lo, Z, X);      // y = lo, front Z x X = +y
  face(lo + Y, X, Z);  // y = hi, front -y
  face(lo, Y, Z);      // x = lo, front Y x Z = +x
  face(lo + X, Z, Y);  // x = hi, front -x
  return m;
}

// Closed box [lo, hi] with faces whose fronts point OUT of it (furniture, glass blocks).
inline Mesh solid_box_mesh(const std::string& name, int material, dvec3 lo, dvec3 hi, int n = 1) {
  Mesh m = room_mesh(name, material, lo, hi, n);
  for (auto& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

inline Luminaire spot_light(dvec3 position, dvec3 direction, double beam_deg, double field_deg,
                            double flux_lm) {
  Luminaire l;
  l.name = "spot";
  l.type = Luminaire::Type::Spot;
  l.position = position;
  l.direction = direction;
  l.beam_angle_deg = beam_deg;
  l.field_angle_deg = field_deg;
  l.flux_lm = flux_lm;
  return l;
}

inline Luminaire point_light(dvec3 p, double flux_lm) {
  Luminaire l;
  l.name = "point";
  l.type = Luminaire::Type::Point;
  l.position = p;
  l.flux_lm = flux_lm;
  return l;
}

inline Target grid(const std::string& name, dvec3 corner, dvec3 e1, dvec3 e2, unsigned nu,
                   unsigned nv) {
  Target t;
  t.name = name;
  t.type = Target::Type::Grid;
  t.corner = corner;
  t.edge1 = e1;
  t.edge2 = e2;
  t.nu = nu;
  t.nv = nv;
  return t;
}

inline Target surface(const std::string& name, int mesh) {
  Target t;
  t.name = name;
  t.type = Target::Type::Surface;
  t.mesh = mesh;
  return t;
}

// A grey 6 x 4 x 3 m room, a block (mesh 1, a surface target) shifted by `block_offset`, a spot
// over one side and a workplane grid: the scene for moving-geometry tests on every backend.
inline Scene room_with_block(dvec3 block_offset) {
  Scene s;
  add_material(s, "grey", Material::Type::Diffuse, 0.5);
  add_material(s, "block", Material::Type::Diffuse, 0.3);
  s.meshes.push_back(room_mesh("room", 0, dvec3(0), dvec3(6, 4, 3), 2));
  s.meshes.push_back(
      solid_box_mesh("block", 1, dvec3(1, 1, 0) + block_offset, dvec3(2, 2, 0.8) + block_offset));
  s.luminaires.push_back(spot_light({4.5, 1.5, 2.9}, {0, 0, -1}, 30, 50, 2000));
  s.targets.push_back(surface("block", 1));
  s.targets.push_back(grid("workplane", {0.5, 0.5, 0.85}, {5, 0, 0}, {0, 3, 0}, 5, 3));
  return s;
}

// Two independent estimates of the same quantity agree within 5 combined sigma.
inline void expect_same_within(const Estimate& a, const Estimate& b, const std::string& what) {
  EXPECT_LT(std::abs(a.mean - b.mean), 5.0 * std::hypot(a.sigma, b.sigma) + 1e-12)
      << what << ": " << a.mean << " vs " << b.mean;
}

// Solid angle of triangle abc seen from p (Van Oosterom & Strackee 1983).
// Every cell of the first target of `a` agrees with `b`'s (expect_same_within); returns the two
// runs' cell intervals' summed widths, for the caller's check of which is narrower.
inline std::pair<double, double> expect_cells_agree(const Results& a, const Results& b) {
  double width_a = 0.0, width_b = 0.0;
  for (std::size_t k = 0; k < a.targets[0].cells.size(); ++k) {
    const Estimate &x = a.targets[0].cells[k], &y = b.targets[0].cells[k];
    expect_same_within(x, y, "cell " + std::to_string(k));
    width_a += x.ci_high - x.ci_low;
    width_b += y.ci_high - y.ci_low;
  }
  return {width_a, width_b};
}

inline double triangle_solid_angle(dvec3 p, dvec3 a, dvec3 b, dvec3 c) {
  a -= p;
  b -= p;
  c -= p;
  const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
  const double num = std::abs(glm::dot(a, glm::cross(b, c)));
  const double den = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
  return 2.0 * std::atan2(num, den);
}

// Mean illuminance over parallelogram corner + s*e1 + t*e2 from an isotropic point source:
// E = I * Omega / A, exact for a planar patch facing the source.
inline double point_source_patch_lux(dvec3 src, double flux_lm, dvec3 c, dvec3 e1, dvec3 e2) {
  const double omega = triangle_solid_angle(src, c, c + e1, c + e1 + e2) +
                       triangle_solid_angle(src, c, c + e1 + e2, c + e2);
  return flux_lm / (4.0 * std::numbers::pi) * omega / glm::length(glm::cross(e1, e2));
}

// Configuration factor from a point to a parallel a x b rectangle whose corner lies on the
// point's normal at distance c (lighting-facts.md).
inline double corner_factor_parallel(double a, double b, double c) {
  const double X = a / c, Y = b / c;
  const double sx = std::sqrt(1 + X * X), sy = std::sqrt(1 + Y * Y);
  return (X / sx * std::atan(Y / sx) + Y / sy * std::atan(X / sy)) / (2.0 * std::numbers::pi);
}

// Signed corner rectangle: the rectangle from the foot point (0,0) to (x, y), sign by quadrant.
inline double signed_corner(double x, double y, double c) {
  if (x == 0.0 || y == 0.0) return 0.0;
  const double s = (x > 0) == (y > 0) ? 1.0 : -1.0;
  return s * corner_factor_parallel(std::abs(x), std::abs(y), c);
}

// Factor from a point to the parallel rectangle [x0,x1] x [y0,y1] (coordinates relative to the
// point's foot), by adding and subtracting four corner rectangles.
inline double parallel_rect_factor(double x0, double x1, double y0, double y1, double c) {
  return signed_corner(x1, y1, c) - signed_corner(x0, y1, c) - signed_corner(x1, y0, c) +
         signed_corner(x0, y0, c);
}

// Perpendicular planes, point on the line through a corner: a = edge along the planes'
// intersection, depth = the rectangle's other edge, y = the point's distance to the
// rectangle's plane (lighting-facts.md).
inline double corner_factor_perpendicular(double a, double depth, double y) {
  const double X = depth / a, Y = y / a, r = std::sqrt(X * X + Y * Y);
  return (std::atan(1.0 / Y) - Y / r * std::atan(1.0 / r)) / (2.0 * std::numbers::pi);
}

// Confidence for closed-form checks: a 5-sigma two-sided interval, so a correct solver fails a
// single check with probability 6e-7 (the seeds are fixed anyway) while a wrong one cannot hide.
constexpr double kCheckConfidence = 0.9999994;

// One run of `s` on `backend` with next-event estimation `next_event` ("auto", "on", "off"):
// the next-event suites' common call, and run_on_backend's.
inline Results run_next_event(const std::string& backend, const Scene& s, std::uint64_t photons,
                              std::uint64_t seed, const std::string& next_event,
                              double confidence = kCheckConfidence) {
  SolveOptions o;
  o.backend = backend;
  o.photons = photons;
  o.seed = seed;
  o.confidence = confidence;
  o.next_event = next_event;
  return solve(s, o);
}

// One run of `s` on `backend` at `confidence`: the closed-form suites' common call.
// `backend` may end in "+nee": that backend with next-event estimation on (backends_and_nee()).
inline Results run_on_backend(const std::string& backend, Scene s, std::uint64_t photons,
                              std::uint64_t seed, double confidence = kCheckConfidence) {
  validate(s);
  // A plain backend name traces direct light by photons (the default is next-event estimation
  // where it applies): the "+nee" names run the same checks with it.
  const auto plus = backend.find("+nee");
  if (plus == std::string::npos)
    return run_next_event(backend, s, photons, seed, "off", confidence);
  return run_next_event(backend.substr(0, plus), s, photons, seed, "auto", confidence);
}

// The exact value lies inside the reported interval AND the interval is narrow (half-width
// below max_rel_half_width of the exact value), so a wrong solver cannot pass by being noisy.
inline void expect_in_ci(const Estimate& e, double exact, double max_rel_half_width,
                         const std::string& what) {
  EXPECT_LE(e.ci_low, exact) << what << ": mean " << e.mean << " exact " << exact;
  EXPECT_GE(e.ci_high, exact) << what << ": mean " << e.mean << " exact " << exact;
  EXPECT_LT(0.5 * (e.ci_high - e.ci_low), max_rel_half_width * exact) << what << " CI too wide";
}

// One face of a room: the rectangle corner + s*e1 + t*e2 (front e1 x e2) triangulated around a
// slit of `m` segments of length `eps` along e1 through `slit_mid`, so that 2m triangles are
// slivers (two edges of ~1 m, one of `eps`) fanning out to the corners corner and
// corner + e1 + e2. Only the four corners lie on the rectangle's border, so faces built this way
// meet their neighbours edge to edge (no T-junctions): a closed, watertight room of slivers.
inline void add_slit_face(Mesh& mesh, dvec3 corner, dvec3 e1, dvec3 e2, dvec3 slit_mid, int m,
                          double eps) {
  const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
  const std::uint32_t A = base, B = base + 1, C = base + 2, D = base + 3, P = base + 4;
  mesh.vertices.insert(mesh.vertices.end(), {corner, corner + e1, corner + e1 + e2, corner + e2});
  const dvec3 along = glm::normalize(e1) * eps;
  for (int k = 0; k <= m; ++k) mesh.vertices.push_back(slit_mid + (k - 0.5 * m) * along);
  const auto last = P + static_cast<std::uint32_t>(m);
  mesh.triangles.push_back({A, B, last});  // below the slit (side of A and B)
  for (std::uint32_t k = last; k > P; --k) mesh.triangles.push_back({A, k, k - 1});
  mesh.triangles.push_back({A, P, D});  // left of the slit
  mesh.triangles.push_back({C, D, P});  // above the slit (side of C and D)
  for (std::uint32_t k = P; k < last; ++k) mesh.triangles.push_back({C, k, k + 1});
  mesh.triangles.push_back({B, C, last});  // right of the slit
}

// Longest edge over the altitude onto it: 1 for a well-shaped triangle, huge for a sliver.
inline double aspect_ratio(dvec3 a, dvec3 b, dvec3 c) {
  const double l = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
  return l * l / glm::length(glm::cross(b - a, c - a));
}

// UV sphere of `stacks` x `slices` facets with outward fronts (a solid glass ball).
inline Mesh sphere_mesh(const std::string& name, int material, dvec3 centre, double radius,
                        int stacks, int slices) {
  Mesh m;
  m.name = name;
  m.material = material;
  const double pi = std::numbers::pi;
  for (int i = 0; i <= stacks; ++i) {
    const double theta = pi * i / stacks;
    // The poles exactly, so that their `slices` copies coincide (a watertight cap).
    const double st = i == 0 || i == stacks ? 0.0 : std::sin(theta);
    const double ct = i == 0 ? 1.0 : i == stacks ? -1.0 : std::cos(theta);
    for (int j = 0; j < slices; ++j) {
      const double phi = 2.0 * pi * j / slices;
      m.vertices.push_back(centre + radius * dvec3(st * std::cos(phi), st * std::sin(phi), ct));
    }
  }
  auto v = [&](int i, int j) { return static_cast<std::uint32_t>(i * slices + (j % slices)); };
  for (int i = 0; i < stacks; ++i) {
    for (int j = 0; j < slices; ++j) {
      // Counter-clockwise seen from outside: theta grows downward, phi eastward.
      if (i > 0) m.triangles.push_back({v(i, j), v(i + 1, j), v(i, j + 1)});
      if (i + 1 < stacks) m.triangles.push_back({v(i, j + 1), v(i + 1, j), v(i + 1, j + 1)});
    }
  }
  return m;
}

// The backends every closed-form test runs on: every one the registry lists (auto aside), so a
// backend added to the build is tested without editing this list (backends_test.cpp checks the
// registry itself against the build).
inline constexpr double kFluxPerWall_lm = 1000.0;

// A closed unit cube of reflectance rho whose six walls each carry a flush area luminaire of
// kFluxPerWall_lm emitting into the room: the emitted radiance is the same everywhere inside
// (M0 = Phi / A), so every wall receives M0, and the reflected light is uniform too. Its
// radiosity sums the geometric series M0 (rho + rho^2 + ...) = M0 rho / (1 - rho): the
// illuminance at any interior point, on any plane, from light reflected at least once.
inline Scene glowing_cube(double rho) {
  Scene s;
  add_material(s, "grey", Material::Type::Diffuse, rho);
  s.meshes.push_back(room_mesh("cube", 0, dvec3(0), dvec3(1), 2));
  struct Face {
    dvec3 corner, e1, e2;  // e1 x e2 points into the cube
  };
  const Face faces[] = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}},
                        {{0, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
                        {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}}, {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}}};
  for (const Face& f : faces) {
    Luminaire l;
    l.name = "wall " + std::to_string(s.luminaires.size());
    l.type = Luminaire::Type::Area;
    l.corner = f.corner;
    l.edge1 = f.e1;
    l.edge2 = f.e2;
    l.flux_lm = kFluxPerWall_lm;
    s.luminaires.push_back(l);
  }
  return s;
}

/// A luminaire with a name and a `group` key ("" : its own group).
inline Luminaire named(Luminaire l, const std::string& name, const std::string& group) {
  l.name = name;
  l.group = group;
  return l;
}

/// A grey 6 x 4 x 3 m room with three luminaires in two groups ("left": two spots, "right": a
/// point), a desk (surface target) and a 5 x 3 workplane grid: reflections make per-path counts
/// > 1 (not binomial).
inline Scene grouped_room() {
  Scene s;
  add_material(s, "grey", Material::Type::Diffuse, 0.5);
  s.meshes.push_back(room_mesh("room", 0, dvec3(0), dvec3(6, 4, 3), 2));
  s.meshes.push_back(quad_mesh("desk", 0, {1, 1, 0.75}, {1, 0, 0}, {0, 1, 0}));
  s.luminaires.push_back(
      named(spot_light({1.5, 1.5, 2.9}, {0, 0, -1}, 40, 70, 2000), "l1", "left"));
  s.luminaires.push_back(
      named(spot_light({1.5, 2.5, 2.9}, {0, 0, -1}, 40, 70, 1000), "l2", "left"));
  s.luminaires.push_back(named(point_light({4.5, 2.0, 2.5}, 3000), "r1", "right"));
  s.targets.push_back(surface("desk", 1));
  s.targets.push_back(grid("workplane", {0.5, 0.5, 0.8}, {5, 0, 0}, {0, 3, 0}, 5, 3));
  return s;
}

// The issue-28 box room: 4 x 4 x 3 m, every surface diffuse rho 0.5, an isotropic 100 cd point
// source at (2, 2, 2.9), a cells x cells work-plane grid at 0.8 m; with `table`, a black table
// (top at 0.9 m) whose shadow edges cross cells.
inline Scene box_room(unsigned cells, bool table = false) {
  Scene s;
  add_material(s, "grey", Material::Type::Diffuse, 0.5);
  s.meshes.push_back(room_mesh("room", 0, dvec3(0), dvec3(4, 4, 3)));
  if (table) {
    add_material(s, "black", Material::Type::Diffuse, 0.0);
    s.meshes.push_back(solid_box_mesh("table", 1, {1.3, 1.1, 0.85}, {2.45, 2.2, 0.9}));
  }
  s.luminaires.push_back(point_light({2, 2, 2.9}, 100.0 * 4.0 * std::numbers::pi));
  s.targets.push_back(grid("work plane", {0, 0, 0.8}, {4, 0, 0}, {0, 4, 0}, cells, cells));
  return s;
}

// A sobol run of `photons` on the Embree backend, `replicates` scrambles, next-event estimation
// `next_event` (set explicitly: the tests must not depend on the default).
inline SolveOptions sobol_options(std::uint64_t photons, std::uint64_t seed,
                                  const std::string& next_event = "off",
                                  std::uint32_t replicates = 8) {
  SolveOptions o;
  o.photons = photons;
  o.seed = seed;
  o.backend = "embree";
  o.sampler = "sobol";
  o.replicates = replicates;
  o.next_event = next_event;
  return o;
}

// The message of the InputError `f()` throws, or "no error" (tests of bad input check that
// the message names the file and field).
template <class F>
std::string input_error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

inline std::vector<std::string> backends() {
  std::vector<std::string> names;
  for (const BackendInfo& b : lightsolver::backends()) {
    if (b.name != kAutoBackend) names.push_back(b.name);
  }
  return names;
}

/// The backends that trace shadow rays (next-event estimation needs them): every backend built
/// today (Embree, Vulkan). Not asked by a run here: this list is built in every test process's
/// start (each CTest entry), where a Vulkan start costs seconds on lavapipe;
/// NextEvent.EffectsAndRefine checks that each of them does simulate next_event_direct.
inline std::vector<std::string> shadow_backends() { return backends(); }

/// Every backend, and each that traces shadow rays again as "<name>+nee" (next-event
/// estimation on): closed-form suites run both ways.
inline std::vector<std::string> backends_and_nee() {
  std::vector<std::string> out = backends();
  for (const std::string& b : shadow_backends()) out.push_back(b + "+nee");
  return out;
}

/// A scene file (JSON text): a white floor lit by a point lamp, a surface target on the floor,
/// then `target` (a JSON object) as the second target. For tests of target readers.
inline std::string scene_file_with_target(const std::string& target) {
  return R"({"format": "lightsolver.scene/1",
  "materials": {"white": {"type": "diffuse", "reflectance": 0.7}},
  "meshes": [{"name": "floor", "material": "white",
              "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "triangles": [[0,1,2],[0,2,3]]}],
  "luminaires": [{"name": "lamp", "type": "point", "flux_lm": 1000, "position": [0.5,0.5,2]}],
  "targets": [{"name": "floor", "type": "surface", "mesh": "floor"}, )" +
         target + "]}";
}

/// The InputError message that scene_file_with_target(target) gives, "<no error>" if none.
inline std::string target_error(const std::string& target, const std::string& base_dir) {
  try {
    scene_from_json(scene_file_with_target(target), "scene.json", base_dir);
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no error>";
}

}  // namespace lightsolver::test
