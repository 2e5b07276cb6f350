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
};

}  // namespace lightsolver::detail
