#pragma once
/// \file cost.hpp
/// What accuracy costs in time (`lightsolver cost`, Python `lightsolver.cost`): ONE run with
/// checkpoints at 10^4 photons, then 4x each (each halves the interval), so a row's photons are
/// the first photons of the next row and nothing is traced twice; then the photons and seconds
/// each accuracy goal (kCostGoals) needs, extrapolated from the last row by the rule the
/// solver's own forecast uses (accuracy_cost). `lightsolver study` is its detailed sibling.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "lightsolver/solver.hpp"

namespace lightsolver {

struct CostOptions {
  /// seed, confidence, threads, backend, cancel, processes; photons and checkpoints are set here
  SolveOptions solve;
  std::uint64_t max_photons = 16'000'000;  ///< the run's photons: the last row at or below it
};

/// One accuracy goal's cost, from the last row.
struct CostGoal {
  double accuracy = 0.0;  ///< relative CI half-width (kCostGoals)
  AccuracyCost need;      ///< infinite photons while a target has no hit
};

struct Cost {
  /// One per checkpoint reached: photons, tracing seconds, worst relative half-width (the
  /// per-target results are not kept).
  std::vector<Checkpoint> rows;
  std::vector<CostGoal> goals;   ///< kCostGoals, from the last row; empty without rows
  double prepare_seconds = 0.0;  ///< building the scene once, before tracing
  Results results;               ///< the run (its photons are the last row's)
};

/// Throws InputError(where) when `max_photons` gives no row (below 10^4).
void check_cost_photons(std::uint64_t max_photons, const std::string& where);

/// Runs `cost`. `on_row` is called as each checkpoint is reached (e.g. to print it). Throws
/// InputError for bad options (naming `max_photons` for too few photons).
Cost run_cost(const Scene& scene, const CostOptions& options,
              const std::function<void(const Checkpoint&)>& on_row = {});

}  // namespace lightsolver
