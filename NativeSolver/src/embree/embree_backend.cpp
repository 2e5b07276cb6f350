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

// What a hit needs of its triangle, in one cache line: on large models the BVH leaves hold
// their own triangle copies, so the scene's vertex, index and normal arrays are cold and four
// scattered reads per hit would cost more than the intersection. e1, e2 are exactly the float
// differences the interpolation used to compute, so results are unchanged to the bit.
struct alignas(64) HitTriangle {
  vec3 v0, e1, e2, n;
};

std::vector<std::vector<HitTriangle>> pack_triangles(const PreparedScene& s) {
  std::vector<std::vector<HitTriangle>> out(s.meshes.size());
  for (std::size_t i = 0; i < s.meshes.size(); ++i) {
    const PreparedMesh& m = s.meshes[i];
    auto vertex = [&](std::uint32_t k) {
      return vec3(m.vertices[3 * k], m.vertices[3 * k + 1], m.vertices[3 * k + 2]);
    };
    out[i].reserve(m.normals.size());
    for (std::size_t t = 0; t < m.normals.size(); ++t) {
      const vec3 v0 = vertex(m.indices[3 * t]);
      out[i].push_back(
          {v0, vertex(m.indices[3 * t + 1]) - v0, vertex(m.indices[3 * t + 2]) - v0, m.normals[t]});
    }
  }
  return out;
}

class EmbreeBackend final : public Backend {
 public:
  explicit EmbreeBackend(const PreparedScene& s)
      : s_(s), embree_(s), triangles_(pack_triangles(s)) {}

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
      bool instanced = false;
      const unsigned mesh = embree_.mesh_of(rh.hit, instanced);
      const PreparedMesh& m = s_.meshes[mesh];
      const HitTriangle& tri = triangles_[mesh][rh.hit.primID];
      vec3 n = tri.n;
      if (instanced) n = glm::normalize(glm::mat3(m.transform) * n);  // rigid: no inverse needed
      if (m.bin >= 0 && glm::dot(ray.direction, n) < 0.0f) deposits.add(m.bin);
      if (!scatter(s_.materials[m.material], n, ray.direction, rng)) return;
      if (bounce >= s_.max_bounces) {
        ++t.capped_paths;  // still alive: stopping here loses its energy (reported)
        return;
      }
      // Interpolating the triangle is more accurate than origin + t * direction, whose error
      // grows with the distance travelled (it biases reflective rooms: tested).
      vec3 p = tri.v0 + rh.hit.u * tri.e1 + rh.hit.v * tri.e2;
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

  const PreparedScene& s_;
  EmbreeScene embree_;
  std::vector<std::vector<HitTriangle>> triangles_;  // per mesh, per primitive
};

}  // namespace

std::unique_ptr<Backend> make_embree_backend(const PreparedScene& scene) {
  return std::make_unique<EmbreeBackend>(scene);
}

}  // namespace lightsolver::detail
