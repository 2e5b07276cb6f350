// The Embree backend's specialised path kernel (embree/path_kernel.hpp, picked by the scene
// analysis) against its general kernel (every effect compiled in), photons per process
// CPU-second, on example scenes, in one run with the two interleaved at random (ratios only
// mean something within one run on this noisy shared machine). Results go to
// docs/BENCHMARKS.md, "Specialised path kernels".
#include <benchmark/benchmark.h>

#include <string>

#include "bench_scenes.hpp"
#include "bench_util.hpp"
#include "model/prepared_scene.hpp"
#include "embree/embree_backend.hpp"
#include "lightsolver/scene_io.hpp"

namespace lightsolver::bench {
namespace {

// 0: an all-diffuse office (conference room); 1: a Cornell box with a glass lens and a mirror;
// 2: the office with every reflectance 0 (direct light only); 3: the 1M-triangle hall of
// solver_bench with every reflectance 0 (direct light only, a grid target: no hit reads its
// triangle).
Scene black(Scene s) {
  for (Material& m : s.materials) m.reflectance = 0.0;
  return s;
}

const Scene& scene_by_index(int i) {
  static const std::string root = LIGHTSOLVER_SOURCE_DIR "/Examples/optimization/";
  static const Scene office = load_scene(root + "conference/conference.json");
  static const Scene cornell = load_scene(root + "cornell/cornell.json");
  static const Scene black_office = black(office);
  if (i == 3) {
    static const Scene black_hall = black(million_triangles());
    return black_hall;
  }
  return i == 0 ? office : i == 1 ? cornell : black_office;
}

void BM_PathKernel(benchmark::State& state) {
  const Scene& scene = scene_by_index(static_cast<int>(state.range(0)));
  const detail::PreparedScene prepared = detail::prepare(scene);
  const auto kernel =
      state.range(1) == 0 ? detail::EmbreeKernel::Specialised : detail::EmbreeKernel::General;
  auto backend = detail::make_embree_backend(prepared, kernel);
  measure_tracing(state, *backend, prepared.bins.size(),
                  static_cast<std::uint64_t>(state.range(2)));
}

}  // namespace

BENCHMARK(BM_PathKernel)
    ->ArgNames({"scene", "general", "photons"})
    ->Args({0, 0, 1'000'000})
    ->Args({0, 1, 1'000'000})
    ->Args({1, 0, 1'000'000})
    ->Args({1, 1, 1'000'000})
    ->Args({2, 0, 2'000'000})
    ->Args({2, 1, 2'000'000})
    ->Args({3, 0, 2'000'000})
    ->Args({3, 1, 2'000'000})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->MinTime(2.0);

}  // namespace lightsolver::bench

BENCHMARK_MAIN();
