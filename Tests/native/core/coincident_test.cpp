// Coincident surfaces (docs/solver.md): a target lying in the plane of another surface gets the
// light arriving at its front, on every backend, and the results say so; other coplanar
// overlaps are reported. Direct light only (black materials), so each target has a closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>

#include "model/prepared_scene.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

using detail::Coincidence;

// n x n quads over corner + s e1 + t e2, front e1 x e2; `flip` picks the other diagonal.
Mesh tessellated_quad(const std::string& name, int material, dvec3 c, dvec3 e1, dvec3 e2, int n,
                      bool flip) {
  Mesh m;
  m.name = name;
  m.material = material;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i)
      m.vertices.push_back(c + (double(i) / n) * e1 + (double(j) / n) * e2);
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const auto a = std::uint32_t(j * (n + 1) + i), b = a + 1, d = a + n + 1, e = d + 1;
      if (flip) {
        m.triangles.push_back({a, b, d});
        m.triangles.push_back({b, e, d});
      } else {
        m.triangles.push_back({a, b, e});
        m.triangles.push_back({a, e, d});
      }
    }
  }
  return m;
}

// The number before " m²" in a warning.
double area_in(const std::string& w) {
  const auto end = w.find(" m²");
  if (end == std::string::npos) return -1.0;
  const auto begin = w.rfind(' ', end - 1) + 1;
  return std::strtod(w.substr(begin, end - begin).c_str(), nullptr);
}

// The single warning mentioning both names; fails the test if there is not exactly one.
std::string warning_naming(const Warnings& ws, const std::string& a, const std::string& b) {
  std::vector<std::string> found;
  for (const auto& w : ws) {
    if (w.find("\"" + a + "\"") != std::string::npos &&
        w.find("\"" + b + "\"") != std::string::npos)
      found.push_back(w);
  }
  EXPECT_EQ(found.size(), 1u) << "warnings naming " << a << " and " << b;
  return found.empty() ? std::string() : found.front();
}

// Total area of the recorded coincidences of `kind` between meshes `a` and `b` (either order).
double coincident_area(const detail::PreparedScene& p, Coincidence::Kind kind, int a, int b) {
  double area = 0.0;
  for (const Coincidence& c : p.coincidences) {
    const bool same = (int(c.a) == a && int(c.b) == b) || (int(c.a) == b && int(c.b) == a);
    if (same && c.kind == kind) area += c.area_m2;
  }
  return area;
}

bool any_warning_naming(const Warnings& ws, const std::string& a, const std::string& b) {
  for (const auto& w : ws) {
    if (w.find("\"" + a + "\"") != std::string::npos &&
        w.find("\"" + b + "\"") != std::string::npos)
      return true;
  }
  return false;
}

void expect_area(const std::string& warning, double exact_m2) {
  EXPECT_NEAR(area_in(warning), exact_m2, 1e-9 * exact_m2) << warning;
}

class Coincident : public ::testing::TestWithParam<std::string> {
 protected:
  Results run(Scene s, std::uint64_t photons) {
    return run_on_backend(GetParam(), std::move(s), photons, 11);
  }
};

const dvec3 kSource(0.3, -0.2, 2.0);
constexpr double kFlux = 5000.0;

// A floor target exactly on a floor sheet, same vertices and triangles: on main the tracers
// split the light between the two arbitrarily.
TEST_P(Coincident, FloorTargetOnSlabSameTriangulation) {
  Scene s;
  const int black = add_material(s, "black", Material::Type::Diffuse, 0.0);
  const dvec3 c(-2, -2, 0), e1(4, 0, 0), e2(0, 4, 0);
  s.meshes.push_back(quad_mesh("slab", black, c, e1, e2));
  s.meshes.push_back(quad_mesh("floor target", black, c, e1, e2));
  s.targets.push_back(surface("floor", 1));
  s.luminaires.push_back(point_light(kSource, kFlux));
  const Results r = run(s, 1'000'000);
  expect_in_ci(r.targets[0].estimate, point_source_patch_lux(kSource, kFlux, c, e1, e2), 0.03,
               "floor target");
  const std::string w = warning_naming(r.warnings, "floor target", "slab");
  EXPECT_NE(w.find("counted on the target"), std::string::npos) << w;
  expect_area(w, 16.0);
}

