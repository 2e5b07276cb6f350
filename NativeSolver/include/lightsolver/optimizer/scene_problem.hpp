#pragma once
/// \file scene_problem.hpp
/// The engine connected to real scenes: the `optimization` block of a scene file (intention,
/// variables, search settings; docs/optimization.md §10) and the Evaluator that applies a
/// configuration to a lightsolver::Simulation, traces it and reduces the results to the
/// intention's estimates.
///
/// Usage:
///   SceneProblem p = load_problem("cornell.json");
///   OptimizationResult r = run_problem(p, {}, control);
///   std::string json = problem_result_json(p, r);   // to_json + world positions per member

#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lightsolver/backends.hpp"
#include "lightsolver/optimizer/domain.hpp"
#include "lightsolver/optimizer/evaluator.hpp"
#include "lightsolver/optimizer/intention.hpp"
#include "lightsolver/optimizer/result.hpp"
#include "lightsolver/optimizer/vns.hpp"
#include "lightsolver/scene.hpp"
#include "lightsolver/simulation.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver::optimizer {

/// A placement region in a rectangle's (u, v) coordinates: outer ring first, then holes.
using PlacementRegion = std::vector<std::vector<glm::dvec2>>;

/// One entry of `optimization.variables`, with the Domain variables it owns.
struct SceneVariable {
  enum class Type {
    kPosition,     ///< luminaire(s) on a parallelogram: corner + u·edge1 + v·edge2 (2 variables)
    kTranslation,  ///< a mesh's `anchor` moved onto a parallelogram (2 variables)
    kAim,          ///< a luminaire's tilt (from nadir) or pan (from +x, counter-clockwise), deg
    kFlux,         ///< the flux of one or more luminaires, lm (1 variable)
    kRotation,     ///< a mesh turned about `axis` through `pivot`, deg (1 variable)
  };
  enum class Angle { kTilt, kPan };

  Type type = Type::kPosition;
  std::vector<std::size_t> luminaires;  ///< position: moved together; aim: one; flux: all set
  std::vector<glm::dvec3> offsets;      ///< position: each luminaire's anchor − the first's
  std::size_t mesh = 0;                 ///< translation, rotation
  glm::dvec3 anchor{0.0};  ///< translation: mesh point (as loaded) placed on the rectangle
  glm::dvec3 corner{0.0}, edge1{0.0}, edge2{0.0};  ///< position / translation rectangle
  /// position / translation `within`: the admissible region in rectangle coordinates (u, v);
  /// cells whose centre lies outside are never evaluated. Empty: the whole rectangle.
  PlacementRegion region;
  Angle angle = Angle::kTilt;  ///< aim
  /// rotation: a point of the mesh as loaded (default: the anchor of the mesh's translation
  /// variable, else the centre of its bounding box) and a unit axis (default +z, vertical)
  glm::dvec3 pivot{0.0}, axis{0.0, 0.0, 1.0};
  std::size_t first = 0;  ///< index of its first variable in SceneProblem::domain
};

/// A scene with its inverse problem, ready to run.
struct SceneProblem {
  Scene scene;
  Intention intention;
  Domain domain;
  std::vector<SceneVariable> variables;
  VnsOptions search;
  /// `search.reuse_traces` (default true): trace each luminaire group apart and keep its
  /// trace for the configurations that do not change it; a flux variable then costs no tracing
  /// (docs/optimization.md, "Reused traces"). False: every evaluation traces every group.
  bool reuse_traces = true;
  /// `search.refine_stage_photons` where given (stage_photons(): N/4 otherwise under strategy B)
  std::optional<std::uint64_t> refine_stage_photons;
  /// `search.match_widths` (default true): with next-event estimation, scale N (and the
  /// stages) down to the interval width a photon-only search has at N (width_factor()), so N
  /// means the same resolution with shadow rays as without; false keeps N as given.
  bool match_widths = true;
  /// `search.min_spacing_m`: no two luminaires closer than this (anchor to anchor) in any
  /// configuration searched; positions are always distinct (docs/optimization.md §10).
  double min_spacing_m = 0.0;
  std::string file;  ///< for messages
  /// SHA-256 of the optimization block's canonical JSON (the scene file's, or the one given in
  /// its place): the output's provenance.optimization_sha256.
  std::string block_sha256;

  /// Meshes that translation or rotation variables move (Simulation::Options::movable_meshes).
  std::vector<std::string> movable_meshes() const;
};

/// Reads a scene file and its `optimization` block. Throws InputError naming the file and the
/// field (e.g. `optimization.variables[1].cells`), also when the block is missing.
SceneProblem load_problem(const std::string& path);

/// Same from JSON text of a whole scene file; `base_dir` resolves mesh and photometric files.
SceneProblem problem_from_json(const std::string& text, const std::string& file,
                               const std::string& base_dir);

/// A scene built elsewhere (Python) plus the JSON text of an `optimization` block.
SceneProblem problem_from_scene(Scene scene, const std::string& optimization_json,
                                const std::string& file = "");

/// What a configuration changes: luminaires to replace and movable meshes to place.
struct SceneChanges {
  std::vector<std::pair<std::size_t, Luminaire>> luminaires;
  std::vector<std::pair<std::size_t, glm::dmat4>> meshes;  ///< rigid world transforms
};

/// The changes for a configuration's values (Domain order), starting from the loaded scene.
SceneChanges changes_for(const SceneProblem& problem, const std::vector<double>& values);

