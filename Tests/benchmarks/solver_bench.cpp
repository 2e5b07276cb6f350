// Photon throughput of the solver next to Embree's raw rtcIntersect1 rate for random rays on
// the same scene, in the same run (ratios only mean something within one run on this noisy
// shared machine). Results go to docs/BENCHMARKS.md.
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <xmmintrin.h>

#include <limits>

#include "bench_scenes.hpp"
#include "bench_util.hpp"
#include "model/backend.hpp"
#include "model/emitters.hpp"
#include "model/prepared_scene.hpp"
#include "model/sampling.hpp"
#include "model/scatter.hpp"
#include "embree/embree_backend.hpp"
#include "embree/embree_scene.hpp"
#include "lightsolver/rng.hpp"
#include "lightsolver/simulation.hpp"

namespace lightsolver::bench {
namespace {

const Scene& scene_by_index(int i) {
  static const Scene cornell = cornell_box();
  static const Scene million = million_triangles();
  return i == 0 ? cornell : million;
}

// Tracing alone (scene prepared and BVH built once, outside the timed loop), so the rate is
// comparable with the raw-ray figure below.
void BM_PhotonTracing(benchmark::State& state) {
  const Scene& scene = scene_by_index(static_cast<int>(state.range(0)));
  const detail::PreparedScene prepared = detail::prepare(scene);
  auto backend = detail::make_embree_backend(prepared);
  measure_tracing(state, *backend, prepared.bins.size(),
                  static_cast<std::uint64_t>(state.range(1)));
}

// What a user's run pays before the first photon: validation copy, re-centring, BVH build.
void BM_ScenePrepareAndBuild(benchmark::State& state) {
  const Scene& scene = scene_by_index(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const detail::PreparedScene prepared = detail::prepare(scene);
    benchmark::DoNotOptimize(detail::make_embree_backend(prepared));
  }
  state.counters["triangles"] = double(detail::prepare(scene).triangle_count);
}

// Prepare alone (re-centring, float geometry, bins and the coincident-surface check, which
// runs on all cores): beside BM_ScenePrepareAndBuild it shows what the check adds to a run.
void BM_ScenePrepare(benchmark::State& state) {
  const Scene& scene = scene_by_index(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(detail::prepare(scene));
}

// Random rays: origins uniform in the scene's box, directions uniform on the sphere, one
// rtcIntersect1 each, spread over TBB workers exactly as the photon tracer spreads paths.
void BM_RawEmbreeRandomRays(benchmark::State& state) {
  const Scene& scene = scene_by_index(static_cast<int>(state.range(0)));
  const detail::PreparedScene prepared = detail::prepare(scene);
  const detail::EmbreeScene embree(prepared);
  RTCBounds b;
  rtcGetSceneBounds(embree.handle(), &b);
  const glm::vec3 lo(b.lower_x, b.lower_y, b.lower_z), hi(b.upper_x, b.upper_y, b.upper_z);
  const std::uint64_t rays = static_cast<std::uint64_t>(state.range(1));
  std::uint64_t total = 0, hits = 0;
  for (auto _ : state) {
    tbb::enumerable_thread_specific<std::uint64_t> local_hits(0);
    tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, rays, 256), [&](auto r) {
      _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
      _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
      RTCIntersectContext ctx;
      rtcInitIntersectContext(&ctx);
      ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
      for (std::uint64_t i = r.begin(); i != r.end(); ++i) {
        PathRng rng(77, i);
        RTCRayHit rh{};
        const glm::vec3 o = lo + glm::vec3(rng.uniform(), rng.uniform(), rng.uniform()) * (hi - lo);
        const float z = 1 - 2 * rng.uniform(), rr = std::sqrt(std::max(0.f, 1 - z * z));
        const float ph = 6.2831853f * rng.uniform();
        rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
        rh.ray.dir_x = rr * std::cos(ph), rh.ray.dir_y = rr * std::sin(ph), rh.ray.dir_z = z;
        rh.ray.tfar = std::numeric_limits<float>::infinity();
        rh.ray.mask = ~0u;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(embree.handle(), &ctx, &rh);
        local_hits.local() += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
      }
    });
    total += rays;
    for (auto h : local_hits) hits += h;
  }
  state.counters["rays/s"] = benchmark::Counter(double(total), benchmark::Counter::kIsRate);
  state.counters["hit_fraction"] = double(hits) / double(total);
}

// The photon tracer's own segments, recorded once (same emission, scattering and offsets, no
// tallies), replayed through bare rtcIntersect1: the ceiling for the tracer on this scene, with
// the rays' own lengths and directions. Random rays (above) start anywhere in the box; photon
// segments start on lights and surfaces and cross the room, so their traversal costs differ.
std::vector<RTCRay> record_photon_segments(const detail::PreparedScene& s,
                                           const detail::EmbreeScene& embree, std::uint64_t n) {
  std::vector<RTCRay> rays;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  for (std::uint64_t id = 0; id < n; ++id) {
    PathRng rng(5, id);
    detail::EmittedRay ray = detail::emit(s.luminaires[detail::pick_luminaire(s.groups[0], rng)], rng);
    for (std::uint32_t bounce = 0;; ++bounce) {
      RTCRayHit rh{};
      rh.ray.org_x = ray.origin.x, rh.ray.org_y = ray.origin.y, rh.ray.org_z = ray.origin.z;
      rh.ray.dir_x = ray.direction.x, rh.ray.dir_y = ray.direction.y;
      rh.ray.dir_z = ray.direction.z;
      rh.ray.tfar = std::numeric_limits<float>::infinity();
      rh.ray.mask = ~0u;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rays.push_back(rh.ray);
      rtcIntersect1(embree.handle(), &ctx, &rh);
      if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID || bounce >= s.max_bounces) break;
      bool moved = false;
      const detail::PreparedMesh& m = s.meshes[embree.mesh_of(rh.hit, moved)];
      const detail::vec3 n = m.normals[rh.hit.primID];
      if (!detail::scatter(s.materials[m.material], n, ray.direction, rng)) break;
      auto vertex = [&](int k) {
        const std::uint32_t i = m.indices[3 * rh.hit.primID + k];
        return detail::vec3(m.vertices[3 * i], m.vertices[3 * i + 1], m.vertices[3 * i + 2]);
      };
      const detail::vec3 v0 = vertex(0);
      const detail::vec3 p = v0 + rh.hit.u * (vertex(1) - v0) + rh.hit.v * (vertex(2) - v0);
      ray.origin = detail::offset_ray_origin(p, glm::dot(ray.direction, n) > 0.0f ? n : -n);
    }
  }
  return rays;
}

