#pragma once
/// \file simulation.hpp
/// A scene kept ready for many runs with small changes in between: the optimizer's inner loop,
/// or a parametric script. The acceleration structure is built once; changing a luminaire
/// costs nothing; moving a mesh declared movable is an instance transform update, not a
/// rebuild.

#include <glm/mat4x4.hpp>
#include <memory>
#include <string>
#include <vector>

#include "lightsolver/solver.hpp"

namespace lightsolver {

namespace detail {
struct SimulationState;
}

class Simulation {
 public:
  struct Options {
    std::string backend = "auto";
    int threads = 0;                          ///< 0: all cores
    std::vector<std::string> movable_meshes;  ///< meshes that set_mesh_transform() may move
  };

  /// Validates and prepares the scene and builds the backend. Throws InputError.
  Simulation(Scene scene, Options options);
  Simulation(Scene scene) : Simulation(std::move(scene), Options{}) {}
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  /// The scene as it stands (with every change applied).
  const Scene& scene() const;

  /// Replaces luminaire `index` (same or other type); validated like a loaded one.
  void set_luminaire(std::size_t index, const Luminaire& luminaire);

  /// Places movable mesh `mesh` with a rigid world transform (rotation + translation) applied
  /// to its coordinates as loaded. Throws InputError for a non-rigid matrix or a mesh that was
  /// not declared movable.
  void set_mesh_transform(std::size_t mesh, const glm::dmat4& world_transform);

  /// Traces photons (settings and overrides as in solve()). The run's tallies are kept for
  /// refine().
  Results run(const SolveOptions& options = {}, const ProgressFn& progress = {});

  /// Continues the previous run up to `options.photons` photons in all (photon i is photon i:
  /// equal, bit for bit, to one run() of that many photons with the same seed). Starts at photon
  /// 0 when nothing is kept: no run yet, a change since (set_luminaire, set_mesh_transform),
  /// another seed, or a kept run that already has more photons. Throws InputError without
  /// `options.photons` or with decide (its looks are counted from photon 0).
  Results refine(const SolveOptions& options, const ProgressFn& progress = {});

  /// Photons of the kept tallies refine() continues from (0 when nothing is kept).
  std::uint64_t kept_photons() const;

  /// Seconds spent applying changes since the previous run (reported, then reset, by run()).
  double pending_update_seconds() const;

 private:
  Results run_from(const SolveOptions& options, const ProgressFn& progress, bool resume);
  std::unique_ptr<detail::SimulationState> state_;
};

}  // namespace lightsolver
