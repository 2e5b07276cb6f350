#include "run/replicate_run.hpp"

#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <string>
#include <vector>

#include "lightsolver/error.hpp"
#include "lightsolver/process_group.hpp"
#include "model/groups.hpp"
#include "model/sobol.hpp"
#include "shared/philox.h"

namespace lightsolver::detail {
namespace {

// Refuses a sobol run for `reason` (the option that cannot go with it).
[[noreturn]] void refuse(const std::string& field, const std::string& reason) {
  throw InputError("", field, "sampler \"sobol\" " + reason);
}

// Keeps the backend quasi-random while it lives, whatever leaves the scope.
struct QuasiRandom {
  Backend& backend;
  explicit QuasiRandom(Backend& b) : backend(b) { backend.set_quasi_random(true); }
  ~QuasiRandom() { backend.set_quasi_random(false); }
  QuasiRandom(const QuasiRandom&) = delete;
  QuasiRandom& operator=(const QuasiRandom&) = delete;
};

}  // namespace

std::optional<ReplicatePlan> plan_replicates(const Scene& scene, const SolveOptions& options,
                                             const Results& r, bool resume,
                                             const Backend& backend) {
  (void)scene;
  if (options.sampler == "random") return std::nullopt;
  if (options.sampler != "sobol") {
    throw InputError("", "sampler",
                     "must be \"random\" or \"sobol\" (got \"" + options.sampler + "\")");
  }
  if (!backend.traces_quasi_random()) {
    refuse("sampler", "needs the embree backend (this run's is " + backend.name() + ")");
  }
  if (resume) refuse("sampler", "cannot refine(): each replicate is a prefix of its own points");
  if (r.target_accuracy) refuse("target_accuracy", "traces a fixed photon count: no accuracy goal");
  if (r.decide) refuse("decide", "traces a fixed photon count: no decide run");
  if (r.max_seconds) refuse("max_seconds", "traces a fixed photon count: no time limit");
  if (r.contributions) {
    refuse("contributions", "has no per-path tallies for a rescale: no contributions");
  }
  if (!options.checkpoints.empty()) refuse("sampler", "is not for cost or study runs");
  if (options.processes && options.processes->size() > 1) {
    refuse("sampler", "runs in one process (no MPI)");
  }
  if (options.replicates < 2 || options.replicates > 1024) {
    throw InputError("", "replicates",
                     "must lie in [2, 1024] (got " + std::to_string(options.replicates) + ")");
  }
  ReplicatePlan plan{options.replicates, r.photons_requested / options.replicates};
  if (plan.per_replicate * plan.replicates != r.photons_requested || plan.per_replicate == 0) {
    refuse("photons", "splits the photons evenly: " + std::to_string(r.photons_requested) +
                          " is not a positive multiple of the " + std::to_string(plan.replicates) +
                          " replicates");
  }
  if (plan.per_replicate > kMaxSobolPoints) {
    refuse("photons", "has at most 2^32 photons per replicate");
  }
  return plan;
}

std::uint64_t replicate_seed(std::uint64_t seed, std::uint32_t replicate) {
  // Philox keyed by the run's seed at a counter no path uses (block 2^32 - 2).
  const glm::uvec2 key(static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32));
  const glm::uvec4 b =
      shared::philox4x32_10(glm::uvec4(replicate, 0x51ed0u, 0xFFFFFFFEu, 0xFFFFFFFFu), key);
  return (std::uint64_t(b.y) << 32) | b.x;
}

double trace_replicates(const ReplicatePlan& plan, const PreparedScene& prepared, Backend& backend,
                        int threads, const SolveOptions& options, const ProgressFn& progress,
                        TallyBlock& tallies, Results& r) {
  const auto start = std::chrono::steady_clock::now();
  const std::size_t block = prepared.groups.size() * prepared.bins.size();
  std::vector<TallyBlock> parts(plan.replicates, TallyBlock(block));
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  QuasiRandom quasi_random(backend);
  r.sampler = "sobol";
  r.replicates = plan.replicates;
  r.stop_reason = kStopPhotons;
  // Rounds double from 2^12 photons per replicate up to 2^20: progress and cancel points.
  std::uint64_t done = 0;
  while (done < plan.per_replicate) {
    const std::uint64_t n =
        std::min(std::clamp<std::uint64_t>(done, 1u << 12, 1u << 20), plan.per_replicate - done);
    const auto ranges = group_ranges(prepared.groups, done, n);
    for (std::uint32_t k = 0; k < plan.replicates; ++k) {
      arena.execute([&] { backend.trace(ranges, replicate_seed(r.seed, k), parts[k]); });
    }
    done += n;
    r.photons = done * plan.replicates;
    const bool cancelled = (options.cancel && options.cancel->load()) ||
                           (progress && !progress(r.photons, r.photons_requested));
    if (cancelled && done < plan.per_replicate) {
      r.stop_reason = kStopCancelled;
      break;
    }
  }
  for (std::uint32_t k = 0; k < plan.replicates; ++k) {
    TallyBlock& p = parts[k];
    std::copy(p.bins.begin(), p.bins.end(), tallies.bins.begin() + k * block);
    tallies.add_counts(p);
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace lightsolver::detail