void BM_RawEmbreePhotonSegments(benchmark::State& state) {
  const Scene& scene = scene_by_index(static_cast<int>(state.range(0)));
  const detail::PreparedScene prepared = detail::prepare(scene);
  const detail::EmbreeScene embree(prepared);
  const std::vector<RTCRay> rays =
      record_photon_segments(prepared, embree, static_cast<std::uint64_t>(state.range(1)));
  std::uint64_t total = 0;
  for (auto _ : state) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 256), [&](auto r) {
      _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
      _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
      RTCIntersectContext ctx;
      rtcInitIntersectContext(&ctx);
      ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        RTCRayHit rh;
        rh.ray = rays[i];
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(embree.handle(), &ctx, &rh);
        benchmark::DoNotOptimize(rh.hit.primID);
      }
    });
    total += rays.size();
  }
  state.counters["rays/s"] = benchmark::Counter(double(total), benchmark::Counter::kIsRate);
}

// Moving one object in a scene (the optimizer's geometry update): an instance transform and a
// top-level rebuild; static geometry is not rebuilt.
void BM_MoveOneMesh(benchmark::State& state) {
  const Scene& scene = scene_by_index(static_cast<int>(state.range(0)));
  Simulation::Options options;
  options.movable_meshes = {scene.meshes[1].name};
  Simulation sim(scene, options);
  double x = 0.0;
  for (auto _ : state) {
    x = x > 0.5 ? 0.0 : x + 0.01;
    sim.set_mesh_transform(1, glm::dmat4(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, x, 0, 0, 1));
  }
}

// Args: {scene (0 Cornell box, 1 ~1M triangles), photons or rays}.
// Rates are per process CPU-second (every worker thread counted): on this shared machine other
// jobs steal wall-clock time, not CPU time, so CPU-normalised rates compare fairly in one run.
BENCHMARK(BM_PhotonTracing)
    ->Args({0, 2'000'000})
    ->Args({1, 2'000'000})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->MinTime(2.0);
BENCHMARK(BM_ScenePrepareAndBuild)
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime();
BENCHMARK(BM_ScenePrepare)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();
BENCHMARK(BM_MoveOneMesh)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();
BENCHMARK(BM_RawEmbreeRandomRays)
    ->Args({0, 4'000'000})
    ->Args({1, 4'000'000})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->MinTime(2.0);
BENCHMARK(BM_RawEmbreePhotonSegments)
    ->Args({0, 1'000'000})
    ->Args({1, 1'000'000})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->MinTime(2.0);

}  // namespace
}  // namespace lightsolver::bench

BENCHMARK_MAIN();
