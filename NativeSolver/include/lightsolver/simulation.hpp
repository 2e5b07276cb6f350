#pragma once
/// \file simulation.hpp
/// A scene kept ready for many runs with small changes in between: the optimizer's inner loop,
/// or a parametric script. The acceleration structure is built once; changing a luminaire
/// costs nothing; moving a mesh declared movable is an instance transform update, not a
/// rebuild.

#include <chrono>
#include <functional>
#include <glm/mat4x4.hpp>
#include <memory>
#include <string>
#include <vector>

#include "lightsolver/solver.hpp"

namespace lightsolver {

namespace detail {
struct SimulationState;
}

/// A luminaire group as the simulation holds it (the scene's `group` keys, docs/statistics.md
/// "Groups"): its own photon stream and tallies.
struct LuminaireGroup {
  std::string name;
  std::vector<std::size_t> luminaires;  ///< indices into scene().luminaires
  double flux_lm = 0.0;                 ///< emitted as the scene stands (photometric tilt included)
};

/// One group's tallies, traced alone by Simulation::trace_group and summed into results by
/// Simulation::combine: the optimizer re-traces only the groups a configuration changes.
struct GroupTrace {
  std::size_t group = 0;
  std::uint64_t run_photons = 0;  ///< the run whose share of photons this group traced
  std::uint64_t photons = 0;      ///< this group's share of them
  std::uint64_t seed = 0;
  std::vector<Tally> bins;  ///< one per tally bin of the scene (layout internal)
  /// Next-event estimation, as the scene's `settings.next_event` plans it for this group: its
  /// direct light per bin (same layout as `bins`) by shadow rays, at `flux_lm`; its photons
  /// then tally only light scattered at least once. Empty: the photons carry all its light,
  /// and `next_event_off` says why.
  std::vector<DirectLight> direct;
  double flux_lm = 0.0;  ///< the group's flux as traced (direct parts scale with it)
  bool photons_reflect =
      true;  ///< false: nothing returns light (a direct group's photon part is 0)
  std::uint64_t shadow_rays = 0;  ///< traced for `direct` (at most)
  std::string next_event_off;     ///< why `direct` is empty
  std::uint64_t ray_segments = 0, capped_paths = 0, cut_paths = 0;
  OpeningCounts openings;  ///< daylight photons blocked outside their openings
  /// When it was traced and by how many processes (the combined results' provenance).
  std::chrono::system_clock::time_point started{}, finished{};
  int mpi_ranks = 1;
};

class Simulation {
 public:
  struct Options {
    std::string backend = "auto";
    int threads = 0;                          ///< 0: all cores
    std::vector<std::string> movable_meshes;  ///< meshes that set_mesh_transform() may move
    /// The scene comes from load_scene() or validate() with its meshes unchanged: their
    /// vertices and triangles are not checked again (the rest is).
    bool scene_validated = false;
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

  /// The backend that traces ("embree", "vulkan") and its device, as the backend reports it.
  std::string backend_name() const;
  std::string device() const;

  /// The luminaire groups, in the order of their first luminaire in the scene.
  std::vector<LuminaireGroup> groups() const;

  /// Shares a run's photons among the groups by these weights (one per group, >= 0, e.g. each
  /// group's largest flux over a search) instead of by their fluxes now: a group's photons then
  /// stay the same when another group's flux changes, so its trace can be reused. Empty: by flux
  /// again. Throws InputError for a wrong count or a negative or non-finite weight.
  void fix_photon_shares(const std::vector<double>& weights);

  /// Traces group `group` alone, as the scene stands: its share of a run of `run_photons`
  /// photons with `seed`, and its direct parts where the scene's `settings.next_event` plans
  /// them (points sized to the run as run() sizes them). Equal, bit for bit, to that group's
  /// tallies and direct parts in run() with the same photons and seed (and no accuracy goal or
  /// decide). `processes`: MPI ranks sharing the trace (null: alone). `prefix`: this group's
  /// trace with the same seed and at most `run_photons`, made with the scene as it stands: its
  /// photons are this trace's first ones, so only the rest are traced (the result is the trace
  /// from photon 0, bit for bit). Throws InputError for an unknown group or one without flux,
  /// for next_event "on" where no group can have it, and std::invalid_argument for a prefix of
  /// another group, seed, next-event plan or a larger run. `direct_run_photons` (0: run_photons)
  /// sizes the direct parts for a run of that many photons instead: a trace of the first photons
  /// of a larger run (the optimizer's staged refinement) then has that run's direct parts, which
  /// its continuation keeps, so the larger trace's estimate continues this one's.
  GroupTrace trace_group(std::size_t group, std::uint64_t run_photons, std::uint64_t seed,
                         const std::shared_ptr<ProcessGroup>& processes = nullptr,
                         const GroupTrace* prefix = nullptr, std::uint64_t direct_run_photons = 0);

  /// Results from groups traced apart: `traces[g]` for group g (null: the group is dark, and
  /// its flux must be 0) and
  /// `flux_lm[g]` the flux each group emits now (its traced tallies are scaled to it: light is
  /// linear in a group's flux). Combining the traces of every group made with one seed equals
  /// run() with it, bit for bit, in every estimate. The results record each group's factor
  /// against the scene as it stands in `rescaled` (as a rescale does: flux_lm[g] / the group's
  /// flux; 0 for a dark group) and a provenance as run() does: the scene's source (none after
  /// a change in memory), the traces' photons, processes, times and the simulation's backend,
  /// device and threads; its `seed` option is null when the traces have different seeds.
  /// Direct parts (GroupTrace::direct) are scaled by flux_lm[g] / the trace's flux and added to
  /// the photons' estimates as run() adds them; `next_event` is the scene's setting and the
  /// effects list says whether any group had direct parts (next_event_direct).
  /// Throws std::invalid_argument when the traces do not fit the scene.
  Results combine(const std::vector<const GroupTrace*>& traces, const std::vector<double>& flux_lm,
                  double confidence) const;

 private:
  Provenance combined_provenance(const std::vector<const GroupTrace*>& traces,
                                 const Results& r) const;
  Results run_from(const SolveOptions& options, const ProgressFn& progress, bool resume);
  // Next-event estimation (next_event_plan.cpp): the run's groups and first direct parts,
  // the parts a checkpoint of `photons` gets (returns the seconds they took), and the planned
  // parts after the photons (returns a warning when stopped before them). `stop` is asked
  // between batches of shadow rays.
  void plan_direct_light(const Results& r, const std::function<bool()>& stop);
  bool use_direct_parts(std::uint64_t seed, std::uint32_t scale, const std::function<bool()>& stop);
  double checkpoint_direct_light(const Results& r, std::uint64_t photons);
  std::string finish_direct_light(Results& r, const std::function<bool()>& stop);
  void trace_direct_part(GroupTrace& trace, const GroupTrace* prefix, std::uint64_t run_photons);
  std::unique_ptr<detail::SimulationState> state_;
};

}  // namespace lightsolver