/// The scene with a configuration's values applied (for independent checks, pictures).
Scene apply_values(const SceneProblem& problem, const std::vector<double>& values);

/// Where each variable puts things, in world coordinates: "<luminaire>" → its anchor (position,
/// centre of an area light), "<mesh>" → its translation, "<luminaire>.direction", flux in lm.
std::map<std::string, std::vector<double>> describe_values(const SceneProblem& problem,
                                                           const std::vector<double>& values);

/// The level of each interval in U0's simultaneous family over a grid of `cells` cells and its
/// mean: 1 − (1 − confidence) / (cells + 1).
double uniformity_confidence(std::size_t cells, double confidence);

/// U0 = Emin / Em of a grid with a conservative interval (docs/optimization.md §9): the cells
/// and the mean are one family of simultaneous intervals (Bonferroni), so the interval covers
/// min_j E_j / Em whichever cell is the minimum. `grid`: the grid's results at `confidence`;
/// `wide`: the same tallies' results at uniformity_confidence(cells, confidence).
Estimate uniformity_estimate(const TargetResult& grid, const TargetResult& wide, double confidence);

/// Evaluator over a Simulation that owns a copy of the problem's scene.
class SceneEvaluator final : public Evaluator {
 public:
  /// `threads` 0: all cores; `backend`: a name from lightsolver::backends(). Throws InputError
  /// as Simulation does.
  /// `processes`: MPI ranks sharing every trace (null: alone); the search itself runs the
  /// same on every rank (its randomness and the traced numbers are identical there).
  /// `reuse_traces`: as SceneProblem::reuse_traces, which it overrides when given.
  /// `next_event`: "auto", "on" or "off", overriding the scene's settings.next_event (direct
  /// light at the targets by shadow rays, docs/optimization.md "Next-event estimation").
  SceneEvaluator(const SceneProblem& problem, int threads = 0,
                 const std::string& backend = kAutoBackend,
                 std::shared_ptr<ProcessGroup> processes = nullptr,
                 std::optional<bool> reuse_traces = std::nullopt,
                 const std::optional<std::string>& next_event = std::nullopt);
  ~SceneEvaluator() override;
  /// Applies the request's configuration, traces the groups it changed (all of them without
  /// reuse) with seeds derived from the run seed and the group's part of the configuration,
  /// and sums the groups' traces scaled to their fluxes. Depends only on the request.
  Evaluation evaluate(const EvaluationRequest& request) override;
  /// The simulation's scene with the last request applied.
  const Scene& scene() const { return simulation_.scene(); }
  /// Results of the last trace (for tests and pictures).
  const Results& last_results() const { return last_; }
  /// The backend that traces and its device (the search's provenance).
  std::string backend_name() const { return simulation_.backend_name(); }
  std::string device() const { return simulation_.device(); }
  /// The next-event setting the evaluations follow and what it did so far: on when some
  /// evaluation had direct parts, else the reason (the effects list's next_event_direct).
  NextEventUse next_event_use() const { return next_event_; }

 private:
  struct Reuse;  // the trace plan and the kept group traces (group_traces.hpp)

  void apply(const std::vector<double>& values);
  Estimate metric(const Metric& m) const;
  void note_next_event(const Results& r);

  const SceneProblem& problem_;
  Simulation simulation_;
  double confidence_;
  std::shared_ptr<ProcessGroup> processes_;
  std::unique_ptr<Reuse> reuse_;
  Results last_;
  NextEventUse next_event_;
};

/// Command-line / Python overrides of the `search` block.
struct RunOverrides {
  std::optional<std::uint64_t> iterations, seed, screening_photons, confirmation_photons;
  int threads = 0;
  std::string backend = kAutoBackend;       ///< a name from lightsolver::backends()
  std::shared_ptr<ProcessGroup> processes;  ///< MPI ranks sharing every trace (null: alone)
  std::optional<bool> reuse_traces;         ///< overrides SceneProblem::reuse_traces
  /// How the search was started, for its provenance: the CLI's command line, "python: ...".
  std::string command;
  std::optional<std::string> next_event;  ///< overrides the scene's settings.next_event
  /// Overrides search.refine_stage_photons (0: the unstaged end refinement).
  std::optional<std::uint64_t> refine_stage_photons;
  /// Overrides search.match_widths (SceneProblem::match_widths).
  std::optional<bool> match_widths;
};

/// The staged refinement's first-stage photons a search uses (VnsOptions::refine_stage_photons):
/// the override's, else the block's `refine_stage_photons`, else N/4, under strategy B (0 for
/// strategy A, or where it would reach N: unstaged).
std::uint64_t stage_photons(const SceneProblem& problem, const RunOverrides& overrides,
                            const VnsOptions& search);

/// Builds a SceneEvaluator and runs optimize() with the problem's search settings. The result's
/// provenance records the base scene's source, the build, backend, device, processes, threads,
/// the resolved search settings, the times, host and `overrides.command`.
OptimizationResult run_problem(const SceneProblem& problem, const RunOverrides& overrides,
                               const Control& control = {});

/// to_json(result) with, per ISOC member, `"scene": describe_values(...)` added, and the
/// result's `provenance` (with the block's hash and the domain searched) when it has one.
std::string problem_result_json(const SceneProblem& problem, const OptimizationResult& result,
                                int indent = 2);

}  // namespace lightsolver::optimizer
