#pragma once
/// \file vns.hpp
/// Variable Neighbourhood Search (Mladenović & Hansen 1997) over a discretised domain, with the
/// ISOC of Sec. III-C, the tabu cache of Sec. IV-B and the adaptive photon counts of Sec. IV-A.
///
/// Usage:
///   Domain d;  d.add_rectangle("lum0", 0, 6, 24, 0, 4, 16);
///   Intention in = maximize_mean_illuminance("podium");
///   MyEvaluator ev(scene, in);                 // implements Evaluator
///   VnsOptions opt;  opt.seed = 7;  opt.max_iterations = 500;
///   OptimizationResult r = optimize(d, in, ev, opt);

#include <atomic>
#include <cstdint>
#include <functional>
#include <vector>

#include "lightsolver/optimizer/domain.hpp"
#include "lightsolver/optimizer/evaluator.hpp"
#include "lightsolver/optimizer/intention.hpp"
#include "lightsolver/optimizer/result.hpp"

namespace lightsolver::optimizer {

/// How photon counts are chosen (Sec. IV-A). Either way a cell is traced at most once per level.
enum class PhotonStrategy {
  /// A: every candidate is traced with n photons; only if its CI is not dominated by the
  /// ISOC (it reaches or beats the SIISOC) is it traced again with N, and the N estimate is
  /// what the ISOC sees. The ISOC holds N estimates only.
  kConfirm,
  /// B: the search runs on n-photon estimates; at the end every ISOC member is traced with N
  /// and the ISOC is rebuilt from those estimates.
  kRefineAtEnd,
};

/// Local search rule over the distance-1 neighbourhood.
enum class LocalSearch {
  kFirstImprovement,  ///< move to the first improving neighbour (random order from the seed)
  kBestImprovement,   ///< trace every neighbour, move to the best
};

/// What to do with a candidate whose constraints are still "uncertain" with N photons.
enum class UncertainPolicy {
  kReject,  ///< default: a reported member meets every constraint at the run's confidence
  kAccept,  ///< keep it (its verdicts say "uncertain" in the result)
};

/// Settings of a run. Defaults follow the paper where it gives numbers.
struct VnsOptions {
  std::uint64_t seed = 1;    ///< search randomness and evaluation seeds derive from it
  double confidence = 0.95;  ///< level of the =α comparisons and feasibility verdicts
  std::uint64_t screening_photons = 32768;       ///< n (0 or >= N: always trace with N)
  std::uint64_t confirmation_photons = 2097152;  ///< N (paper: 2.66e6)
  PhotonStrategy strategy = PhotonStrategy::kConfirm;
  /// Strategy B's end refinement in stages (docs/optimization.md §6, "Staged refinement"):
  /// every member is first traced with this many photons N1 of its N-photon stream, continued
  /// to 2 N1, 4 N1, ... below N and to N only while the best member might not beat it; 0 (or
  /// >= N): every member with N at once, as the paper refines. The final ISOC equals the
  /// unstaged one except with probability at most 1 - confidence.
  std::uint64_t refine_stage_photons = 0;
  UncertainPolicy uncertain = UncertainPolicy::kReject;
  std::uint64_t max_iterations = 1000;  ///< over all starts (paper: 1000)
  std::uint64_t max_evaluations = 0;    ///< evaluator calls; 0 = no limit
  std::uint32_t starts = 1;             ///< multi-start: the iteration budget is shared evenly
  std::vector<Configuration> initial;   ///< starting cells for the first starts; others random
  std::uint32_t kmax = 0;  ///< largest shake radius; 0 = largest variable size − 1 (whole grid)
  LocalSearch local_search = LocalSearch::kFirstImprovement;
  Neighbourhood neighbourhood = Neighbourhood::kAxis;
  bool keep_history = true;  ///< fill OptimizationResult::history
  /// Optional filter: cells for which it returns false are never traced nor admitted (a
  /// non-rectangular placement face on its bounding grid, or lum0 <= lum1 to skip mirror
  /// images of interchangeable luminaires). Must be deterministic; initial cells must pass.
  std::function<bool(const Configuration&)> admissible;
  /// Optional: called once, with the cell about to be traced, before the first trace with N
  /// (strategy A's first confirmation, strategy B's refinement with the best n-level member,
  /// or the first visit under a static N); N and refine_stage_photons are scaled by what it
  /// returns, clamped to (0, 1] (docs/optimization.md §6, "Equal widths").
  std::function<double(std::uint64_t cell)> confirmation_factor;
};

/// Observation and cancellation. The callback runs after every iteration on the calling
/// thread; returning false stops the run (StopReason::kCancelled). The flag is polled before
/// every evaluation, so a cancel takes effect within one trace.
struct Control {
  std::function<bool(const IterationStats&)> progress;
  const std::atomic<bool>* cancel = nullptr;
  /// Called after every ISOC update (refinement included) with the candidate's cells, the
  /// photon count of the estimate offered and what the update did: for logs and debugging.
  std::function<void(const Configuration&, std::uint64_t, const IsocUpdate&)> on_update;
  /// Called after every evaluator call (one trace) with the run so far: `iteration` is the
  /// number of iterations completed, `evaluations`/`photons` those of the iteration under way,
  /// `total_evaluations`, `total_photons`, `elapsed_seconds`, the ISOC's size and best. An
  /// iteration's local search may trace many cells, so this is what lets a caller show
  /// progress (and a time estimate) within one trace of the start. False stops the run.
  std::function<bool(const IterationStats&)> on_evaluation;
};

/// Runs the search. Throws std::invalid_argument on bad options (confidence outside (0, 1),
/// N = 0, starts = 0, an initial configuration outside the domain or not admissible, no
/// admissible cell at all, an empty domain) and
/// whatever the evaluator throws. A cancelled run still returns the ISOC found so far
/// (under strategy B it skips the refinement, and says so by StopReason::kCancelled).
OptimizationResult optimize(const Domain& domain, const Intention& intention, Evaluator& evaluator,
                            const VnsOptions& options, const Control& control = {});

}  // namespace lightsolver::optimizer
