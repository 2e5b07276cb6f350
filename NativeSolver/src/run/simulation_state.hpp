#pragma once
// What a Simulation keeps between runs (simulation.cpp runs, simulation_groups.cpp traces one
// group at a time for the optimizer).
#include <cstdint>
#include <memory>
#include <optional>

#include "model/backend.hpp"
#include "lightsolver/scene.hpp"

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
  // The last run's direct parts (next-event estimation), for the next run with the same seed
  // and points; dropped by any change to the scene.
  std::vector<DirectPart> direct;
  std::optional<std::uint64_t> direct_seed;
  std::uint32_t direct_strata_scale = 0;
  std::uint64_t direct_connect_paths = 0;  // their connected reflected light's paths (0: none)
};

}  // namespace lightsolver::detail
