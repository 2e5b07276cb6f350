#pragma once
// A quasi-random run (SolveOptions::sampler "sobol"; docs/statistics.md, "Quasi-random
// photons"): R replicates, each the first photons / R Sobol' points of every group's stream
// under its own scramble seed, traced into its own groups x bins block. The blocks lie end to
// end in one TallyBlock, which GroupedTallies reads as replicates (model/groups.hpp).
#include <cstdint>
#include <optional>

#include "lightsolver/scene.hpp"
#include "lightsolver/solver.hpp"
#include "model/backend.hpp"

namespace lightsolver::detail {

struct ReplicatePlan {
  std::uint32_t replicates = 0;
  std::uint64_t per_replicate = 0;  // photons of each replicate
};

/// The replicates of a run whose plan is in `r` (photons, time limit, decide, accuracy,
/// contributions set), or nothing for sampler "random". InputError naming `sampler` (or
/// `photons`, `replicates`) where a sobol run cannot be: another backend, an accuracy goal,
/// decide, a time limit, contributions, checkpoints (cost, study), several processes, refine,
/// a photon count that is not a multiple of the replicates or above 2^32 per replicate.
std::optional<ReplicatePlan> plan_replicates(const Scene& scene, const SolveOptions& options,
                                             const Results& r, bool resume, const Backend& backend);

/// Replicate r's seed: its scramble and Philox key, independent of every other replicate's.
std::uint64_t replicate_seed(std::uint64_t seed, std::uint32_t replicate);

/// Traces the plan's replicates into `tallies` (replicates x groups x bins, zero), in rounds
/// that give every replicate the same photons, so a cancelled run stops between rounds with
/// equal replicates. Sets r.photons, r.stop_reason, r.sampler, r.replicates; returns the
/// seconds spent tracing.
double trace_replicates(const ReplicatePlan& plan, const PreparedScene& prepared, Backend& backend,
                        int threads, const SolveOptions& options, const ProgressFn& progress,
                        TallyBlock& tallies, Results& r);

}  // namespace lightsolver::detail
