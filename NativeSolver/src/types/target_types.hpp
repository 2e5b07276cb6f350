#pragma once
// One row per target type: how the scene file spells it, how it is read, checked, laid out as
// tallies and turned into results. The reader (scene_json.cpp), the validator (scene.cpp),
// prepare() (prepared_scene.cpp), the results (simulation.cpp, results_io.cpp) and study.cpp
// look the type up here instead of switching over Target::Type. Backends have no per-type
// code: a type tallies into a mesh's bin or into grid rows (PreparedGrid, with the
// indirect-only flag), which Embree (path_deposits.hpp) and Vulkan (GpuGrid rows) already
// count. docs/solver.md, "Adding a target type".
#include <cstdint>
#include <glm/vec3.hpp>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "model/backend.hpp"
#include "model/groups.hpp"
#include "model/prepared_scene.hpp"
#include "lightsolver/scene.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver::detail {

class JsonNode;
struct ObserverGridGeometry;

/// What a type's check may ask of the scene validator. `key` names a field of the target being
/// checked (the validator turns it into "targets[i].key"); failures throw InputError.
class TargetChecks {
 public:
  virtual ~TargetChecks() = default;
  [[noreturn]] virtual void fail(const std::string& key, const std::string& what) const = 0;
  /// Finite and within 10^9 m of the origin.
  virtual void coordinates(const std::string& key, const glm::dvec3& v) const = 0;
  /// Finite, non-zero and normalisable (the caller normalises).
  virtual void direction(const std::string& key, const glm::dvec3& v) const = 0;
  /// corner, edge1, edge2: finite, non-zero, not parallel (`what` ends the parallel message).
  virtual void parallelogram(const Target& t, const char* what) const = 0;
  /// The scene's mesh `index` (fails "mesh" when there is none), or nullptr when that mesh had
  /// an error of its own (a target on it is not checked again).
  virtual const Mesh* mesh(int index) const = 0;
  /// Adds grid cells to the scene's total (at most 10^7 together).
  virtual void add_grid_cells(std::uint64_t cells) const = 0;
};

/// How a type is tallied by every backend.
enum class TallyKind {
  MeshBin,  ///< the bin of its mesh (Target::mesh): photons absorbed or reflected there
  GridRows  ///< PreparedGrid rows: virtual rectangles crossed (indirect_only: reflected light)
};

/// Requirement keys, as bits of TargetType::requirements.
enum RequirementKey : unsigned {
  kRequireEm = 1u << 0,
  kRequireU0 = 1u << 1,
  kRequireEmin = 1u << 2,
  kRequireUd = 1u << 3,
  kRequireUgr = 1u << 4,
};

/// What a daylight-factor grid's result reads: the sky's group (its tallies alone), the sky's
/// flux as traced (a rescale's dimming leaves the ratio alone) and its outside illuminance.
struct DaylightFactorBasis {
  std::string sky;
  std::size_t group = 0;
  double sky_flux_lm = 0.0;
  double outside_lx = 0.0;
};

/// A target's tallies at the end (or a checkpoint) of a run, for its result hook.
struct TargetTallies {
  const Target& target;
  const std::vector<BinInfo>& bins;  ///< every bin's area
  const GroupedTallies& tallies;     ///< the run's tallies, its groups combined (groups.hpp)
  const PreparedTarget& layout;      ///< where its bins are (PreparedScene::targets)
  double confidence;
  /// A grid gets its Emin/Emax/U0/Ud intervals: always in final results; in a run's batch
  /// looks only when the run judges requirements (they cost a pass over the cells).
  bool judged;
  /// The scene's luminaires, for glare; null when results are rebuilt without the scene
  /// (rescale.cpp rescales an observer's glare itself).
  const std::vector<Luminaire>* luminaires;
  /// An observer grid's geometry read back from results (rescale); null: from `luminaires`.
  const ObserverGridGeometry* observer_grid;
  /// A daylight-factor grid's sky; null elsewhere (and then no daylight factor is reported).
  const DaylightFactorBasis* daylight = nullptr;

  /// Bin `b`'s illuminance (lux) at the run's confidence, or at the critical value `z`.
  Estimate estimate(std::uint32_t b) const;
  Estimate estimate_z(std::uint32_t b, double z) const;
};

/// One target type. Every hook is required.
struct TargetType {
  Target::Type type;
  const char* name;  ///< "type" in the scene file
  /// The keys of its scene-file entry.
  std::span<const char* const> keys;
  /// Reads the type's keys, rejecting unknown ones ("name" is already read; "requirements"
  /// and "task" are read after it, and must be allowed).
  void (*read)(const JsonNode& n, const Scene& scene, Target& t);
  /// Checks value ranges and normalises directions, in the order the messages should come.
  void (*check)(const TargetChecks& c, Target& t);
  /// The requirements it takes (RequirementKey bits): a task row's others are dropped, and
  /// explicit others are errors with `other_requirements` as the message.
  unsigned requirements;
  const char* other_requirements;
  TallyKind tally;
  /// Its bins after the first are nu x nv cells (results' `cells`; per-cell accuracy goals).
  bool cells;
  /// The eyes it tallies (kEyeBins each, reflected light only); 0: its bins are the whole
  /// target and its cells. An observer grid read back from results counts its points instead.
  std::uint32_t (*eyes)(const Target& t);
  /// A point of the target for the scene's centre, when it has coordinates of its own.
  std::optional<glm::dvec3> (*anchor)(const Target& t);
  /// Adds its bins (append_target_bins) and grid rows to `out`, and its record to out.targets.
  /// `mesh_area_m2`: per mesh.
  void (*prepare)(const Target& t, const std::vector<double>& mesh_area_m2, PreparedScene& out);
  /// Fills the type's part of `r` (name, type, requirements, area and estimate are set).
  void (*result)(const TargetTallies& tallies, TargetResult& r);
  /// The results-file keys its result adds to every target's (results_io.cpp writes them).
  std::span<const char* const> result_fields;
};

/// All types, one row each, complete (every hook set). Assembled above core and glare
/// (src/tables/target_table.cpp) from core_target_rows() and the glare layer's result hooks.
std::span<const TargetType> target_types();
/// The rows as core defines them (target_types.cpp): the observer rows' `result` is null here,
/// glare's (src/glare/observer_rows.cpp), which core never includes.
std::span<const TargetType> core_target_rows();
/// The row of `type`.
const TargetType& target_type(Target::Type type);
/// The row whose scene-file name is `name`, or nullptr.
const TargetType* find_target_type(std::string_view name);
/// "surface, grid, observer or observer_grid", for messages.
std::string target_type_names();

/// Appends a target's bins to `bins` in the one layout every reader takes from the record it
/// returns: `eyes` > 0: kEyeBins per eye, each of `area_m2` (an eye's square); otherwise the
/// whole target (`area_m2`) and then `cells` equal cells. Grid rows and mesh are left unset.
/// prepare() and rescale (results read back) both lay bins out here.
PreparedTarget append_target_bins(std::vector<BinInfo>& bins, double area_m2, std::uint32_t cells,
                                  std::uint32_t eyes);

/// An observer grid's eyes (listed, or the rectangle's cell centres, row by row) and lines of
/// sight (listed, or every view_step_deg about `up` from +x; +y when up is along x).
std::vector<glm::dvec3> observer_grid_positions(const Target& t);
std::vector<glm::dvec3> observer_grid_directions(const Target& t);

}  // namespace lightsolver::detail
