#pragma once
// What a Simulation keeps between runs (simulation.cpp runs, simulation_groups.cpp traces one
// group at a time for the optimizer).
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>

#include "lightsolver/scene.hpp"
#include "lightsolver/solver.hpp"
#include "model/backend.hpp"

namespace lightsolver::detail {

struct SimulationState {
  Scene scene;
  PreparedScene prepared;
  std::unique_ptr<Backend> backend;
  int threads = 0;
  double pending_update_seconds = 0.0;
  Warnings backend_notes;  // e.g. why "auto" fell back to the CPU
  // The last run's tallies, for refine(); dropped by any change to the scene.
  std::optional<TallyBlock> kept;
  std::uint64_t kept_photons = 0, kept_seed = 0;
  // The targets whose direct light the kept tallies' photons deposited (direct_by_photons).
  std::vector<bool> kept_by_photons;
  // The last run's direct parts (next-event estimation), for the next run with the same seed
  // and points; dropped by any change to the scene.
  std::vector<DirectPart> direct;
  std::optional<std::uint64_t> direct_seed;
  std::uint32_t direct_strata_scale = 0;
  std::vector<bool> direct_by_photons;  // the targets `direct` left to the photons (zero parts)
  double direct_seconds = 0.0;          // the time `direct` took to trace
  // The strata scale the current run's parts end at (0: none, or fixed by an accuracy goal).
  std::uint32_t direct_final_scale = 0;
  // Connected reflected light (estimate/reflection_connection.hpp), kept apart from `direct`
  // (whose strata change between the coarse and the planned parts) and added to it in use:
  // its paths and seed (the last whole connection traced, kept for the next run), the paths the
  // run uses now (0: none) and the paths a plain run plans after its photons (0: none, or fixed
  // before them by an accuracy goal or deciding), and the time the connection took.
  std::vector<DirectPart> connected;
  std::uint64_t connected_paths = 0;
  std::optional<std::uint64_t> connected_seed;
  std::uint64_t connect_paths = 0;
  std::uint64_t connect_final = 0;
  double connected_seconds = 0.0;
  // Why an accuracy goal's connection stopped short of its paths (a device limit cut the next
  // ones); the run's warnings carry it. Empty when it did not.
  std::string connect_note;
  // next_event "auto"'s judging parts (estimate/direct_choice.hpp) and their seed; dropped with
  // `direct` by any change to the scene.
  std::vector<DirectPart> judging;
  std::optional<std::uint64_t> judging_seed;
};

/// next_event "auto": gives the targets where shadow rays would be wider back to the photons,
/// judged for a run of `r` (its seed, photons, accuracy goal) from judging parts traced once per
/// seed (run/next_event_plan.cpp). False when none is left to the shadow rays or the judging was
/// stopped: then no group has next-event estimation and PreparedScene::next_event_off says why.
bool judge_direct_targets(SimulationState& st, const Results& r, const std::function<bool()>& stop);

}  // namespace lightsolver::detail
