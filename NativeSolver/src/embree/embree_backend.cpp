// The CPU backend: rtcIntersect1 per segment, a few paths interleaved per worker, paths spread
// over TBB workers. Tallies are integer counts, so the result is independent of the schedule.
#include "embree/embree_backend.hpp"

#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <xmmintrin.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <fstream>
#include <glm/mat3x3.hpp>
#include <limits>
#include <stdexcept>
#include <string_view>

#include "embree/embree_scene.hpp"
#include "embree/hit_triangles.hpp"
#include "embree/path_kernel.hpp"
#include "model/emitters.hpp"
#include "model/path_deposits.hpp"
#include "model/scatter.hpp"
#include "model/sobol.hpp"
#include "shared/luminaires.h"

namespace lightsolver::detail {
namespace {

// "CPU: <model name> (Embree 3.13.5)": the processor as Linux names it (/proc/cpuinfo).
std::string cpu_device() {
  std::string model = "CPU";
  std::ifstream info("/proc/cpuinfo");
  for (std::string line; std::getline(info, line);) {
    if (line.rfind("model name", 0) != 0) continue;
    const auto colon = line.find(':');
    if (colon != std::string::npos && colon + 2 <= line.size())
      model = "CPU: " + line.substr(colon + 2);
    break;
  }
  return model + " (Embree " RTC_VERSION_STRING ")";
}

// Embree wants denormals flushed in every tracing thread. TBB also runs chunks on the caller's
// thread (Python's, say): its modes come back when the chunk ends.
class DenormalsFlushed {
 public:
  DenormalsFlushed() : ftz_(_MM_GET_FLUSH_ZERO_MODE()), daz_(_MM_GET_DENORMALS_ZERO_MODE()) {
    _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
    _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
  }
  ~DenormalsFlushed() {
    _MM_SET_FLUSH_ZERO_MODE(ftz_);
    _MM_SET_DENORMALS_ZERO_MODE(daz_);
  }
  DenormalsFlushed(const DenormalsFlushed&) = delete;
  DenormalsFlushed& operator=(const DenormalsFlushed&) = delete;

 private:
  unsigned ftz_, daz_;
};

class EmbreeBackend final : public Backend {
 public:
  EmbreeBackend(const PreparedScene& s, EmbreeKernel kernel)
      : s_(s),
        embree_(s),
        triangles_(s),
        kernel_(kernel == EmbreeKernel::General ? kGeneralKernel : kernel_for(analyse_effects(s))) {
  }

  std::string name() const override { return "embree"; }

  std::string device() const override {
    static const std::string device = cpu_device();  // the same for every run of a process
    return device;
  }

  KernelFeatures kernel() const { return kernel_; }

  bool traces_shadow_rays() const override { return true; }

  bool traces_quasi_random() const override { return true; }
  void set_quasi_random(bool on) override { quasi_random_ = on; }

  void visible(std::span<const ShadowRay> rays, std::vector<std::uint8_t>& out) override {
    out.assign(rays.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 1024),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        const DenormalsFlushed flushed;
                        RTCIntersectContext context;
                        rtcInitIntersectContext(&context);
                        for (std::size_t i = r.begin(); i != r.end(); ++i) {
                          out[i] = occluded(rays[i], context) ? 0 : 1;
                        }
                      });
  }

  bool traces_path_vertices() const override { return true; }

  void path_vertices(std::uint32_t group, std::uint64_t first, std::uint64_t count,
                     std::uint64_t seed, std::uint32_t stream,
                     std::vector<PathVertex>& out) override {
    // Blocks of paths in parallel, each into its own list: the order is the photons'.
    constexpr std::uint64_t kBlock = 16;
    std::vector<std::vector<PathVertex>> blocks((count + kBlock - 1) / kBlock);
    tbb::parallel_for(std::size_t(0), blocks.size(), [&](std::size_t b) {
      const DenormalsFlushed flushed;
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      context.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
      const std::uint64_t end = std::min(count, (b + 1) * kBlock);
      for (std::uint64_t i = b * kBlock; i < end; ++i) {
        trace_vertices(group, first + i, std::uint32_t(i), seed, stream, context, blocks[b]);
      }
    });
    for (const auto& b : blocks) out.insert(out.end(), b.begin(), b.end());
  }

  void set_mesh_transform(std::size_t mesh, const glm::mat4& transform) override {
    embree_.set_transform(mesh, transform);
  }