// A finely tessellated target over part of a slab of another triangulation.
TEST_P(Coincident, PartialTargetOnSlabOtherTriangulation) {
  Scene s;
  const int black = add_material(s, "black", Material::Type::Diffuse, 0.0);
  s.meshes.push_back(tessellated_quad("slab", black, {-2, -2, 0}, {4, 0, 0}, {0, 4, 0}, 3, false));
  const dvec3 c(-1, -0.5, 0), e1(1.5, 0, 0), e2(0, 1.2, 0);
  s.meshes.push_back(tessellated_quad("patch", black, c, e1, e2, 4, true));
  s.targets.push_back(surface("patch", 1));
  s.luminaires.push_back(point_light(kSource, kFlux));
  const Results r = run(s, 1'000'000);
  expect_in_ci(r.targets[0].estimate, point_source_patch_lux(kSource, kFlux, c, e1, e2), 0.05,
               "patch");
  expect_area(warning_naming(r.warnings, "patch", "slab"), 1.8);
}

// A desk (closed box) whose top carries a target; the desk stands on a floor target, bottom
// face on the floor (back to back: the floor keeps what reaches it around the desk).
TEST_P(Coincident, DeskTopTargetAndDeskOnFloorTarget) {
  Scene s;
  const int black = add_material(s, "black", Material::Type::Diffuse, 0.0);
  s.meshes.push_back(solid_box_mesh("desk", black, {0, 0, 0}, {1.6, 0.8, 0.75}));
  const dvec3 c(0.2, 0.1, 0.75), e1(1.2, 0, 0), e2(0, 0.6, 0);
  s.meshes.push_back(quad_mesh("desk top", black, c, e1, e2));
  s.meshes.push_back(quad_mesh("floor", black, {-1, -1, 0}, {4, 0, 0}, {0, 3, 0}));
  s.targets.push_back(surface("desk top", 1));
  s.targets.push_back(surface("floor", 2));
  const dvec3 src(0.8, 0.4, 2.5);
  s.luminaires.push_back(point_light(src, kFlux));
  const Results r = run(s, 1'000'000);
  expect_in_ci(r.targets[0].estimate, point_source_patch_lux(src, kFlux, c, e1, e2), 0.05,
               "desk top");
  expect_area(warning_naming(r.warnings, "desk top", "desk"), 0.72);
  // Standing on the floor target is contact, not a modelling slip: resolved, not warned.
  EXPECT_FALSE(any_warning_naming(r.warnings, "floor", "desk"));
  // The floor sees the source except in the desk's shadow: the source is above the desk top,
  // so the shadow is the top rectangle projected from the source (scale 2.5 / 1.75 about its
  // foot point).
  const double k = 2.5 / (2.5 - 0.75);
  const dvec3 shadow_c(0.8 - 0.8 * k, 0.4 - 0.4 * k, 0), shadow_e1(1.6 * k, 0, 0),
      shadow_e2(0, 0.8 * k, 0);
  const double floor_area = 12.0, shadow_area = 1.6 * k * 0.8 * k;
  const double exact =
      (point_source_patch_lux(src, kFlux, {-1, -1, 0}, {4, 0, 0}, {0, 3, 0}) * floor_area -
       point_source_patch_lux(src, kFlux, shadow_c, shadow_e1, shadow_e2) * shadow_area) /
      floor_area;
  expect_in_ci(r.targets[1].estimate, exact, 0.05, "floor around the desk");
}

// A panel flush with a closed room's ceiling, a ceiling target and a floor target on the room's
// own faces: the panel's light is not blocked, the floor target gets the parallel-plane form.
TEST_P(Coincident, FlushPanelCeilingTargetAndFloorTargetInARoom) {
  Scene s;
  const int black = add_material(s, "black", Material::Type::Diffuse, 0.0);
  s.meshes.push_back(room_mesh("room", black, {0, 0, 0}, {4, 3, 2.5}, 2));
  // Ceiling target, front down like the ceiling: edge1 x edge2 = -z.
  s.meshes.push_back(quad_mesh("ceiling target", black, {0.5, 0.5, 2.5}, {0, 2, 0}, {3, 0, 0}));
  const dvec3 c(1.6, 1.1, 0), e1(0.5, 0, 0), e2(0, 0.5, 0);
  s.meshes.push_back(quad_mesh("floor probe", black, c, e1, e2));
  s.targets.push_back(surface("ceiling", 1));
  s.targets.push_back(surface("probe", 2));
  Luminaire panel;
  panel.name = "panel";
  panel.type = Luminaire::Type::Area;
  panel.corner = {1.5, 1, 2.5};
  panel.edge1 = {0, 1, 0};
  panel.edge2 = {1, 0, 0};  // edge1 x edge2 = -z: emits downward
  panel.flux_lm = 1000.0;
  s.luminaires.push_back(panel);
  const Results r = run(s, 2'000'000);
  EXPECT_EQ(r.targets[0].estimate.hits, 0u) << "nothing reaches a black room's ceiling";
  constexpr int n = 100;  // midpoint rule over the probe: error ~1e-5, far below the interval
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const dvec3 p = c + ((i + 0.5) / n) * e1 + ((j + 0.5) / n) * e2;
      sum += 1000.0 * parallel_rect_factor(1.5 - p.x, 2.5 - p.x, 1 - p.y, 2 - p.y, 2.5);
    }
  }
  expect_in_ci(r.targets[1].estimate, sum / (n * n), 0.05, "floor probe");
  expect_area(warning_naming(r.warnings, "ceiling target", "room"), 6.0);
  expect_area(warning_naming(r.warnings, "floor probe", "room"), 0.25);
}

