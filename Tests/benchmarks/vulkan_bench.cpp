// Photon throughput of the Vulkan backend next to Embree on the same scenes, in one run (ratios
// only mean something within one run on a shared machine). Without a GPU this measures lavapipe,
// Mesa's CPU implementation: a correctness backend, expected to be much slower than Embree.
#include <benchmark/benchmark.h>

#include "bench_scenes.hpp"
#include "bench_util.hpp"
#include "model/backend.hpp"
#include "model/prepared_scene.hpp"
#include "embree/embree_backend.hpp"
#include "vulkan/vulkan_backend.hpp"

namespace lightsolver::bench {
namespace {

const Scene& scene_by_index(int i) {
  static const Scene cornell = cornell_box();
  static const Scene million = million_triangles();
  return i == 0 ? cornell : million;
}

// Tracing only: scene prepared, BVH built and pipeline compiled outside the timed loop.
void trace_rate(benchmark::State& state, bool vulkan) {
  const Scene& scene = scene_by_index(static_cast<int>(state.range(0)));
  const detail::PreparedScene prepared = detail::prepare(scene);
  auto backend =
      vulkan ? detail::make_vulkan_backend(prepared) : detail::make_embree_backend(prepared);
  measure_tracing(state, *backend, prepared.bins.size(),
                  static_cast<std::uint64_t>(state.range(1)));
}

void BM_Embree(benchmark::State& state) { trace_rate(state, false); }
void BM_Vulkan(benchmark::State& state) { trace_rate(state, true); }

// Scene 0: Cornell box; 1: ~1M triangles. Wall time: Vulkan work runs outside this thread.
BENCHMARK(BM_Embree)
    ->Args({0, 1 << 18})
    ->Args({1, 1 << 16})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Vulkan)
    ->Args({0, 1 << 18})
    ->Args({1, 1 << 16})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace lightsolver::bench

BENCHMARK_MAIN();
