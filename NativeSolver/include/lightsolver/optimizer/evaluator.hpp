#pragma once
/// \file evaluator.hpp
/// The engine's only view of the world: something that estimates an intention's metrics for
/// a configuration with a given number of photons and seed. The scene integration implements
/// it (apply the configuration to the scene, trace, reduce tallies to Estimates); the tests
/// implement it with synthetic functions.

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <unordered_map>
#include <vector>

#include "lightsolver/optimizer/domain.hpp"
#include "lightsolver/statistics.hpp"

namespace lightsolver::optimizer {

/// What the engine asks for. References are valid for the duration of the call only.
struct EvaluationRequest {
  const Configuration& cells;         ///< one cell index per variable
  const std::vector<double>& values;  ///< the cells' centre values, same order
  std::uint64_t cell_index;           ///< Domain::index(cells)
  std::uint64_t photons;              ///< photon paths to trace
  std::uint64_t seed;                 ///< evaluation_seed(run seed, cell_index, photons)
  /// The run's seed: an evaluator that traces parts of a configuration apart (SceneEvaluator's
  /// reused group traces) seeds each part with evaluation_seed(run_seed, part's index, photons).
  std::uint64_t run_seed = 0;
  /// The photon level whose seeds this trace uses (0: `photons`'s own). A trace of fewer photons
  /// than that level with its seeds is the first part of the level's trace (photon i is photon
  /// i): the staged refinement's stages, which an evaluator may later continue instead of
  /// tracing those photons again (docs/optimization.md §6, "Staged refinement"). The level's
  /// estimate must continue this one's: anything not traced photon by photon (a direct part)
  /// is the level's own, so that E_level - E_this has sigma_this sqrt(1 - photons / level) for
  /// a mean illuminance.
  std::uint64_t seed_photons = 0;
};

/// What the evaluator returns. Estimates use the run's confidence level for their CIs.
struct Evaluation {
  Estimate objective;
  std::vector<Estimate> constraints;  ///< one per Intention::constraints, same order
  double update_seconds = 0.0;        ///< time spent applying the configuration to the scene
  double trace_seconds = 0.0;         ///< time spent tracing photons
  /// Photons actually traced, where an evaluator reused traces (fewer than requested); unset:
  /// the request's photons.
  std::optional<std::uint64_t> photons_traced;
};

/// Interface the scene integration implements. evaluate() is called from one thread at a
/// time; it may parallelise internally. Results must depend only on the request.
class Evaluator {
 public:
  virtual ~Evaluator() = default;
  virtual Evaluation evaluate(const EvaluationRequest& request) = 0;
};

/// Adapter for a callable (tests, quick experiments).
class FunctionEvaluator final : public Evaluator {
 public:
  using Function = std::function<Evaluation(const EvaluationRequest&)>;
  explicit FunctionEvaluator(Function f) : f_(std::move(f)) {}
  Evaluation evaluate(const EvaluationRequest& request) override { return f_(request); }

 private:
  Function f_;
};

/// Seed for one evaluation: a SplitMix64 hash of (run seed, cell index, photon count). The
/// same cell at the same photon level always gets the same seed, so an estimate does not
/// depend on when or how often the search visits the cell; two levels get independent seeds.
std::uint64_t evaluation_seed(std::uint64_t run_seed, std::uint64_t cell_index,
                              std::uint64_t photons);

/// The tabu cache of Sec. IV-B: one evaluation per (cell, photon level). Pointers returned stay
/// valid until the cache is destroyed.
class TabuCache {
 public:
  /// The stored evaluation, or nullptr.
  const Evaluation* find(std::uint64_t cell, std::uint64_t photons) const;
  /// The evaluation with the most photons stored for this cell, or nullptr.
  const Evaluation* most_precise(std::uint64_t cell) const;
  /// Photon count of most_precise(cell), 0 when none.
  std::uint64_t most_photons(std::uint64_t cell) const;
  /// Stores an evaluation; throws std::logic_error if (cell, photons) is already present.
  const Evaluation& insert(std::uint64_t cell, std::uint64_t photons, Evaluation e);
  /// Distinct cells with at least one evaluation.
  std::size_t cells() const { return map_.size(); }
  /// Stored (cell, photons) pairs.
  std::size_t entries() const { return entries_; }

 private:
  std::unordered_map<std::uint64_t, std::map<std::uint64_t, Evaluation>> map_;
  std::size_t entries_ = 0;
};

}  // namespace lightsolver::optimizer