// A room exported twice, once as the target (finely meshed) and once as the building shell
// (faces not sharing vertices): every photon must end on the target, even from a panel flush
// with the ceiling, here and 4000 km out (georeferenced).
TEST_P(Coincident, RoomExportedTwiceTheTargetCopyGetsAllFlux) {
  for (const dvec3 offset : {dvec3(0.0), dvec3(4.1e6, 6.3e6, 310.0)}) {
    Scene s;
    const int black = add_material(s, "black", Material::Type::Diffuse, 0.0);
    s.meshes.push_back(room_mesh("shell", black, offset, offset + dvec3(4, 3, 2.5), 1));
    s.meshes.push_back(room_mesh("room", black, offset, offset + dvec3(4, 3, 2.5), 3));
    s.targets.push_back(surface("room", 1));
    s.luminaires.push_back(point_light(offset + dvec3(1.3, 2.1, 1.7), 2000.0));
    Luminaire flush;
    flush.name = "flush panel";
    flush.type = Luminaire::Type::Area;
    flush.corner = offset + dvec3(1, 1, 2.5);
    flush.edge1 = {0, 0.6, 0};
    flush.edge2 = {0.6, 0, 0};
    flush.flux_lm = 1000.0;
    s.luminaires.push_back(flush);
    const Results r = run(s, 200'000);
    const TargetResult& t = r.targets[0];
    EXPECT_EQ(t.estimate.hits, r.photons) << "photons lost to the shell, offset " << offset.x;
    EXPECT_NEAR(t.estimate.mean * t.area_m2, 3000.0, 1e-9 * 3000.0);
    const double area = 2 * (4 * 3 + 4 * 2.5 + 3 * 2.5);
    expect_area(warning_naming(r.warnings, "room", "shell"), area);
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, Coincident, ::testing::ValuesIn(backends()));

// --- detection alone (backend-independent) -----------------------------------------------------

detail::PreparedScene prepared(Scene s, const std::vector<std::size_t>& movable = {}) {
  s.luminaires.push_back(point_light({0.5, 0.5, 3.0}, 1000.0));
  if (s.targets.empty()) s.targets.push_back(grid("grid", {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, 1, 1));
  validate(s);
  return detail::prepare(s, movable);
}

TEST(CoincidentDetection, NonTargetMeshesWithDifferentMaterialsAreReported) {
  Scene s;
  const int grey = add_material(s, "grey", Material::Type::Diffuse, 0.5);
  const int red = add_material(s, "red", Material::Type::Diffuse, 0.3);
  s.meshes.push_back(quad_mesh("wall", grey, {0, 0, 0}, {3, 0, 0}, {0, 0, 2.5}));
  s.meshes.push_back(tessellated_quad("paint", red, {2, 0, 1}, {2, 0, 0}, {0, 0, 1}, 3, true));
  const auto p = prepared(s);
  ASSERT_EQ(p.warnings.size(), 1u);
  const std::string& w = p.warnings[0];
  for (const char* part : {"\"wall\"", "\"paint\"", "\"grey\"", "\"red\"", "arbitrary"})
    EXPECT_NE(w.find(part), std::string::npos) << part << " in " << w;
  expect_area(w, 1.0);
  ASSERT_EQ(p.coincidences.size(), 1u);
  EXPECT_EQ(p.coincidences[0].kind, Coincidence::Kind::Materials);
  // Nothing is moved: neither mesh is a target.
  for (int m = 0; m < 2; ++m) {
    for (std::size_t k = 1; k + 1 < p.meshes[m].vertices.size(); k += 3)
      EXPECT_EQ(p.meshes[m].vertices[k], float(0.0 - p.origin.y));
  }
}

// Two closed bodies of different materials touching face to face (a wall standing on a slab, a
// cabinet on the floor): the shared patch lies inside them, nothing is arbitrary, nothing is
// said and nothing moves. The same slab with an open sheet lying on it facing down (its back
// seen from above) is still reported: from above either material may be met.
TEST(CoincidentDetection, ClosedBodiesInContactSayNothingOpenSheetsDo) {
  Scene s;
  const int grey = add_material(s, "grey", Material::Type::Diffuse, 0.5);
  const int red = add_material(s, "red", Material::Type::Diffuse, 0.3);
  s.meshes.push_back(solid_box_mesh("slab", grey, {-2, -2, -0.2}, {2, 2, 0}, 2));
  s.meshes.push_back(solid_box_mesh("wall", red, {-2, -2, 0}, {2, -1.8, 2.5}));
  const auto p = prepared(s);
  EXPECT_TRUE(p.warnings.empty()) << p.warnings[0];
  EXPECT_NEAR(coincident_area(p, Coincidence::Kind::Contact, 0, 1), 4.0 * 0.2, 1e-9);
  for (int m = 0; m < 2; ++m) {  // nothing moved: the same coordinates, in whatever order
    const std::size_t n = 3 * s.meshes[m].vertices.size();  // the prepared array is padded
    ASSERT_GE(p.meshes[m].vertices.size(), n);
    std::vector<float> given, kept(p.meshes[m].vertices.begin(), p.meshes[m].vertices.begin() + n);
    for (const dvec3& v : s.meshes[m].vertices)
      for (int c = 0; c < 3; ++c) given.push_back(float(v[c] - p.origin[c]));
    std::sort(given.begin(), given.end());
    std::sort(kept.begin(), kept.end());
    ASSERT_EQ(kept.size(), given.size()) << s.meshes[m].name;
    // Rounding of the re-centring only; a move is at least 4 ray offsets (>= 6e-5 m).
    for (std::size_t k = 0; k < kept.size(); ++k)
      EXPECT_NEAR(kept[k], given[k], 1e-6) << s.meshes[m].name << " coordinate " << k;
  }
  s.meshes[1] = quad_mesh("sheet", red, {-1, -1, 0}, {0, 2, 0}, {2, 0, 0});  // front -z
  const auto q = prepared(s);
  ASSERT_EQ(q.warnings.size(), 1u);
  EXPECT_NE(q.warnings[0].find("arbitrary"), std::string::npos) << q.warnings[0];
}

TEST(CoincidentDetection, SameMaterialSaysNothing) {
  Scene s;
  const int grey = add_material(s, "grey", Material::Type::Diffuse, 0.5);
  s.meshes.push_back(quad_mesh("wall", grey, {0, 0, 0}, {3, 0, 0}, {0, 0, 2.5}));
  s.meshes.push_back(tessellated_quad("patch", grey, {2, 0, 1}, {2, 0, 0}, {0, 0, 1}, 3, true));
  const auto p = prepared(s);
  EXPECT_TRUE(p.warnings.empty());
  EXPECT_TRUE(p.coincidences.empty());
}

TEST(CoincidentDetection, TargetsFacingTheSameWayAreArbitraryBackToBackAreContact) {
  Scene s;
  const int grey = add_material(s, "grey", Material::Type::Diffuse, 0.5);
  s.meshes.push_back(quad_mesh("a", grey, {0, 0, 0}, {2, 0, 0}, {0, 2, 0}));      // front +z
  s.meshes.push_back(quad_mesh("b", grey, {1, 1, 0}, {2, 0, 0}, {0, 2, 0}));      // front +z
  s.meshes.push_back(quad_mesh("c", grey, {0, 0, 0}, {0, 0.5, 0}, {0.5, 0, 0}));  // front -z
  for (int i = 0; i < 3; ++i) s.targets.push_back(surface(s.meshes[i].name, i));
  const auto p = prepared(s);
  const std::string ab = warning_naming(p.warnings, "a", "b");
  EXPECT_NE(ab.find("arbitrary"), std::string::npos) << ab;
  expect_area(ab, 1.0);
  EXPECT_FALSE(any_warning_naming(p.warnings, "a", "c"));  // back to back: each keeps its front
  EXPECT_NEAR(coincident_area(p, Coincidence::Kind::Contact, 0, 2), 0.25, 1e-12);
  // The smaller of the back-to-back pair steps toward its own front (down), by more than the
  // tracer's ray offset there; "a" and "b" stay where they are.
  // (Near the origin the ray offset is 1/65536 m; the step is 4 of them.)
  const float dz = p.meshes[2].vertices[2] - float(0.0 - p.origin.z);
  EXPECT_LT(dz, -3.0f / 65536.0f);
  EXPECT_GT(dz, -16.0f / 65536.0f);
  for (int m = 0; m < 2; ++m) {
    for (std::size_t k = 2; k + 1 < p.meshes[m].vertices.size(); k += 3)
      EXPECT_EQ(p.meshes[m].vertices[k], float(0.0 - p.origin.z));
  }
}

TEST(CoincidentDetection, OneMillimetreApartIsNotCoincident) {
  Scene s;
  const int grey = add_material(s, "grey", Material::Type::Diffuse, 0.5);
  const int red = add_material(s, "red", Material::Type::Diffuse, 0.3);
  s.meshes.push_back(quad_mesh("slab", grey, {-2, -2, 0}, {4, 0, 0}, {0, 4, 0}));
  s.meshes.push_back(quad_mesh("target", red, {-1, -1, 0.001}, {2, 0, 0}, {0, 2, 0}));
  s.targets.push_back(surface("target", 1));
  const auto p = prepared(s);
  EXPECT_TRUE(p.coincidences.empty());
  EXPECT_TRUE(p.warnings.empty());
  // ...whereas a micrometre is within the tolerance at these coordinates.
  s.meshes[1].vertices = quad_mesh("", 0, {-1, -1, 1e-6}, {2, 0, 0}, {0, 2, 0}).vertices;
  EXPECT_EQ(prepared(s).coincidences.size(), 1u);
}

TEST(CoincidentDetection, SlabBehindATargetStepsBackAndMovableMeshesAreExcluded) {
  Scene s;
  const int grey = add_material(s, "grey", Material::Type::Diffuse, 0.5);
  s.meshes.push_back(solid_box_mesh("slab", grey, {-2, -2, -0.2}, {2, 2, 0}));
  s.meshes.push_back(quad_mesh("target", grey, {-1, -1, 0}, {2, 0, 0}, {0, 2, 0}));
  s.targets.push_back(surface("target", 1));
  const auto p = prepared(s);
  ASSERT_EQ(p.coincidences.size(), 1u);
  EXPECT_EQ(p.coincidences[0].kind, Coincidence::Kind::TargetOnSurface);
  // The slab's top vertices went down by about 4 ray offsets; its bottom and the target did not.
  const float top = float(0.0 - p.origin.z), bottom = float(-0.2 - p.origin.z);
  const double offset = detail::ray_offset_bound_m(std::abs(top) + 0.2);
  int moved = 0;
  for (std::size_t k = 2; k + 1 < p.meshes[0].vertices.size(); k += 3) {
    const float z = p.meshes[0].vertices[k];
    if (z == bottom) continue;
    EXPECT_LT(z, top - 3.0 * offset);
    EXPECT_GT(z, top - 16.0 * offset);
    ++moved;
  }
  EXPECT_GT(moved, 0);
  for (std::size_t k = 2; k + 1 < p.meshes[1].vertices.size(); k += 3)
    EXPECT_EQ(p.meshes[1].vertices[k], top);
  for (std::size_t movable : {0u, 1u}) {
    const auto q = prepared(s, {movable});
    EXPECT_TRUE(q.coincidences.empty()) << "movable mesh " << movable;
  }
}

// A target box in a room's corner: its bottom and its side against the wall are back to back
// with the room, and smaller, so they step into the floor and into the wall; the corner vertex
// moves along both.
TEST(CoincidentDetection, TargetBoxInACornerStepsIntoFloorAndWall) {
  Scene s;
  const int grey = add_material(s, "grey", Material::Type::Diffuse, 0.5);
  s.meshes.push_back(room_mesh("room", grey, {0, 0, 0}, {4, 3, 2.5}));
  s.meshes.push_back(solid_box_mesh("box", grey, {0, 1, 0}, {1, 2, 0.8}));
  s.targets.push_back(surface("box", 1));
  const auto p = prepared(s);
  EXPECT_TRUE(p.warnings.empty());  // contact: resolved, nothing to warn about
  EXPECT_NEAR(coincident_area(p, Coincidence::Kind::Contact, 0, 1), 1.0 + 0.8, 1e-9);
  const auto& box = s.meshes[1].vertices;
  const auto& v = p.meshes[1].vertices;
  for (std::size_t i = 0; i < box.size(); ++i) {
    const glm::vec3 before(box[i] - p.origin), after(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
    EXPECT_EQ(after.x < before.x, box[i].x == 0.0) << i;
    EXPECT_EQ(after.z < before.z, box[i].z == 0.0) << i;
    EXPECT_EQ(after.y, before.y) << i;
    EXPECT_LT(glm::length(after - before), 1e-3f) << i;
  }
  for (std::size_t k = 0; k + 1 < p.meshes[0].vertices.size(); ++k)
    EXPECT_EQ(p.meshes[0].vertices[k], float(s.meshes[0].vertices[k / 3][k % 3] - p.origin[k % 3]));
}

// Far from the scene's centre the tolerance is wide, so a small target tilted by almost the
// 0.01 rad limit still lies on the floor: its plane's offset n·p then differs from the floor's
// by about the tilt times the distance (9 m here). The plane filter in front of the grid must
// keep such pairs (coincident_planes.hpp); the same patch facing down is a contact.
TEST(CoincidentDetection, TiltedTargetsFarFromTheCentreAreFound) {
  Scene s;
  const int grey = add_material(s, "grey", Material::Type::Diffuse, 0.5);
  s.meshes.push_back(quad_mesh("floor", grey, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}));  // front +z
  s.meshes.push_back(quad_mesh("far", grey, {2000, 0, 0}, {1, 0, 0}, {0, 1, 0}));
  const double w = 0.04, tilt = 0.009;  // 0.18 mm out of the floor's plane at its edges
  const dvec3 e1 = w * dvec3(std::cos(tilt), 0, std::sin(tilt)), e2(0, w, 0);
  const dvec3 up(0.5, 0.5, 0), down(0.2, 0.2, 0);  // the patches' centres
  s.meshes.push_back(quad_mesh("up", grey, up - 0.5 * e1 - 0.5 * e2, e1, e2));
  s.meshes.push_back(quad_mesh("down", grey, down - 0.5 * e1 - 0.5 * e2, e2, e1));  // front -z
  s.targets.push_back(surface("up", 2));
  s.targets.push_back(surface("down", 3));
  const auto p = prepared(s);
  EXPECT_NEAR(coincident_area(p, Coincidence::Kind::TargetOnSurface, 2, 0), w * w, 1e-9 * w * w);
  EXPECT_NEAR(coincident_area(p, Coincidence::Kind::Contact, 3, 0), w * w, 1e-9 * w * w);
  EXPECT_EQ(p.coincidences.size(), 2u);
  // A little steeper than the limit: not coplanar.
  const dvec3 f1 = w * dvec3(std::cos(0.0105), 0, std::sin(0.0105));
  s.meshes[2] = quad_mesh("up", grey, up - 0.5 * f1 - 0.5 * e2, f1, e2);
  EXPECT_EQ(prepared(s).coincidences.size(), 1u);
}

// About a million triangles, mostly a finely tessellated floor under a target and a rug of
// another material: detection must stay about linear (a quadratic one would take hours).
TEST(CoincidentDetection, MillionTriangleFloorStaysFast) {
  Scene s;
  const int grey = add_material(s, "grey", Material::Type::Diffuse, 0.5);
  const int red = add_material(s, "red", Material::Type::Diffuse, 0.3);
  s.meshes.push_back(
      tessellated_quad("floor", grey, {0, 0, 0}, {40, 0, 0}, {0, 30, 0}, 700, false));
  s.meshes.push_back(tessellated_quad("target", grey, {3, 2, 0}, {7, 0, 0}, {0, 5, 0}, 3, true));
  s.meshes.push_back(quad_mesh("rug", red, {20.01, 10.02, 0}, {3, 0, 0}, {0, 2, 0}));
  s.targets.push_back(surface("target", 1));
  s.luminaires.push_back(point_light({20, 15, 3}, 1000.0));
  validate(s);
  const auto start = std::chrono::steady_clock::now();
  const auto p = detail::prepare(s);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  expect_area(warning_naming(p.warnings, "target", "floor"), 35.0);
  expect_area(warning_naming(p.warnings, "rug", "floor"), 6.0);
  EXPECT_EQ(p.warnings.size(), 2u);
  EXPECT_LT(seconds, 30.0) << "prepare of " << p.triangle_count << " triangles";
  std::printf("prepare of %zu triangles: %.2f s\n", p.triangle_count, seconds);
}

}  // namespace
}  // namespace lightsolver::test
