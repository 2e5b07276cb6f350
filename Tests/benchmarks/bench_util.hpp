#pragma once
// Shared measuring loop of the benchmark programs.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>

#include "model/backend.hpp"

namespace lightsolver::bench {

// Traces `n` photons per benchmark iteration (scene prepared and backend built beforehand) and
// reports photons/s, segments/s and segments per photon.
inline void measure_tracing(benchmark::State& state, detail::Backend& backend, std::size_t bins,
                            std::uint64_t n) {
  std::uint64_t photons = 0, segments = 0, seed = 1;
  for (auto _ : state) {
    detail::TallyBlock tallies(bins);
    backend.trace({{0, 0, n}}, seed++, tallies);  // the first group's photons
    photons += n;
    segments += tallies.ray_segments;
  }
  state.counters["photons/s"] = benchmark::Counter(double(photons), benchmark::Counter::kIsRate);
  state.counters["segments/s"] = benchmark::Counter(double(segments), benchmark::Counter::kIsRate);
  state.counters["segments/photon"] =
      double(segments) / double(std::max<std::uint64_t>(photons, 1));
}

}  // namespace lightsolver::bench
