#pragma once
/// \file result.hpp
/// What an optimisation run reports: the ISOC with its members' estimates, the SIISOC,
/// counters and a per-iteration history. Plain structs, easy to serialise; to_json() gives the
/// documented JSON form (docs/optimization.md).

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lightsolver/optimizer/domain.hpp"
#include "lightsolver/optimizer/intention.hpp"
#include "lightsolver/optimizer/isoc.hpp"
#include "lightsolver/provenance.hpp"
#include "lightsolver/statistics.hpp"

namespace lightsolver::optimizer {

/// One ISOC member.
struct ResultMember {
  Configuration cells;                   ///< cell index per variable
  std::vector<double> values;            ///< cell centre values, same order
  std::uint64_t photons = 0;             ///< photon count of the estimates below
  Estimate objective;                    ///< the estimate the ISOC holds
  std::vector<Estimate> constraints;     ///< same order as Intention::constraints
  std::vector<Feasibility> feasibility;  ///< verdict per constraint at `photons`
};

/// Count of ISOC updates per case, indexed by UpdateCase.
using CaseCounts = std::array<std::uint64_t, 6>;

/// Totals over the run.
struct Counters {
  std::uint64_t iterations = 0;   ///< VNS iterations done (a start's first descent is one)
  std::uint64_t evaluations = 0;  ///< evaluator calls
  std::uint64_t cache_hits = 0;   ///< look-ups answered by the tabu cache
  std::uint64_t photons = 0;      ///< photons requested by all evaluations
  /// photons actually traced: fewer where the evaluator reused traces (a flux change, one
  /// luminaire moved among several)
  std::uint64_t photons_traced = 0;
  std::uint64_t screened_out = 0;   ///< strategy A: dominated at n, never traced with N
  std::uint64_t confirmations = 0;  ///< evaluations with N photons (precise)
  std::uint64_t infeasible = 0;     ///< candidates kept out of the ISOC by their constraints
  std::uint64_t refined = 0;        ///< strategy B: members re-evaluated with N at the end
  /// Strategy B's staged refinement: members traced with the first stage's photons, and those
  /// of them left out of the N traces (beaten by the best with room to spare)
  std::uint64_t refine_stage = 0, refine_dropped = 0;
  std::uint64_t inadmissible = 0;  ///< cells skipped by VnsOptions::admissible
  CaseCounts cases{};              ///< ISOC updates per UpdateCase (refinement included)
  double update_seconds = 0.0;     ///< evaluator: applying configurations to the scene
  double trace_seconds = 0.0;      ///< evaluator: tracing
  double other_seconds = 0.0;      ///< everything else (search, ISOC, callbacks)
  double total_seconds = 0.0;      ///< wall time of the whole run
};

/// Statistics of one VNS iteration, handed to the progress callback.
struct IterationStats {
  std::uint64_t iteration = 0;          ///< 1-based over the whole run
  std::uint32_t start = 0;              ///< 0-based multi-start index
  std::uint32_t k = 0;                  ///< shake radius used (0: the start's first descent)
  double update_seconds = 0.0;          ///< this iteration's scene updates (evaluator-reported)
  double trace_seconds = 0.0;           ///< this iteration's tracing (evaluator-reported)
  double other_seconds = 0.0;           ///< this iteration's wall time minus the two above
  std::uint64_t evaluations = 0;        ///< evaluator calls this iteration
  std::uint64_t photons = 0;            ///< photons requested this iteration
  std::uint64_t total_photons = 0;      ///< photons requested so far
  std::uint64_t total_evaluations = 0;  ///< evaluator calls so far
  double elapsed_seconds = 0.0;         ///< wall time since the run began
  std::size_t isoc_size = 0;            ///< after the iteration
  Interval siisoc{};                    ///< after the iteration (meaningless when isoc_size = 0)
  bool has_best = false;                ///< false while the ISOC is empty
  Estimate best{};                      ///< the ISOC member with the best mean
};

/// Why the run stopped.
enum class StopReason {
  kIterationLimit,   ///< max_iterations reached
  kEvaluationLimit,  ///< max_evaluations reached
  kExhausted,        ///< every cell of the grid has been evaluated
  kCancelled,        ///< cancel flag set or progress callback returned false
};

const char* to_string(StopReason r);

/// Next-event estimation in a scene search (docs/optimization.md, "Next-event estimation"):
/// the setting the evaluations followed and whether direct light came from shadow rays.
struct NextEventUse {
  std::string setting = "off";  ///< "auto", "on" or "off"
  bool direct = false;          ///< some evaluation had direct parts (next_event_direct)
  std::string reason;           ///< why not, when `direct` is false
};

/// The outcome of optimize().
struct OptimizationResult {
  Goal goal = Goal::kMaximize;
  double confidence = 0.95;
  std::vector<std::string> variable_names;
  std::vector<ResultMember> isoc;  ///< best mean first; ties by cell index
  Interval siisoc{};               ///< of the final ISOC (meaningless when it is empty)
  Counters counters;
  StopReason stop = StopReason::kIterationLimit;
  std::vector<IterationStats> history;  ///< one entry per iteration (if requested)
  /// Where the search comes from (run_problem() sets it; the engine alone does not).
  std::optional<Provenance> provenance;
  /// Scene searches (run_problem() sets it): next-event estimation as the evaluations had it.
  std::optional<NextEventUse> next_event;
};

/// JSON text ("lightsolver.optimization/1", described in docs/optimization.md).
std::string to_json(const OptimizationResult& r, int indent = 2);

}  // namespace lightsolver::optimizer
