// The GPU BVH (rtcBuildBVH, flattened) and its watertight traversal against Embree's
// rtcIntersect1 on random rays: the same hit or miss and the same distance.
#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <cmath>
#include <limits>

#include "benchmarks/bench_scenes.hpp"
#include "model/prepared_scene.hpp"
#include "embree/embree_scene.hpp"
#include "lightsolver/rng.hpp"
#include "vulkan/gpu_bvh.hpp"
#include "vulkan_test_util.hpp"

namespace lightsolver::test {
namespace {

constexpr std::uint32_t kRaycastSpirv[] = {
#include "raycast_test.spv.inc"
};

struct RayIn {
  float origin[4], dir[4];
};
struct HitOut {
  float t;
  std::uint32_t mesh, prim, hit;
};

struct Rays {
  std::vector<RayIn> rays;
  void add(glm::vec3 o, glm::vec3 d) { rays.push_back({{o.x, o.y, o.z, 0}, {d.x, d.y, d.z, 0}}); }
};

glm::vec3 random_direction(PathRng& rng) {
  const float z = 1 - 2 * rng.uniform(), r = std::sqrt(std::max(0.0f, 1 - z * z));
  const float phi = 6.2831853f * rng.uniform();
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Origins uniform in [lo, hi], directions uniform; a few axis-parallel directions too, since
// zero direction components take a special path in the slab test.
Rays random_rays(glm::vec3 lo, glm::vec3 hi, std::uint32_t n) {
  Rays r;
  for (std::uint32_t i = 0; i < n; ++i) {
    PathRng rng(99, i);
    const glm::vec3 o = lo + glm::vec3(rng.uniform(), rng.uniform(), rng.uniform()) * (hi - lo);
    glm::vec3 d = random_direction(rng);
    if (i % 16 == 0) d = glm::vec3(0.0f), d[i / 16 % 3] = (i / 48) % 2 ? 1.0f : -1.0f;
    r.add(o, d);
  }
  return r;
}

std::vector<HitOut> gpu_hits(const detail::PreparedScene& s, const Rays& rays) {
  const vkw::Context ctx;
  const detail::GpuGeometry g = detail::build_gpu_geometry(s);
  auto buffer = [&](const void* data, std::size_t bytes, const char* name) {
    vkw::Buffer b(ctx, std::max<std::size_t>(bytes, 16), vkw::MemoryKind::Device, name);
    vkw::upload(ctx, b, data, bytes);
    return b;
  };
  const vkw::Buffer nodes = buffer(g.nodes.data(), g.nodes.size() * sizeof(g.nodes[0]), "nodes");
  const vkw::Buffer tris = buffer(g.tris.data(), g.tris.size() * sizeof(g.tris[0]), "tris");
  const vkw::Buffer normals =
      buffer(g.normals.data(), g.normals.size() * sizeof(g.normals[0]), "normals");
  const vkw::Buffer in = buffer(rays.rays.data(), rays.rays.size() * sizeof(RayIn), "rays");
  const vkw::Buffer out(ctx, rays.rays.size() * sizeof(HitOut), vkw::MemoryKind::Readback, "hits");
  const auto n = static_cast<std::uint32_t>(rays.rays.size());
  run_kernel(ctx, kRaycastSpirv, {&nodes, &tris, &normals, &in, &out}, &n, 4, n);
  const auto* h = static_cast<const HitOut*>(out.mapped());
  return {h, h + n};
}

// Compares every ray; returns the number of rays that hit on both sides.
std::size_t expect_same_hits(const detail::PreparedScene& s, const Rays& rays) {
  const std::vector<HitOut> gpu = gpu_hits(s, rays);
  const detail::EmbreeScene embree(s);
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  std::size_t both = 0, failures = 0;
  for (std::size_t i = 0; i < rays.rays.size(); ++i) {
    const RayIn& r = rays.rays[i];
    RTCRayHit rh{};
    rh.ray.org_x = r.origin[0], rh.ray.org_y = r.origin[1], rh.ray.org_z = r.origin[2];
    rh.ray.dir_x = r.dir[0], rh.ray.dir_y = r.dir[1], rh.ray.dir_z = r.dir[2];
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.mask = 0xFFFFFFFFu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(embree.handle(), &ctx, &rh);
    const bool hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    const HitOut& g = gpu[i];
    bool ok = hit == (g.hit != 0);
    if (ok && hit) {  // the mesh may differ where coplanar faces tie (a box on the floor)
      ++both;
      ok = std::abs(g.t - rh.ray.tfar) <= 1e-5f * (1 + rh.ray.tfar);
    }
    if (!ok && ++failures <= 5) {
      ADD_FAILURE() << "ray " << i << ": embree hit " << hit << " mesh " << rh.hit.geomID << " t "
                    << rh.ray.tfar << "; gpu hit " << g.hit << " mesh " << g.mesh << " t " << g.t;
    }
  }
  EXPECT_EQ(failures, 0u);
  return both;
}

using BvhTest = VulkanTest;

TEST_F(BvhTest, CornellBoxRaysFromInsideAllHitLikeEmbree) {
  const Scene scene = bench::cornell_box();
  const detail::PreparedScene s = detail::prepare(scene);
  const glm::vec3 lo = glm::vec3(0.01f) - glm::vec3(s.origin), hi = lo + glm::vec3(5.48f);
  const Rays rays = random_rays(lo, hi, 20000);
  EXPECT_EQ(expect_same_hits(s, rays), rays.rays.size()) << "a closed room leaked";
}

TEST_F(BvhTest, SpheresFromOutsideHitAndMissLikeEmbree) {
  Scene scene;
  add_material(scene, "grey", Material::Type::Diffuse, 0.5);
  for (int i = 0; i < 4; ++i) {
    scene.meshes.push_back(
        bench::sphere_mesh("s" + std::to_string(i), 0, {1.5 * i, 0.3 * i, 0.0}, 0.7, 24, 32));
  }
  scene.luminaires.push_back(point_light({0, 0, 5}, 1));
  scene.targets.push_back(surface("s0", 0));
  validate(scene);
  const detail::PreparedScene s = detail::prepare(scene);
  const std::size_t both = expect_same_hits(s, random_rays({-3, -3, -3}, {7, 3, 3}, 20000));
  EXPECT_GT(both, 1000u);  // the test saw hits as well as misses
  EXPECT_LT(both, 19000u);
}

// Georeferenced: re-centred coordinates, 4x4-tessellated walls with many shared edges; rays
// start on wall vertices' lines, the hardest case for leaks.
TEST_F(BvhTest, GeoreferencedRoomIsWatertight) {
  Scene scene;
  add_material(scene, "black", Material::Type::Diffuse, 0.0);
  const glm::dvec3 off(4.1e6, 6.3e6, 310.0);
  scene.meshes.push_back(room_mesh("room", 0, off, off + glm::dvec3(4, 3, 2.5), 4));
  scene.luminaires.push_back(point_light(off + glm::dvec3(1, 1, 1), 1));
  scene.targets.push_back(surface("room", 0));
  validate(scene);
  const detail::PreparedScene s = detail::prepare(scene);
  Rays rays;
  const glm::vec3 base = glm::vec3(glm::dvec3(off) - s.origin);
  for (std::uint32_t i = 0; i < 20000; ++i) {
    PathRng rng(5, i);
    // Origins on the grid lines x = k, y = 0.75 j: rays aimed at edges and vertices too.
    const glm::vec3 o = base + glm::vec3(1 + (i % 3), 0.75f * (1 + i % 3), 1.25f);
    const glm::vec3 target = base + glm::vec3(float(i % 5), 0.75f * float(i / 5 % 5), 0.0f);
    rays.add(o, i % 2 ? glm::normalize(target - o) : random_direction(rng));
  }
  EXPECT_EQ(expect_same_hits(s, rays), rays.rays.size()) << "a closed room leaked";
}

}  // namespace
}  // namespace lightsolver::test