  void trace(const std::vector<GroupRange>& ranges, std::uint64_t seed, TallyBlock& out) override {
    const std::size_t bins = s_.bins.size();
    if (out.bins.size() <= kSharedBlockTallies) {
      trace_ranges(ranges, seed, true, out);
      return;
    }
    // Many groups over many bins: each worker's block would hold every group's tallies (up to
    // 1 GiB each); one group at a time, it holds that group's only. Same counts either way.
    for (const GroupRange& r : ranges) {
      TallyBlock part(bins);
      trace_ranges({r}, seed, false, part);
      for (std::size_t b = 0; b < bins; ++b) {
        out.bins[r.group * bins + b].sum += part.bins[b].sum;
        out.bins[r.group * bins + b].sum_sq += part.bins[b].sum_sq;
      }
      out.add_counts(part);
    }
  }

 private:
  // Above this many groups x bins (16 MiB a worker), groups are traced one at a time.
  static constexpr std::size_t kSharedBlockTallies = std::size_t(1) << 20;

  // Traces `ranges` into `out`: at group * bins + bin when `by_group`, else at bin.
  void trace_ranges(const std::vector<GroupRange>& ranges, std::uint64_t seed, bool by_group,
                    TallyBlock& out) const {
    // The ranges end to end: index k of [0, total) is photon k - starts[r] of range r.
    std::vector<std::uint64_t> starts{0};
    for (const GroupRange& r : ranges) starts.push_back(starts.back() + r.count);
    std::vector<SobolScramble> scrambles;  // per range, for quasi-random photons
    if (quasi_random_) {
      for (const GroupRange& r : ranges) scrambles.emplace_back(seed, r.group);
    }
    const Photons photons{ranges, starts, seed, by_group, scrambles};
    tbb::enumerable_thread_specific<TallyBlock> local([&] { return TallyBlock(out.bins.size()); });
    tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, starts.back(), 256),
                      [&](const tbb::blocked_range<std::uint64_t>& r) {
                        const DenormalsFlushed flushed;
                        with_kernel(kernel_, [&]<KernelFeatures F>() {
                          trace_range<F>(r.begin(), r.end(), photons, local.local());
                        });
                      });
    for (const TallyBlock& t : local) out.add(t);
  }

  // Paths in flight per worker. A hit's triangle record is, on large models, a DRAM miss that a
  // raw ray never pays; with several paths interleaved, the record is prefetched right after
  // the intersection and used only after the other lanes' rays have been traced, by when it has
  // arrived. Each lane keeps its own deposits, so the per-path totals (and hence the integer
  // tallies) are exactly those of one-path-at-a-time tracing. Four lanes measured best on the
  // 1M-triangle benchmark (+10 % over one lane; two and eight were no better).
  static constexpr int kLanes = 4;

  // Which photon of which group index k of a trace() call is.
  struct Photons {
    const std::vector<GroupRange>& ranges;
    const std::vector<std::uint64_t>& starts;  // starts[r]: index of range r's first photon
    std::uint64_t seed;
    bool by_group;  // tallies at group * bins + bin (else at bin: one group's block)
    const std::vector<SobolScramble>& scrambles;  // per range; empty: Philox only
  };

  struct Lane {
    PathRng rng{0, 0};
    std::size_t tally_offset = 0;  // the path's group's first tally
    EmittedRay ray;
    std::uint32_t bounce = 0;
    std::uint32_t first_bounce = 0;  // 1: its group's direct light is by next-event estimation
    bool connected = false;          // its group's far reflected light at grids is by connection
    RTCRayHit rh;
    PathDeposits deposits;
    bool active = false;
  };

  template <KernelFeatures F>
  void trace_range(std::uint64_t next, std::uint64_t end, const Photons& seed,
                   TallyBlock& t) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
    std::array<Lane, kLanes> lanes;
    int active = 0;
    for (Lane& lane : lanes) {
      if (!start_next_path(lane, next, end, seed, context, t)) break;
      intersect<F>(lane, context, t);
      ++active;
    }
    while (active > 0) {
      for (Lane& lane : lanes) {
        if (!lane.active) continue;
        if (!continue_path<F>(lane, t)) {
          lane.deposits.flush(t.bins, lane.tally_offset);
          if (!start_next_path(lane, next, end, seed, context, t)) {
            lane.active = false;
            --active;
            continue;
          }
        }
        intersect<F>(lane, context, t);
      }
    }
  }

  void start_path(Lane& lane, std::uint64_t k, const Photons& p) const {
    const std::size_t r =
        std::upper_bound(p.starts.begin(), p.starts.end(), k) - p.starts.begin() - 1;
    const GroupRange& range = p.ranges[r];
    const std::uint64_t i = range.first + (k - p.starts[r]);
    lane.rng = p.scrambles.empty() ? PathRng(p.seed, i, range.group)
                                   : p.scrambles[r].path_rng(p.seed, i, range.group);
    lane.tally_offset = p.by_group ? std::size_t(range.group) * s_.bins.size() : 0;
    lane.ray = emit(s_.luminaires[pick_luminaire(s_.groups[range.group], lane.rng)], lane.rng);
    lane.bounce = 0;
    lane.first_bounce = s_.groups[range.group].next_event ? 1 : 0;
    lane.connected = s_.groups[range.group].connect;
    lane.active = true;
  }

  // Starts the lane's next photon that gets into the scene (photons blocked outside their
  // opening end at birth, with no tally); false, the lane left inactive, when none is left (a
  // lane whose last photons were all blocked has no segment to continue).
  bool start_next_path(Lane& lane, std::uint64_t& next, std::uint64_t end, const Photons& seed,
                       RTCIntersectContext& context, TallyBlock& t) const {
    while (next != end) {
      start_path(lane, next++, seed);
      if (!blocked_outside(lane.ray, context, t)) return true;
    }
    lane.active = false;
    return false;
  }

  // A daylight photon from an opening: does its way out (toward its sky, against its direction)
  // meet the scene? Then it is absorbed there (docs/daylight.md, "Portals and outside
  // obstructions"); the count of those says how much the outside blocks.
  bool blocked_outside(const EmittedRay& ray, RTCIntersectContext& context, TallyBlock& t) const {
    if (ray.opening_push == vec3(0.0f)) return false;
    ++t.opening_photons;
    RTCRayHit rh =
        make_ray({shared::opening_escape_origin(ray.origin, ray.opening_push), -ray.direction});
    rtcIntersect1(embree_.handle(), &context, &rh);
    ++t.ray_segments;
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    ++t.opening_blocked;
    bool instanced = false;
    const PreparedMesh& m = s_.meshes[embree_.mesh_of(rh.hit, instanced)];
    if (s_.materials[m.material].type == Material::Type::Glass) ++t.opening_glass;
    return true;
  }

  // Traces the lane's next segment, counts the grids it crosses and starts fetching the record
  // of the triangle it hit.
  template <KernelFeatures F>
  void intersect(Lane& lane, RTCIntersectContext& context, TallyBlock& t) const {
    lane.rh = make_ray(lane.ray);
    rtcIntersect1(embree_.handle(), &context, &lane.rh);
    ++t.ray_segments;
    cross_grids_with<F>(s_.grids, lane.ray.origin, lane.ray.direction, lane.rh.ray.tfar,
                        lane.bounce, lane.deposits, lane.first_bounce, lane.connected);
    if (lane.rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return;
    bool instanced = false;
    const unsigned mesh = embree_.mesh_of(lane.rh.hit, instanced);
    // Direct light only: the path ends here, and only a target's hit reads its triangle.
    if constexpr (!F.reflects) {
      if (s_.meshes[mesh].bin < 0) return;
    }
    _mm_prefetch(reinterpret_cast<const char*>(&triangles_.at(mesh, lane.rh.hit.primID)),
                 _MM_HINT_T0);
  }

  // Deposits on and scatters at the lane's last hit; false when the path has ended.
  template <KernelFeatures F>
  bool continue_path(Lane& lane, TallyBlock& t) const {
    const RTCHit& h = lane.rh.hit;
    if (h.geomID == RTC_INVALID_GEOMETRY_ID) return false;
    bool instanced = false;
    const unsigned mesh = embree_.mesh_of(h, instanced);
    const PreparedMesh& m = s_.meshes[mesh];
    if constexpr (!F.reflects) {
      if (m.bin < 0) return false;  // absorbed where nothing is tallied: no triangle to read
    }
    const HitTriangle& tri = triangles_.at(mesh, h.primID);
    EmittedRay& ray = lane.ray;
    vec3 n = tri.n;
    if (instanced) n = glm::normalize(glm::mat3(m.transform) * n);  // rigid: no inverse needed
    // Bounce 0 of a next-event group only where the target's direct light is by photons.
    if (m.bin >= 0 && (lane.bounce >= lane.first_bounce || m.direct_by_photons) &&
        glm::dot(ray.direction, n) < 0.0f) {
      lane.deposits.add(m.bin);
    }
    if constexpr (!F.reflects) return false;  // no surface returns light: absorbed
    if (!scatter_with<F>(s_.materials[m.material], n, ray.direction, lane.rng)) return false;
    if (lane.bounce++ >= s_.max_bounces) {
      ++t.capped_paths;  // still alive: stopping here loses its energy (reported)
      return false;
    }
    // Interpolating the triangle is more accurate than origin + t * direction, whose error
    // grows with the distance travelled (it biases reflective rooms: tested).
    vec3 p = tri.v0 + h.u * tri.e1 + h.v * tri.e2;
    if (instanced) p = vec3(m.transform * glm::vec4(p, 1.0f));
    ray.origin = offset_ray_origin(p, glm::dot(ray.direction, n) > 0.0f ? n : -n);
    return true;
  }

  // One photon of path_vertices(): emitted as start_path() emits, then diffuse reflections
  // only, as continue_path() scatters (survival by reflectance, a cosine lobe, max_bounces).
  void trace_vertices(std::uint32_t group, std::uint64_t photon, std::uint32_t path,
                      std::uint64_t seed, std::uint32_t stream, RTCIntersectContext& context,
                      std::vector<PathVertex>& out) const {
    PathRng rng(seed, photon, stream);
    EmittedRay ray = emit(s_.luminaires[pick_luminaire(s_.groups[group], rng)], rng);
    TallyBlock unused;
    if (blocked_outside(ray, context, unused)) return;
    for (std::uint32_t vertex = 1; vertex <= s_.max_bounces; ++vertex) {
      RTCRayHit rh = make_ray(ray);
      rtcIntersect1(embree_.handle(), &context, &rh);
      const RTCHit& h = rh.hit;
      if (h.geomID == RTC_INVALID_GEOMETRY_ID) return;
      bool instanced = false;
      const unsigned mesh = embree_.mesh_of(h, instanced);
      const PreparedMesh& m = s_.meshes[mesh];
      const Material& material = s_.materials[m.material];
      if (material.type != Material::Type::Diffuse || !(material.reflectance > 0.0)) return;
      const HitTriangle& tri = triangles_.at(mesh, h.primID);
      vec3 n = tri.n;
      if (instanced) n = glm::normalize(glm::mat3(m.transform) * n);
      const vec3 facing = glm::dot(ray.direction, n) < 0.0f ? n : -n;
      vec3 p = tri.v0 + h.u * tri.e1 + h.v * tri.e2;
      if (instanced) p = vec3(m.transform * glm::vec4(p, 1.0f));
      ray.origin = offset_ray_origin(p, facing);
      out.push_back({ray.origin, float(material.reflectance), facing, path});
      if (!scatter_diffuse(material, facing, ray.direction, rng)) return;
    }
  }

  bool occluded(const ShadowRay& s, RTCIntersectContext& context) const {
    RTCRay ray;
    ray.org_x = s.origin.x;
    ray.org_y = s.origin.y;
    ray.org_z = s.origin.z;
    ray.dir_x = s.direction.x;
    ray.dir_y = s.direction.y;
    ray.dir_z = s.direction.z;
    ray.tnear = 0.0f;
    ray.tfar = s.t_max;
    ray.mask = 0xFFFFFFFFu;
    ray.time = 0.0f;
    ray.flags = 0;
    rtcOccluded1(embree_.handle(), &context, &ray);
    return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
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
  HitTriangles triangles_;
  KernelFeatures kernel_;  // the compiled path kernel this scene runs (path_kernel.hpp)
  bool quasi_random_ = false;
};

// LIGHTSOLVER_EMBREE_KERNEL=general forces the general kernel (comparisons, benchmarks).
EmbreeKernel kernel_from_environment() {
  const char* v = std::getenv("LIGHTSOLVER_EMBREE_KERNEL");
  return v && std::string_view(v) == "general" ? EmbreeKernel::General : EmbreeKernel::Specialised;
}

}  // namespace

std::unique_ptr<Backend> make_embree_backend(const PreparedScene& scene) {
  return make_embree_backend(scene, kernel_from_environment());
}

std::unique_ptr<Backend> make_embree_backend(const PreparedScene& scene, EmbreeKernel kernel) {
  return std::make_unique<EmbreeBackend>(scene, kernel);
}

KernelFeatures embree_kernel(const Backend& backend) {
  const auto* embree = dynamic_cast<const EmbreeBackend*>(&backend);
  if (!embree) throw std::logic_error("embree_kernel: the backend is " + backend.name());
  return embree->kernel();
}

}  // namespace lightsolver::detail
