// The CPU backend: one photon path per loop iteration, rtcIntersect1 per segment, paths spread
// over TBB workers. Tallies are integer counts, so the result is independent of the schedule.
#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <xmmintrin.h>

#include <limits>

#include <glm/mat3x3.hpp>

#include "core/backend.hpp"
#include "core/emitters.hpp"
#include "core/path_deposits.hpp"
#include "core/scatter.hpp"
#include "embree/embree_scene.hpp"

namespace lightsolver::detail {
namespace {

class EmbreeBackend final : public Backend {
 public:
  explicit EmbreeBackend(const PreparedScene& s) : s_(s), embree_(s) {}

  std::string name() const override { return "embree"; }

  void set_mesh_transform(std::size_t mesh, const glm::mat4& transform) override {
    embree_.set_transform(mesh, transform);
  }

  void trace(std::uint64_t first, std::uint64_t count, std::uint64_t seed,
             TallyBlock& out) override {
    tbb::enumerable_thread_specific<TallyBlock> local([&] { return TallyBlock(out.bins.size()); });
    tbb::parallel_for(tbb::blocked_range<std::uint64_t>(first, first + count, 256),
                      [&](const tbb::blocked_range<std::uint64_t>& r) {
                        // Embree wants denormals flushed in every tracing thread.
                        _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
                        _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
                        TallyBlock& t = local.local();
                        PathDeposits deposits;
                        for (std::uint64_t id = r.begin(); id != r.end(); ++id) {
                          trace_path(id, seed, deposits, t);
                          deposits.flush(t.bins);
                        }
                      });
    for (const TallyBlock& t : local) out.add(t);
  }

 private:
  void trace_path(std::uint64_t id, std::uint64_t seed, PathDeposits& deposits,
                  TallyBlock& t) const {
    PathRng rng(seed, id);
    EmittedRay ray = emit(s_.luminaires[pick_luminaire(s_, rng)], rng);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    for (std::uint32_t bounce = 0;; ++bounce) {
      RTCRayHit rh = make_ray(ray);
      rtcIntersect1(embree_.handle(), &context, &rh);
      ++t.ray_segments;
      const bool hit = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
      if (!s_.grids.empty()) cross_grids(s_.grids, ray.origin, ray.direction, rh.ray.tfar, deposits);
      if (!hit) return;
      const bool instanced = rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID;
      const PreparedMesh& m = s_.meshes[instanced ? rh.hit.instID[0] : rh.hit.geomID];
      vec3 n = m.normals[rh.hit.primID];
      if (instanced) n = glm::normalize(glm::mat3(m.transform) * n);  // rigid: no inverse needed
      if (m.bin >= 0 && glm::dot(ray.direction, n) < 0.0f) deposits.add(m.bin);
      if (!scatter(s_.materials[m.material], n, ray.direction, rng)) return;
      if (bounce >= s_.max_bounces) {
        ++t.capped_paths;  // still alive: stopping here loses its energy (reported)
        return;
      }
      vec3 p = hit_point(m, rh.hit.primID, rh.hit.u, rh.hit.v);
      if (instanced) p = vec3(m.transform * glm::vec4(p, 1.0f));
      ray.origin = offset_ray_origin(p, glm::dot(ray.direction, n) > 0.0f ? n : -n);
    }
  }

  static RTCRayHit make_ray(const EmittedRay& r) {
    RTCRayHit rh;
    rh.ray.org_x = r.origin.x;
    rh.ray.org_y = r.origin.y;
    rh.ray.org_z = r.origin.z;
    rh.ray.dir_x = r.direction.x;
    rh.ray.dir_y = r.direction.y;
    rh.ray.dir_z = r.direction.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.mask = 0xFFFFFFFFu;
    rh.ray.time = 0.0f;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rh;
  }

  // Interpolating the triangle is more accurate than origin + t * direction, whose error grows
  // with the distance travelled.
  static vec3 hit_point(const PreparedMesh& m, unsigned prim, float u, float v) {
    const std::uint32_t* idx = &m.indices[3 * prim];
    auto vertex = [&](int k) {
      const float* p = &m.vertices[3 * idx[k]];
      return vec3(p[0], p[1], p[2]);
    };
    const vec3 v0 = vertex(0);
    return v0 + u * (vertex(1) - v0) + v * (vertex(2) - v0);
  }

  const PreparedScene& s_;
  EmbreeScene embree_;
};

}  // namespace

std::unique_ptr<Backend> make_embree_backend(const PreparedScene& scene) {
  return std::make_unique<EmbreeBackend>(scene);
}

}  // namespace lightsolver::detail
