#pragma once
/// \file solver.hpp
/// The direct problem: trace photons through a scene and report illuminance with confidence
/// intervals. Stages: validate (done by the loaders) -> prepare -> trace -> results.

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lightsolver/compliance.hpp"
#include "lightsolver/glare.hpp"
#include "lightsolver/process_group.hpp"
#include "lightsolver/provenance.hpp"
#include "lightsolver/scene.hpp"
#include "lightsolver/statistics.hpp"
#include "lightsolver/sunlight.hpp"

namespace lightsolver {

/// Photon budget of an accuracy run without an explicit photon count.
inline constexpr std::uint64_t kAccuracyPhotonBudget = 10'000'000'000ull;
/// Time limit (s) of an accuracy run without an explicit photon count or time limit.
inline constexpr double kDefaultAccuracySeconds = 300.0;

/// What a run is expected to cost, measured on its first batches.
struct RunForecast {
  std::uint64_t photons = 0;          ///< expected photons: the requested count or, with an
                                      ///< accuracy goal, extrapolated from the interval widths
  double photons_per_second = 0.0;    ///< tracing rate so far
  double seconds = 0.0;               ///< expected tracing time for `photons` at that rate
  std::optional<double> max_seconds;  ///< the time limit, when one applies
  bool accuracy_goal = false;         ///< `photons` is an extrapolation to the accuracy goal
};

struct TargetResult;

/// A point of a run: what the first `photons` photons gave and cost.
struct Checkpoint {
  std::uint64_t photons = 0;  ///< photons traced so far
  double seconds = 0.0;       ///< tracing time so far (s)
  /// Largest CI half-width / mean over the targets (whole grids, not cells); infinity while a
  /// target has no hit (no goal can be judged for it yet).
  double worst_relative_half_width = 0.0;
  /// Every target's results at this point, as a run of `photons` photons would report them
  /// (`lightsolver study` reads cells, Em, Emin and U0 from them).
  std::vector<TargetResult> targets;
};

/// What an accuracy goal costs, extrapolated from a checkpoint.
struct AccuracyCost {
  double photons = 0.0;  ///< photons the worst target needs (infinity while it has no hit)
  double seconds = 0.0;  ///< tracing time for them at the checkpoint's rate
};

/// The one accuracy/time extrapolation (the forecast of accuracy runs and `lightsolver cost`
/// use it): interval half-widths shrink as 1/sqrt(photons), so a goal g needs N (w / g)^2
/// photons where the first N gave worst relative half-width w; time scales with photons.
/// Throws InputError for a goal <= 0.
AccuracyCost accuracy_cost(const Checkpoint& at, double goal);

/// The checkpoints `lightsolver cost` (and Python's `lightsolver.cost`) report: 10^4 photons,
/// then 4x each (each halves the interval), up to `max_photons`; empty below 10^4.
std::vector<std::uint64_t> cost_checkpoints(std::uint64_t max_photons);
/// The accuracy goals (relative half-widths) whose cost they extrapolate from the last row.
inline constexpr double kCostGoals[] = {0.10, 0.05, 0.02, 0.01, 0.005};

/// Overrides of the scene's settings for one run, and how to run it. The options a user sets
/// (photons ... contributions) are rows of the run options table (run_options.hpp): the CLI's
/// flags, the Python keywords, their ranges (check_run_options(), run by solve() and
/// Simulation::run()) and the results keys that echo them come from there. The callbacks,
/// checkpoints, cancel flag and process group below are set by the front ends themselves.
struct SolveOptions {
  std::optional<std::uint64_t> photons;  ///< default: scene.settings.photons
  std::optional<std::uint64_t> seed;     ///< default: scene.settings.seed
  std::optional<double> confidence;      ///< default: scene.settings.confidence
  int threads = 0;                       ///< 0: all cores
  std::string backend = "auto";          ///< "auto", "embree" (and "vulkan" where built)
  /// Stop as soon as every target's CI half-width is at most this fraction of its mean (e.g.
  /// 0.02). `photons`, when given, is then the budget; without it the budget is
  /// kAccuracyPhotonBudget photons bounded by the time limit (scene.settings.photons does not
  /// count: it is the default of runs without a goal). Batches double from 2^14 photons, so
  /// the stopping point is deterministic for a seed unless the time limit ends the run.
  std::optional<double> target_accuracy;
  /// Judge `target_accuracy` per cell: every grid cell's and every surface target's half-width
  /// relative to its own mean (cells darker than 1 % of their grid's mean against that 1 %;
  /// lightsolver/accuracy.hpp). Default: scene.settings.accuracy_per_cell.
  std::optional<bool> accuracy_per_cell;
  /// Time limit of the tracing in seconds, checked between batches (finite, > 0). Default:
  /// scene.settings.max_seconds when `photons` is not given (an explicit count is traced to
  /// the end unless this is set); when neither is set, runs have no time limit except accuracy
  /// runs without an explicit photon count, which stop after kDefaultAccuracySeconds. Where a
  /// time limit ends a run depends on the machine's speed.
  std::optional<double> max_seconds;
  /// Trace until every requirement's verdict is pass or fail (default:
  /// scene.settings.decide), in doubling batches as accuracy runs, within the same budget
  /// (`photons`, else kAccuracyPhotonBudget within the time limit). Needs a target with
  /// requirements; not together with `target_accuracy`.
  std::optional<bool> decide;
  /// Report each luminaire group's contribution per target and cell (TargetResult::
  /// contributions, with the tallies `rescale` needs). Default: scene.settings.contributions.
  std::optional<bool> contributions;
  /// "auto", "on" or "off": direct light at grids and surface targets by shadow rays from
  /// stratified points to the luminaires, only the reflected light by photons
  /// (docs/statistics.md, "Next-event estimation"). Default: scene.settings.next_event.
  std::optional<std::string> next_event;
  /// "auto", "on" or "off": the reflected light at grids, beyond a cell size from each
  /// reflection, by connecting the diffuse vertices of an independent photon stream to every
  /// cell (docs/statistics.md, "Connected reflected light"); needs next_event. Default:
  /// scene.settings.connect_reflections.
  std::optional<std::string> connect_reflections;
  const std::atomic<bool>* cancel = nullptr;  ///< set to true to stop after the current batch
  /// Called once, when the first batches give a tracing rate: what the run is expected to
  /// cost (the CLI prints it for runs longer than a minute).
  std::function<void(const RunForecast&)> forecast;
  /// Photon counts (ascending) at which `checkpoint` is called with what the photons traced so
  /// far give; counts beyond the run's end are not reached. Batches are split there, which
  /// changes no result (photon i is photon i): one run measures accuracy against time at many
  /// photon counts without tracing any photon twice (`lightsolver cost`).
  std::vector<std::uint64_t> checkpoints;
  std::function<void(const Checkpoint&)> checkpoint;
  /// Processes sharing the run (MPI ranks; null: this process alone). Every process calls
  /// solve() with the same scene and options; each traces a slice of every batch, the tallies
  /// are summed exactly, so every process gets the results a lone process would, bit for bit.
  /// Batch sizes, time limits and cancel are rank 0's (its callbacks and flag count).
  std::shared_ptr<ProcessGroup> processes;
  /// "random" (independent photons, the default) or "sobol": quasi-random photons in
  /// `replicates` independent randomisations, whose spread gives the intervals
  /// (docs/statistics.md, "Quasi-random photons"). Embree backend, fixed photon counts only.
  std::string sampler = "random";
  std::uint32_t replicates = 8;  ///< replicates of a sobol run (2 to 1024)
  /// How the run was started, for the results' provenance: the CLI's command line, "python:
  /// lightsolver.solve" ... ("" : "library call").
  std::string command;
};

/// Called between batches with photons traced so far and the total; return false to cancel.
using ProgressFn = std::function<bool(std::uint64_t done, std::uint64_t total)>;

/// Why a run ended: "photons" (the requested count was traced), "accuracy" (every target met
/// the goal), "time" (the time limit), "cancelled" (cancel flag or progress callback).
inline constexpr const char* kStopPhotons = "photons";
inline constexpr const char* kStopAccuracy = "accuracy";
inline constexpr const char* kStopTime = "time";
inline constexpr const char* kStopCancelled = "cancelled";
/// A decide run ended because every verdict was pass or fail.
inline constexpr const char* kStopDecided = "decided";

/// Discomfort glare at an observer target (docs/glare.md): the background luminance from the
/// traced indirect illuminance at the eye, and the UGR of the scene's luminaires with the
/// interval that L_b's interval gives (the luminaire sum has no Monte-Carlo noise).
struct ObserverGlare {
  /// L_b = E_ind / pi (cd/m2), with its interval: the target's estimate (lux) over pi.
  double background_luminance_cd_m2 = 0.0, background_ci_low_cd_m2 = 0.0,
         background_ci_high_cd_m2 = 0.0;
  /// UGR at L_b; absent when no luminaire counts (no glare) or L_b is 0 (unbounded).
  std::optional<double> ugr;
  /// UGR at L_b's upper end (always, when a luminaire counts and L_b's upper end is > 0) and at
  /// its lower end (absent when that is 0: the interval is open above).
  std::optional<double> ugr_ci_low, ugr_ci_high;
  /// Sum of L^2 omega / p^2 over the counted luminaires (0: none counts, no glare).
  double luminaire_sum = 0.0;
  /// One per scene luminaire, in scene order: L, omega, p, term and ugr_alone (h_over_r,
  /// t_over_r and distance_m stay 0: a rescale rebuilds the glare from L, omega and p alone).
  std::vector<GlareContribution> contributions;
  Warnings warnings;
};

/// Every luminaire's glare terms at every point of an observer grid, at the result's fluxes:
/// what `rescale` rebuilds the points from, dimming L by the group's factor (docs/glare.md,
/// "Rescaling an observer grid"). Written to the results only with contributions.
struct GlareTerms {
  std::vector<std::string> luminaires;  ///< the scene's, in scene order
  /// Per luminaire: why it is no glare source at any eye ("" when it is one).
  std::vector<std::string> not_rated;
  /// Per point, one character per luminaire: 'c' counted, 'b' behind the eye, 'l' below the
  /// line of sight, 'o' outside the field or hidden by brow, 'd' dark or edge-on toward the
  /// eye, 'x' not rated (not_rated says why).
  std::vector<std::string> status;
  /// Per point: luminance (cd/m2), solid angle (sr) and position index of each counted
  /// luminaire, three numbers each, in scene order.
  std::vector<std::vector<double>> terms;
};

/// Glare over an observer grid (docs/glare.md, "Observer grids"): every (position, direction)
/// with its UGR and interval. The maximum, with an interval that holds for all points at once,
/// is the target's `glare`.
struct ObserverGridGlare {
  std::vector<glm::dvec3> positions, view_directions;
  /// Point k = position * view_directions.size() + direction; contributions are left out (the
  /// maximum's point has them in TargetResult::glare).
  std::vector<ObserverGlare> points;
  /// The point of the largest UGR estimate; absent when no point has glare from a luminaire.
  std::optional<std::size_t> max_at;
  GlareTerms terms;  ///< every point's luminaires (results JSON: with contributions only)
};

/// Illuminance of one target. For grids `estimate` is over the whole grid (flux crossing the
/// grid / its area) and `cells` holds every cell, row by row (index = iv * nu + iu).
/// A group's direct light in one bin by next-event estimation (shadow rays; docs/statistics.md,
/// "Next-event estimation"): its mean illuminance (at the group's flux, times its dimming factor
/// in a rescaled result), that mean's variance and how many of its samples saw light.
struct DirectLight {
  double lux = 0.0;
  double variance_lx2 = 0.0;
  std::uint64_t lit = 0;
};

/// One luminaire group's part of a target (lux at its own flux, times its dimming factor in a
/// rescaled result), with the integer tallies a rescale recomputes every interval from.
struct Contribution {
  std::string group;
  Estimate estimate;
  std::vector<Estimate> cells;  ///< grids: per cell
  /// The target's bins: whole target, then its cells; an observer grid's: every point's (its
  /// estimate above is the maximum's point's).
  std::vector<Tally> tallies;
  /// What the group's photons tallied: all its light; or, for a group whose direct light came
  /// from next-event estimation, its light after a scattering only (Reflected), or nothing at
  /// all (None: nothing in the scene reflects, its part is the direct part alone).
  enum class PhotonLight { All, Reflected, None };
  PhotonLight photon_light = PhotonLight::All;
  /// A next-event group's direct part per entry of `tallies` (whole target, then its cells);
  /// empty for an observer's or observer grid's eyes, which see reflected light only.
  std::vector<DirectLight> direct;
};

/// A daylight-factor grid's daylight factor D = E_in / E_out x 100 %: E_in the light of the
/// scene's sky (its group alone), E_out the sky's unobstructed horizontal illuminance above the
/// horizon (exact). Order statistics over the cells (equal in area) with intervals honest for
/// an order statistic of noisy cells (docs/statistics.md).
struct DaylightFactorResult {
  std::string sky;                      ///< the sky luminaire's name
  double outside_illuminance_lx = 0.0;  ///< E_out, as traced (a rescale keeps it and D)
  Estimate mean;                        ///< over the whole grid, percent
  OrderStatistic min;                   ///< the smallest cell
  OrderStatistic p50, p95;              ///< reached or exceeded over 50 % / 95 % of the area
  std::vector<Estimate> cells;          ///< per cell, percent
};

struct TargetResult {
  std::string name;
  std::string type;  ///< the scene file's target type ("surface", "grid", "observer", ...)
  bool is_grid = false;
  /// An observer: `estimate` is the indirect illuminance at its eye (lux, on a small square
  /// facing the line of sight, light reflected at least once) and `glare` its UGR.
  bool is_observer = false;
  /// An observer's glare; for an observer grid the maximum UGR (its interval simultaneous over
  /// the points, its L_b and luminaires those of the point where it occurs).
  std::optional<ObserverGlare> glare;
  std::optional<ObserverGridGlare> observer_grid;  ///< an observer grid's points
  double area_m2 = 0.0;
  Estimate estimate;  ///< lux
  std::uint32_t nu = 0, nv = 0;
  std::vector<Estimate> cells;
  double min_lux = 0.0, max_lux = 0.0, uniformity = 0.0;  ///< grids: over cell means; U0 = min/mean
  Requirements requirements;  ///< as resolved from the scene (none: !requirements.any())
  /// Grids, in runs that judge requirements: intervals of Emin, Emax, U0 and Ud.
  std::optional<GridIntervals> intervals;
  std::vector<Verdict> verdicts;  ///< one per requirement, in the order em, u0, emin, ud, ugr
  VerdictKind verdict = VerdictKind::Undecided;  ///< overall; meaningful with verdicts only
  /// Per luminaire group, in the order of Results::groups, when contributions were asked for.
  std::vector<Contribution> contributions;
  /// A daylight-factor grid's daylight factor (Target::Quantity::DaylightFactor).
  std::optional<DaylightFactorResult> daylight_factor;
};

/// A luminaire group: its own photon stream, traced apart (docs/statistics.md, "Groups").
struct GroupResult {
  std::string name;
  double flux_lm = 0.0;       ///< the group's flux (times its dimming factor in a rescaled result)
  std::uint64_t photons = 0;  ///< photons traced from this group
  std::vector<std::string> luminaires;
};

/// One luminaire as traced: the flux it emitted in the run, and where that number comes from.
/// The maintenance factor is not the solver's: a scene's `flux_lm` is already the flux to
/// trace (the workbench exports initial flux x MF and keeps MF in the scene's metadata).
struct LuminaireResult {
  std::string name;
  std::string type;   ///< the scene file's luminaire type ("point", "photometric", ...)
  std::string group;  ///< its luminaire group (GroupResult::name)
  /// Its flux before TILT: the scene's flux_lm; a photometric file's own flux (scaled by
  /// flux_lm when given); a directional beam's illuminance x opening area across the beam.
  double flux_lm = 0.0;
  double tilt_factor = 1.0;  ///< a photometric TILT table's factor at its tilt (1 without one)
  double dimming = 1.0;      ///< its group's factor in a rescaled result (1 as traced)
  /// flux_lm x tilt_factor x dimming: what it emitted in the calculation. The group's
  /// luminaires add up to GroupResult::flux_lm.
  double emitted_flux_lm = 0.0;
};

/// An effect the tracer left out because the scene does not need it, and why ("no glass").
struct SkippedEffect {
  std::string effect;
  std::string reason;
};

/// How a simulated effect was applied where it was not applied everywhere, in words
/// (next_event_direct under "auto": "floor: photons (shadow rays would be 3.1x wider)").
struct EffectNote {
  std::string effect;
  std::string note;
};

/// What the run simulated (docs/scene-format.md, "effects"): the effect names a scene needs,
/// and those skipped with the reason. The same analysis picks the Embree path kernel and the
/// Vulkan specialisation. `notes`: details of simulated effects (usually none).
struct EffectsReport {
  std::vector<std::string> simulated;
  std::vector<SkippedEffect> skipped;
  std::vector<EffectNote> notes;
};

/// Daylight photons that left an opening (a sky's portal, a sun's opening): a photon whose way
/// out toward its sky (the ray from its opening point against its direction) meets the scene is
/// blocked outside (absorbed, no tally); `glass`: of those, the ones whose way out met a glass
/// surface first (a modelled pane outside the opening: docs/daylight.md, "Portals").
struct OpeningCounts {
  std::uint64_t photons = 0, blocked = 0, glass = 0;
  void add(const OpeningCounts& o) {
    photons += o.photons;
    blocked += o.blocked;
    glass += o.glass;
  }
};

struct Results {
  std::vector<TargetResult> targets;
  std::uint64_t photons = 0;               ///< traced (== requested when stop_reason is "photons")
  std::uint64_t photons_requested = 0;     ///< the count or budget asked for
  bool partial = false;                    ///< stopped early by cancel or progress callback
  std::optional<double> target_accuracy;   ///< the goal, when one was set
  bool accuracy_met = false;               ///< every target reached target_accuracy
  bool accuracy_per_cell = false;          ///< the goal was judged per cell (with target_accuracy)
  std::string stop_reason = kStopPhotons;  ///< which limit ended the run (kStop*)
  std::optional<double> max_seconds;       ///< the time limit that applied, if any
  double seconds = 0.0;
  std::string backend;
  std::string sampler = "random";  ///< the photon sampler (SolveOptions::sampler)
  std::uint32_t replicates = 0;    ///< a sobol run's replicates (0: a random run)
  double confidence = 0.95;
  std::uint64_t seed = 0;
  std::uint64_t ray_segments = 0;
  std::uint64_t capped_paths = 0;  ///< paths still alive at max_bounces (bias, warned)
  /// Paths a device's own loop limit stopped even when traced alone (Mesa lavapipe ends a
  /// shader after 65535 loop iterations); their light is missing (bias, warned).
  std::uint64_t cut_paths = 0;
  /// Daylight photons through openings blocked outside them (warned with their share).
  OpeningCounts openings;
  double total_flux_lm = 0.0;
  Warnings warnings;
  EffectsReport effects;  ///< effects simulated and skipped (scene analysis before tracing)
  /// Some target has requirements: verdicts, grid intervals and `decide` are reported.
  bool judged = false;
  bool decide = false;  ///< the run traced until decided (SolveOptions::decide)
  VerdictKind verdict = VerdictKind::Undecided;  ///< overall over the judged targets
  std::vector<GroupResult> groups;  ///< every luminaire group, in the order of first appearance
  bool contributions = false;       ///< targets carry their per-group contributions
  /// The next-event setting of the run ("auto", "on", "off"); what it did is in `effects`
  /// (next_event_direct).
  std::string next_event = "off";
  /// The connect_reflections setting of the run; what it did is in `effects`
  /// (reflection_connection).
  std::string connect_reflections = "auto";
  /// A result of `rescale`: the dimming factor of every group (1 where none was given).
  std::vector<std::pair<std::string, double>> rescaled;
  /// Every luminaire, in scene order, as traced: the flux it emitted in the calculation.
  std::vector<LuminaireResult> luminaires;
  /// Where the results come from (provenance.hpp): set by every run; absent in results read
  /// from files written before it, and in results combined from group traces.
  std::optional<Provenance> provenance;
  /// EN 17037 sunlight exposure, when the scene asks for it (sunlight.hpp).
  std::optional<SunlightExposureResult> sunlight_exposure;
};

/// Runs the photon tracer. Deterministic: same scene, seed and photons give bit-identical
/// results for any thread count. Throws InputError for bad options, std::runtime_error when a
/// backend fails.
Results solve(const Scene& scene, const SolveOptions& options = {},
              const ProgressFn& progress = {});

/// Results as JSON text, format `lightsolver.results/1` (docs/scene-format.md).
std::string results_to_json(const Results& results);

/// Human-readable table: target, lux, ± half-width, hits; grids with min/max/U0; glare,
/// verdicts, one line of the effects simulated (`list_skipped_effects`: and a line per effect
/// skipped, with why) and the warnings.
std::string results_table(const Results& results, bool list_skipped_effects = false);

/// Library version ("0.1.0").
const char* version();

}  // namespace lightsolver
