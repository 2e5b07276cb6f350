// Shadow rays on the Vulkan backend (Shaders/visibility.comp) against the Embree backend's
// rtcOccluded1, ray for ray, and against an exact test in double that also sorts out the rays
// whose answer float rounding could flip (an end within 0.1 mm of a surface, a pass within a
// hair of a triangle's edge): those are left out of the comparison and counted.
#include "vulkan/visibility.hpp"

#include <algorithm>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <random>
#include <stdexcept>
#include <thread>

#include "embree/embree_backend.hpp"
#include "model/backend.hpp"
#include "model/prepared_scene.hpp"
#include "native/core/scene_builders.hpp"
#include "vulkan_test_util.hpp"

namespace lightsolver::test {
namespace {

using detail::ShadowRay;

// What the exact test says of a ray.
enum class Truth { Visible, Blocked, Unsure };

struct Triangle {
  dvec3 a, b, c;
};

// Every triangle of the prepared scene in its coordinates, movable mesh `moved` placed by `m`.
std::vector<Triangle> triangles(const detail::PreparedScene& p, int moved = -1,
                                const glm::mat4& m = glm::mat4(1.0f)) {
  std::vector<Triangle> out;
  for (std::size_t k = 0; k < p.meshes.size(); ++k) {
    const detail::PreparedMesh& mesh = p.meshes[k];
    auto vertex = [&](std::uint32_t i) {
      const glm::vec3 v(mesh.vertices[3 * i], mesh.vertices[3 * i + 1], mesh.vertices[3 * i + 2]);
      return dvec3(int(k) == moved ? glm::vec3(m * glm::vec4(v, 1.0f)) : v);
    };
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      out.push_back(
          {vertex(mesh.indices[t]), vertex(mesh.indices[t + 1]), vertex(mesh.indices[t + 2])});
    }
  }
  return out;
}

// Möller-Trumbore in double. A hit within kEps of 0 or t_max, or within kEdge (barycentric,
// relative) of an edge, is one float rounding could decide either way: Unsure.
Truth exact(const ShadowRay& r, const std::vector<Triangle>& tris) {
  constexpr double kEps = 1e-4, kEdge = 1e-5;
  const dvec3 o(r.origin), d(r.direction);
  bool unsure = false;
  for (const Triangle& t : tris) {
    const dvec3 e1 = t.b - t.a, e2 = t.c - t.a, p = glm::cross(d, e2);
    const double det = glm::dot(e1, p);
    if (std::abs(det) < 1e-12 * glm::length(e1) * glm::length(e2)) continue;  // edge-on
    const dvec3 s = o - t.a, q = glm::cross(s, e1);
    const double u = glm::dot(s, p) / det, v = glm::dot(d, q) / det;
    const double tt = glm::dot(e2, q) / det;
    const double inside = std::min({u, v, 1.0 - u - v});
    if (inside < -kEdge || tt < -kEps || tt > double(r.t_max) + kEps) continue;  // clear miss
    if (inside < kEdge || tt < kEps || tt > double(r.t_max) - kEps) {
      unsure = true;
      continue;
    }
    return Truth::Blocked;
  }
  return unsure ? Truth::Unsure : Truth::Visible;
}

dvec3 local(const detail::PreparedScene& p, dvec3 world) { return world - p.origin; }

ShadowRay ray_to(dvec3 from, dvec3 to, double shorter) {
  const dvec3 d = to - from;
  const double len = glm::length(d);
  return {glm::vec3(from), float(len - shorter), glm::vec3(d / len), 0.0f};
}

// Random rays in the box [lo, hi] (world): origins inside, directions uniform, t_max up to the
// box's diagonal; then rays ending 1 mm before and after points on the box's walls, and rays
// grazing its floor and a wall at 1 mm.
std::vector<ShadowRay> rays_in(const detail::PreparedScene& p, dvec3 lo, dvec3 hi, std::size_t n,
                               std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto point = [&](double margin) {
    return local(p, lo + margin + (hi - lo - 2.0 * margin) * dvec3(u(rng), u(rng), u(rng)));
  };
  const double diagonal = glm::length(hi - lo);
  std::vector<ShadowRay> rays;
  for (std::size_t i = 0; i < n; ++i) {
    const double z = 2.0 * u(rng) - 1.0, phi = 2.0 * glm::pi<double>() * u(rng);
    const double s = std::sqrt(1.0 - z * z);
    rays.push_back({glm::vec3(point(0.01)), float(diagonal * u(rng)),
                    glm::vec3(s * std::cos(phi), s * std::sin(phi), z), 0.0f});
  }
  for (int i = 0; i < 2000; ++i) {
    dvec3 wall = point(0.02) + p.origin;  // world, then onto one of the six walls
    const int axis = i % 3;
    wall[axis] = (i / 3) % 2 ? hi[axis] : lo[axis];
    for (const double shorter : {1e-3, -1e-3}) {
      rays.push_back(ray_to(point(0.05), local(p, wall), shorter));
    }
  }
  for (int i = 0; i < 2000; ++i) {
    dvec3 a = point(0.05), b = point(0.05);
    if (i % 2) {
      a.z = b.z = float(local(p, lo).z + 1e-3);  // 1 mm above the floor
    } else {
      a.x = b.x = float(local(p, hi).x - 1e-3);  // 1 mm off a wall
    }
    rays.push_back(ray_to(a, b, 0.0));
  }
  return rays;
}

// Vulkan's answer equals Embree's for every ray, and the exact one's where that is sure; both
// answers occur often.
void expect_same_visibility(detail::Backend& embree, detail::Backend& vulkan,
                            const std::vector<ShadowRay>& rays, const std::vector<Triangle>& tris,
                            const std::string& what) {
  std::vector<std::uint8_t> e, v;
  embree.visible(rays, e);
  vulkan.visible(rays, v);
  ASSERT_EQ(v.size(), rays.size());
  std::size_t differ = 0, wrong = 0, unsure = 0, seen = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    differ += e[i] != v[i];
    seen += v[i];
    const Truth t = exact(rays[i], tris);
    if (t == Truth::Unsure) {
      ++unsure;
    } else {
      wrong += v[i] != (t == Truth::Visible ? 1 : 0);
    }
    if ((e[i] != v[i] || (t != Truth::Unsure && v[i] != (t == Truth::Visible))) && wrong < 5) {
      ADD_FAILURE() << what << ": ray " << i << " embree " << int(e[i]) << " vulkan " << int(v[i])
                    << " exact " << int(t);
    }
  }
  EXPECT_EQ(differ, 0u) << what;
  EXPECT_EQ(wrong, 0u) << what;
  EXPECT_LT(unsure, rays.size() / 100) << what;
  EXPECT_GT(seen, rays.size() / 10) << what << ": too few visible rays to prove anything";
  EXPECT_GT(rays.size() - seen, rays.size() / 10) << what << ": too few blocked rays";
  std::printf("%s: %zu rays, %zu visible, %zu left to the backends (rounding)\n", what.c_str(),
              rays.size(), seen, unsure);
}

// `n` triangles in the planes x = 0, 50 um, 100 um, ..., each (y, z) = (-1, 1), (1, 1),
// (1, -0.9) about (y0, 0): a ray along x at (y0 - 0.1, 0) is inside every one's box but hits
// none (it passes below the long edge).
Mesh fan_mesh(const std::string& name, std::uint32_t n, double y0) {
  Mesh fan;
  fan.name = name;
  for (std::uint32_t k = 0; k < n; ++k) {
    const double x = 5e-5 * k;
    fan.vertices.push_back({x, y0 - 1, 1});
    fan.vertices.push_back({x, y0 + 1, 1});
    fan.vertices.push_back({x, y0 + 1, -0.9});
    fan.triangles.push_back({3 * k, 3 * k + 1, 3 * k + 2});
  }
  return fan;
}

using VulkanVisibilityTest = VulkanTest;

// The room with a block on the floor and a workplane grid through the middle (grids never
// block). Over 2^18 rays: more than one submission.
TEST_F(VulkanVisibilityTest, RoomWithAnOccluderAgreesWithEmbree) {
  const detail::PreparedScene p = detail::prepare(room_with_block(dvec3(0)));
  const auto embree = detail::make_embree_backend(p);
  const auto vulkan = detail::make_vulkan_backend(p);
  EXPECT_TRUE(vulkan->traces_shadow_rays());
  const std::vector<ShadowRay> rays = rays_in(p, dvec3(0), dvec3(6, 4, 3), 300'000, 1);
  ASSERT_GT(rays.size(), std::size_t(detail::kShadowRaysPerSubmit));
  expect_same_visibility(*embree, *vulkan, rays, triangles(p), "room with a block");
}

// Glass is opaque to shadow rays (its light is the photons' part), mirrors too.
TEST_F(VulkanVisibilityTest, GlassAndMirrorsBlock) {
  Scene s = room_with_block(dvec3(0));
  Material glass;
  glass.name = "glass";
  glass.type = Material::Type::Glass;
  glass.ior = 1.5;
  glass.thin = true;
  s.materials.push_back(glass);
  s.meshes.push_back(quad_mesh("pane", 2, {3, 0, 0}, {0, 4, 0}, {0, 0, 2}));
  add_material(s, "mirror", Material::Type::Mirror, 0.9);
  s.meshes.push_back(quad_mesh("mirror", 3, {0, 3, 2.5}, {4, 0, 0}, {0, 0.5, 0}));
  validate(s);
  const detail::PreparedScene p = detail::prepare(s);
  const auto embree = detail::make_embree_backend(p);
  const auto vulkan = detail::make_vulkan_backend(p);
  const std::vector<ShadowRay> rays = rays_in(p, dvec3(0), dvec3(6, 4, 3), 20'000, 2);
  expect_same_visibility(*embree, *vulkan, rays, triangles(p), "glass and mirror");
  // Across the pane, nothing else between: blocked on both.
  std::vector<std::uint8_t> v;
  vulkan->visible(
      std::vector<ShadowRay>{ray_to(local(p, {4.5, 3.5, 1.5}), local(p, {1.5, 3.5, 1.5}), 0.0)}, v);
  EXPECT_EQ(v, std::vector<std::uint8_t>{0});
}

// A movable mesh answers where it is now, after each set_mesh_transform.
TEST_F(VulkanVisibilityTest, MovedMeshBlocksWhereItIsNow) {
  const detail::PreparedScene p = detail::prepare(room_with_block(dvec3(0)), {1});
  const auto embree = detail::make_embree_backend(p);
  const auto vulkan = detail::make_vulkan_backend(p);
  const std::vector<ShadowRay> rays = rays_in(p, dvec3(0), dvec3(6, 4, 3), 20'000, 3);
  // Over the block's old place, under its new one after a 3 m move: the answer flips.
  const std::vector<ShadowRay> across = {
      ray_to(local(p, {1.5, 0.5, 0.4}), local(p, {1.5, 3.5, 0.4}), 0.0),
      ray_to(local(p, {4.5, 0.5, 0.4}), local(p, {4.5, 3.5, 0.4}), 0.0)};
  std::vector<std::uint8_t> v;
  vulkan->visible(across, v);
  EXPECT_EQ(v, (std::vector<std::uint8_t>{0, 1}));
  expect_same_visibility(*embree, *vulkan, rays, triangles(p), "block in place");
  const glm::vec3 centre = glm::vec3(local(p, {1.5, 1.5, 0}));
  const glm::mat4 moved = glm::translate(glm::mat4(1.0f), glm::vec3(3, 0, 0));
  const glm::mat4 turned = glm::translate(glm::mat4(1.0f), centre + glm::vec3(2.2f, 0.6f, 0)) *
                           glm::rotate(glm::mat4(1.0f), glm::radians(30.0f), glm::vec3(0, 0, 1)) *
                           glm::translate(glm::mat4(1.0f), -centre);
  for (const glm::mat4& m : {moved, turned}) {
    embree->set_mesh_transform(1, m);
    vulkan->set_mesh_transform(1, m);
    expect_same_visibility(*embree, *vulkan, rays, triangles(p, 1, m), "block moved");
  }
  vulkan->set_mesh_transform(1, moved);
  vulkan->visible(across, v);
  EXPECT_EQ(v, (std::vector<std::uint8_t>{1, 0}));
}

// Next-event estimation may ask from several threads (Embree's visible() is thread-safe): the
// calls take turns and each gets its own answers.
TEST_F(VulkanVisibilityTest, CallsFromSeveralThreadsTakeTurns) {
  const detail::PreparedScene p = detail::prepare(room_with_block(dvec3(0)));
  const auto vulkan = detail::make_vulkan_backend(p);
  std::vector<std::vector<ShadowRay>> rays;
  std::vector<std::vector<std::uint8_t>> answers(4), alone(4);
  for (std::uint32_t k = 0; k < 4; ++k) {
    rays.push_back(rays_in(p, dvec3(0), dvec3(6, 4, 3), 5'000 * (k + 1), 10 + k));
    vulkan->visible(rays[k], alone[k]);
  }
  std::vector<std::thread> threads;
  for (std::size_t k = 0; k < 4; ++k) {
    threads.emplace_back([&, k] { vulkan->visible(rays[k], answers[k]); });
  }
  for (std::thread& t : threads) t.join();
  for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(answers[k], alone[k]) << k;
}

TEST_F(VulkanVisibilityTest, NoRaysNoWork) {
  const detail::PreparedScene p = detail::prepare(room_with_block(dvec3(0)));
  const auto vulkan = detail::make_vulkan_backend(p);
  std::vector<std::uint8_t> v = {1, 2, 3};
  vulkan->visible({}, v);
  EXPECT_TRUE(v.empty());
}

// 100 000 triangles across a ray, one every 50 um, each with a corner cut away where the ray
// passes: it hits none, but its box holds every one of them, so it visits every node of the
// BVH: far over lavapipe's 65 535 loop iterations even traced alone, and the wall behind them,
// the nearest-first traversal's last leaf, is never reached. The backend must refuse rather
// than answer "visible" from a traversal cut short. Devices without the limit answer 0.
TEST_F(VulkanVisibilityTest, RayTooLongForTheLoopLimitIsRefusedNotGuessed) {
  Scene s;
  add_material(s, "grey", Material::Type::Diffuse, 0.5);
  s.meshes.push_back(fan_mesh("fan", 100'000, 0.0));
  s.meshes.push_back(quad_mesh("wall", 0, {5.5, -2, -2}, {0, 4, 0}, {0, 0, 4}));
  s.targets.push_back(surface("fan", 0));
  s.luminaires.push_back(point_light({2, -1.5, -1.5}, 100));
  validate(s);
  const detail::PreparedScene p = detail::prepare(s);
  const auto vulkan = detail::make_vulkan_backend(p);
  const std::vector<ShadowRay> ray = {ray_to(local(p, {-1, -0.1, 0}), local(p, {6, -0.1, 0}), 0.0)};
  ASSERT_EQ(exact(ray[0], triangles(p)), Truth::Blocked);
  std::vector<std::uint8_t> v;
  if (vulkan->device().find("llvmpipe") == std::string::npos) {
    vulkan->visible(ray, v);
    EXPECT_EQ(v, std::vector<std::uint8_t>{0});
    GTEST_SKIP() << "no loop limit on " << vulkan->device();
  }
  try {
    vulkan->visible(ray, v);
    FAIL() << "answered " << int(v.at(0)) << " from a traversal the loop limit cut short";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("loop iterations"), std::string::npos) << e.what();
  }
}

// Eight movable fans of 16 000 cut triangles (as above), one per ray of the first eight rays,
// which lavapipe runs together as the 8 lanes of one invocation. Each instance's traversal runs
// for its own lane only, one instance after the other, so the lanes' iterations add up past the
// limit, while each ray alone needs about a third of it: the rays are queued, traced again alone
// and answered right. Walls behind the fans (the last movable mesh) block the first four rays.
TEST_F(VulkanVisibilityTest, RaysCutTogetherAreTracedAgainAlone) {
  constexpr int kFans = 8;
  Scene s;
  add_material(s, "grey", Material::Type::Diffuse, 0.5);
  for (int j = 0; j < kFans; ++j) {
    s.meshes.push_back(fan_mesh("fan" + std::to_string(j), 16'000, 3.0 * j));
  }
  s.meshes.push_back(quad_mesh("walls", 0, {5.5, -2, -2}, {0, 12.5, 0}, {0, 0, 4}));
  s.targets.push_back(surface("walls", kFans));
  s.luminaires.push_back(point_light({2, -1.5, -1.5}, 100));
  validate(s);
  std::vector<std::size_t> moving(kFans + 1);
  for (std::size_t k = 0; k < moving.size(); ++k) moving[k] = k;
  const detail::PreparedScene p = detail::prepare(s, moving);
  const auto embree = detail::make_embree_backend(p);
  const auto vulkan = detail::make_vulkan_backend(p);
  std::vector<ShadowRay> rays;
  for (int j = 0; j < kFans; ++j) {
    const double y = 3.0 * j - 0.1;
    rays.push_back(ray_to(local(p, {-1, y, 0}), local(p, {6, y, 0}), 0.0));
  }
  const std::vector<Triangle> tris = triangles(p);
  std::vector<std::uint8_t> v, e;
  vulkan->visible(rays, v);
  embree->visible(rays, e);
  const std::vector<std::uint8_t> expected = {0, 0, 0, 0, 1, 1, 1, 1};
  EXPECT_EQ(v, expected);
  EXPECT_EQ(e, expected);
  for (int j = 0; j < kFans; ++j) {
    EXPECT_EQ(exact(rays[j], tris), j < 4 ? Truth::Blocked : Truth::Visible) << j;
  }
}

}  // namespace
}  // namespace lightsolver::test
