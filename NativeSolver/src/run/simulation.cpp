// Simulation: a prepared scene and its backend, kept for many runs (solve() uses it once).
// Photons are traced in batches until a stop policy ends the run (stop_policies.hpp: photons,
// cancel, time, accuracy, decide; progress, forecast and checkpoints observe the batches),
// then integer tallies become illuminance estimates.
#include "lightsolver/simulation.hpp"

#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <limits>
#include <optional>

#include "estimate/cell_accuracy.hpp"
#include "estimate/decide.hpp"
#include "estimate/direct_choice.hpp"
#include "estimate/run_results.hpp"
#include "estimate/target_results.hpp"
#include "lightsolver/run_options.hpp"
#include "lightsolver/timings.hpp"
#include "model/backend.hpp"
#include "model/groups.hpp"
#include "prepare/scene_effects.hpp"
#include "prepare/target_reach.hpp"
#include "run/replicate_run.hpp"
#include "run/shared_tracing.hpp"
#include "run/simulation_state.hpp"
#include "run/stop_policies.hpp"
#include "scene/provenance.hpp"
#include "scene/validate_again.hpp"
#include "types/target_types.hpp"

namespace lightsolver {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// Batches are cancellation points and progress reports; their size never changes results
// (photon i is photon i, tallies are integer sums). Normal runs aim at ~0.2 s per batch so a
// Cancel is felt at once; accuracy runs double from 2^14 up to 2^22 so the point where the goal
// is met does not depend on the machine's speed.
std::uint64_t next_batch(std::uint64_t done, std::uint64_t total, bool accuracy_mode,
                         double photons_per_second) {
  constexpr std::uint64_t kMin = 1u << 14, kMax = 1u << 22;
  std::uint64_t size = kMin;
  if (accuracy_mode) {
    size = std::clamp<std::uint64_t>(done, kMin, kMax);
  } else if (photons_per_second > 0.0) {
    size = std::clamp<std::uint64_t>(static_cast<std::uint64_t>(0.2 * photons_per_second), kMin,
                                     8 * kMax);
  }
  return std::min(size, total - done);
}

// Largest relative half-width over the targets and an observer grid's eyes (scale-free, so the
// per-path tallies' estimates serve); infinity while a target has no hit. The one measure of a
// run's accuracy: the stopping rule, the forecast and the cost checkpoints all read it.
double worst_relative_half_width(const detail::PreparedScene& s, const detail::TallyBlock& t,
                                 std::uint64_t photons, double confidence) {
  double worst = 0.0;
  const detail::GroupedTallies tallies = detail::grouped_tallies(s, t.bins, photons);
  for (const detail::PreparedTarget& target : s.targets) {
    for (std::uint32_t k = 0; k < target.goal_count(); ++k) {
      const std::uint32_t bin = target.goal_bin(k);
      const Estimate e = tallies.estimate(bin, s.bins[bin].area_m2, confidence);
      if (e.hits == 0 || !(e.mean > 0.0)) return std::numeric_limits<double>::infinity();
      worst = std::max(worst, 0.5 * (e.ci_high - e.ci_low) / e.mean);
    }
  }
  return worst;
}

// The measure an accuracy goal is judged by: target means, or every cell (per-cell mode).
double goal_width(const Scene& scene, const detail::PreparedScene& s, const detail::TallyBlock& t,
                  const Results& r) {
  return r.accuracy_per_cell
             ? detail::worst_cell_relative_half_width(scene, s, t, r.photons, r.confidence)
             : worst_relative_half_width(s, t, r.photons, r.confidence);
}

// Photons that would bring the worst target (or cell) to the accuracy goal, from the tallies so
// far; the budget while a target has no hit yet.
std::uint64_t photons_for_goal(const Scene& scene, const detail::PreparedScene& s,
                               const detail::TallyBlock& t, const Results& r) {
  const std::uint64_t photons = r.photons, budget = r.photons_requested;
  const double goal = *r.target_accuracy;
  const Checkpoint at{photons, 0.0, goal_width(scene, s, t, r), {}};
  const double need = accuracy_cost(at, goal).photons;
  return need >= double(budget) ? budget : std::max(photons, static_cast<std::uint64_t>(need));
}

// What the rest of the run will cost at the rate of its first `traced_s` seconds.
RunForecast make_forecast(const Scene& scene, const detail::PreparedScene& s,
                          const detail::TallyBlock& t, const Results& r, double traced_s) {
  RunForecast f;
  f.photons_per_second = double(r.photons) / traced_s;
  f.accuracy_goal = r.target_accuracy.has_value();
  f.photons = f.accuracy_goal ? photons_for_goal(scene, s, t, r) : r.photons_requested;
  f.seconds = double(f.photons) / f.photons_per_second;
  f.max_seconds = r.max_seconds;
  return f;
}

// The photon count and time limit of one run. An accuracy goal without an explicit photon
// count gets a large budget bounded by time; scene.settings.photons is not an explicit count
// (it is the default of runs without a goal). The scene's time limit is a default like its
// photon count: an explicit count (the optimizer's evaluations, --photons) is traced to the
// end unless an explicit time limit is given too.
void plan_run(const Scene& scene, const SolveOptions& o, Results& r) {
  const bool open_budget = (o.target_accuracy || r.decide) && !o.photons;
  // The open budget stays within what exact 64-bit tallies allow at this max_bounces.
  const std::uint64_t budget =
      std::min(kAccuracyPhotonBudget, max_photons(scene.settings.max_bounces));
  r.photons_requested = o.photons ? *o.photons : open_budget ? budget : scene.settings.photons;
  r.max_seconds = o.max_seconds;
  if (!r.max_seconds && !o.photons) r.max_seconds = scene.settings.max_seconds;
  if (!r.max_seconds && open_budget) r.max_seconds = kDefaultAccuracySeconds;
  if (r.max_seconds && !(std::isfinite(*r.max_seconds) && *r.max_seconds > 0.0)) {
    throw InputError(scene.source_file, "max_seconds", "must be a finite number of seconds > 0");
  }
}

// A time limit makes the stopping point depend on the machine: say so, and what it cost.
void add_stop_warnings(Results& r) {
  if (r.stop_reason != kStopTime) return;
  char limit[32];
  std::snprintf(limit, sizeof limit, "%g", *r.max_seconds);
  std::string w = std::string("the time limit (") + limit + " s) ended the run after " +
                  std::to_string(r.photons) + " photons";
  if (r.target_accuracy) {
    w += std::string(", before every ") + (r.accuracy_per_cell ? "cell" : "target") +
         " reached the requested accuracy";
  } else {
    w += " of the " + std::to_string(r.photons_requested) + " requested";
  }
  r.warnings.push_back(w + "; where a time limit stops a run depends on the machine's speed");
}

// One run's batches: traced until a stop policy (stop_policies.hpp) ends the run, with the
// forecast, progress and checkpoints observing them.
struct BatchLoop {
  const Scene& scene;
  const detail::PreparedScene& prepared;
  detail::Backend& backend;
  int threads;
  const SolveOptions& options;
  const ProgressFn& progress;
  detail::TallyBlock& tallies;
  Results& r;
  // Gives a checkpoint of `photons` the direct parts a plain run of them has; returns the
  // seconds those parts took (a row's time includes what its estimate cost).
  std::function<double(std::uint64_t photons)> checkpoint_direct;

  std::vector<TargetResult> targets_at(std::uint64_t photons, double confidence) const {
    return detail::all_targets(scene, prepared, tallies, photons, confidence, r.judged,
                               r.contributions);
  }

  // What the rest of the run will cost, `looks` verdict looks in.
  RunForecast forecast(const detail::BatchState& at, int looks) const {
    RunForecast f = make_forecast(scene, prepared, tallies, r, at.elapsed_s);
    if (r.decide) {  // the photons the verdicts still open are expected to need
      std::vector<TargetResult> now =
          targets_at(r.photons, detail::look_confidence(r.confidence, looks));
      f.photons = detail::photons_to_decide_all(now, r.photons, r.photons_requested);
      f.seconds = double(f.photons) / f.photons_per_second;
    }
    return f;
  }

  Checkpoint checkpoint(std::uint64_t at, double seconds) const {
    Checkpoint c;
    c.photons = at;
    c.seconds = seconds;
    c.worst_relative_half_width = worst_relative_half_width(prepared, tallies, at, r.confidence);
    c.targets = targets_at(at, r.confidence);
    return c;
  }

  // Traces from r.photons until a policy stops; sets r.stop_reason and r.accuracy_met and
  // returns the seconds spent tracing.
  double trace() {
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    const bool doubling = r.target_accuracy || r.decide;  // batches: deterministic stop points
    const std::uint64_t first_photon = r.photons;
    const auto start = Clock::now();
    detail::SharedTracing shared(options.processes.get(), tallies.bins.size());
    // The stopping rules in the order they are asked; the same list on every process, so an
    // agreed index names one rule everywhere.
    detail::PhotonLimit photon_limit;
    detail::CancelPolicy cancel(options.cancel);
    detail::TimeLimit time_limit(r.max_seconds);
    detail::AccuracyGoal accuracy(r.target_accuracy, [&](const detail::BatchState&) {
      return goal_width(scene, prepared, tallies, r);
    });
    detail::DecidePolicy decide(r.decide, [&](std::uint64_t photons, int look) {
      std::vector<TargetResult> now =
          targets_at(photons, detail::look_confidence(r.confidence, look));
      return detail::all_decided(now);
    });
    const detail::StopPolicies policies({&photon_limit, &cancel, &time_limit, &accuracy, &decide});
    detail::ForecastObserver forecast_report;
    if (options.forecast) {
      forecast_report = detail::ForecastObserver(
          [&](const detail::BatchState& at) { options.forecast(forecast(at, decide.looks())); });
    }
    detail::ProgressObserver progress_report(progress, cancel);
    detail::CheckpointSplitter checkpoints(options.checkpoints);
    double aside_s = 0.0;  // spent on the checkpoints' direct parts, counted only in their rows
    auto report_checkpoint = [&](std::uint64_t at) {
      if (!options.checkpoint) return;
      const auto direct_start = Clock::now();
      const double direct_s = checkpoint_direct ? checkpoint_direct(at) : 0.0;
      aside_s += seconds_since(direct_start);
      options.checkpoint(checkpoint(at, seconds_since(start) - aside_s + direct_s));
    };
    auto trace_range = [&](std::uint64_t first, std::uint64_t count) {
      shared.trace(first, count, tallies,
                   [&](std::uint64_t from, std::uint64_t photons, detail::TallyBlock& into) {
                     // Photons [from, from + photons) of the run are each group's share.
                     const auto ranges = detail::group_ranges(prepared.groups, from, photons);
                     arena.execute([&] { backend.trace(ranges, r.seed, into); });
                   });
    };
    for (;;) {
      const double elapsed = seconds_since(start);
      const double rate = elapsed > 0.0 ? double(r.photons - first_photon) / elapsed : 0.0;
      std::uint64_t stop = policies.before({r.photons, r.photons_requested, elapsed});
      std::uint64_t n = next_batch(r.photons, r.photons_requested, doubling, rate);
      n = time_limit.fit(n, rate, elapsed);
      shared.agree(n, stop);  // rank 0's clock and user decide for every process
      if (stop == 0) {
        checkpoints.trace(r.photons, n, trace_range, report_checkpoint);
        r.photons += n;
        stop = policies.after({r.photons, r.photons_requested, seconds_since(start)});
      }
      if (stop != 0) {
        r.stop_reason = policies.reason(stop);
        break;
      }
      const detail::BatchState done{r.photons, r.photons_requested, seconds_since(start)};
      forecast_report.after_batch(done);
      progress_report.after_batch(done);  // a stop it asks for is agreed before the next batch
    }
    r.accuracy_met = r.stop_reason == kStopAccuracy;
    return seconds_since(start);
  }
};

// Rigid: the linear part is orthonormal and the last row is (0, 0, 0, 1).
bool is_rigid(const glm::dmat4& m) {
  const glm::dmat3 r(m);
  const glm::dmat3 should_be_identity = glm::transpose(r) * r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (std::abs(should_be_identity[i][j] - (i == j ? 1.0 : 0.0)) > 1e-6) return false;
    }
  }
  return m[0][3] == 0 && m[1][3] == 0 && m[2][3] == 0 && m[3][3] == 1;
}

}  // namespace

AccuracyCost accuracy_cost(const Checkpoint& at, double goal) {
  if (!(goal > 0.0)) throw InputError("", "accuracy goal", "must be > 0");
  const double ratio = at.worst_relative_half_width / goal;
  AccuracyCost c;
  c.photons = double(at.photons) * ratio * ratio;
  c.seconds = at.photons > 0 ? c.photons * at.seconds / double(at.photons) : 0.0;
  return c;
}

std::vector<std::uint64_t> cost_checkpoints(std::uint64_t max_photons) {
  std::vector<std::uint64_t> at;
  for (std::uint64_t n = 10'000; n <= max_photons; n *= 4) {
    at.push_back(n);
    if (n > max_photons / 4) break;  // the next step would pass max_photons (or overflow)
  }
  return at;
}

Simulation::Simulation(Scene scene, Options options)
    : state_(std::make_unique<detail::SimulationState>()) {
  const timings::Scope phase("set up (Simulation)");
  if (options.threads < 0) throw InputError("", "threads", "must be >= 0 (0: all cores)");
  {
    const timings::Scope validating("validate");
    options.scene_validated ? detail::validate_again(scene) : validate(scene);
  }
  std::vector<std::size_t> movable;
  for (const auto& name : options.movable_meshes) {
    const int i = scene.find_mesh(name);
    if (i < 0)
      throw InputError(scene.source_file, "movable_meshes", "unknown mesh \"" + name + "\"");
    movable.push_back(static_cast<std::size_t>(i));
  }
  state_->scene = std::move(scene);
  {
    const timings::Scope preparing("prepare");
    state_->prepared = detail::prepare(state_->scene, movable);
  }
  state_->backend = detail::make_backend(options.backend, state_->prepared, state_->backend_notes);
  state_->threads = options.threads;
  timings::mark("ready to trace (first photon)");
}

Simulation::~Simulation() = default;

const Scene& Simulation::scene() const { return state_->scene; }

double Simulation::pending_update_seconds() const { return state_->pending_update_seconds; }

void Simulation::set_luminaire(std::size_t index, const Luminaire& luminaire) {
  const auto start = Clock::now();
  Scene& s = state_->scene;
  if (index >= s.luminaires.size()) {
    throw InputError(s.source_file, "luminaires", "no luminaire " + std::to_string(index));
  }
  const Luminaire previous = s.luminaires[index];
  s.luminaires[index] = luminaire;
  try {
    validate_luminaires(s);
  } catch (...) {
    s.luminaires[index] = previous;  // a rejected change leaves the simulation as it was
    throw;
  }
  s.source.reset();  // no longer the scene file's content: results cannot name its hash
  detail::prepare_luminaires(s, state_->prepared);
  state_->backend->luminaires_changed();
  state_->kept.reset();
  state_->direct_seed.reset();
  state_->judging_seed.reset();
  state_->connected_seed.reset();  // the connection too: it saw the old light
  state_->pending_update_seconds += seconds_since(start);
}

void Simulation::set_mesh_transform(std::size_t mesh, const glm::dmat4& world) {
  const auto start = Clock::now();
  detail::PreparedScene& p = state_->prepared;
  const std::string where = "meshes[" + std::to_string(mesh) + "]";
  if (mesh >= p.meshes.size() || !p.meshes[mesh].movable) {
    throw InputError(state_->scene.source_file, where, "mesh is not declared movable");
  }
  if (!is_rigid(world)) {
    throw InputError(state_->scene.source_file, where,
                     "transform must be rigid (rotation + translation): areas must not change");
  }
  // The same motion in re-centred coordinates: T = shift(-origin) * world * shift(origin),
  // composed in double before the float conversion.
  glm::dmat4 local = world;
  local[3] = glm::dvec4(glm::dvec3(world * glm::dvec4(p.origin, 1.0)) - p.origin, 1.0);
  p.meshes[mesh].transform = glm::mat4(local);
  state_->scene.source.reset();  // no longer the scene file's geometry
  state_->backend->set_mesh_transform(mesh, p.meshes[mesh].transform);
  state_->kept.reset();
  state_->direct_seed.reset();
  state_->judging_seed.reset();
  state_->connected_seed.reset();  // the connection too: it saw the old geometry
  state_->pending_update_seconds += seconds_since(start);
}

std::uint64_t Simulation::kept_photons() const { return state_->kept ? state_->kept_photons : 0; }

Results Simulation::refine(const SolveOptions& options, const ProgressFn& progress) {
  check_run_options(options);
  if (!options.photons) throw InputError("", "photons", "refine() needs the photons in all");
  if (options.decide.value_or(false)) throw InputError("", "decide", "not with refine()");
  SolveOptions o = options;
  o.decide = false;  // the scene's own decide setting neither: verdicts are judged as in a run
  return run_from(o, progress, true);
}

Results Simulation::run(const SolveOptions& options, const ProgressFn& progress) {
  check_run_options(options);  // each option's range, as the front ends check it
  return run_from(options, progress, false);
}

Results Simulation::run_from(const SolveOptions& options, const ProgressFn& progress, bool resume) {
  const auto start = Clock::now();
  const auto started = std::chrono::system_clock::now();
  const Scene& scene = state_->scene;
  const detail::PreparedScene& prepared = state_->prepared;
  Results r;
  // A checkpointed run (cost, study) traces to its last checkpoint: the scene's own decide
  // setting does not cut it short (an explicit option still could).
  r.decide = options.decide.value_or(scene.settings.decide && options.checkpoints.empty());
  r.judged = detail::judges_requirements(scene, r.decide, options.target_accuracy.has_value());
  plan_run(scene, options, r);
  r.seed = options.seed.value_or(scene.settings.seed);
  r.confidence = options.confidence.value_or(scene.settings.confidence);
  r.target_accuracy = options.target_accuracy;
  r.accuracy_per_cell =
      r.target_accuracy && options.accuracy_per_cell.value_or(scene.settings.accuracy_per_cell);
  check_photon_count(r.photons_requested, scene.settings.max_bounces, "", "photons");
  if (!(r.confidence > 0.0 && r.confidence < 1.0)) {
    throw InputError("", "confidence", "must lie strictly between 0 and 1");
  }
  if (r.target_accuracy && !(*r.target_accuracy > 0.0 && *r.target_accuracy < 1.0)) {
    throw InputError("", "target_accuracy", "must lie strictly between 0 and 1 (e.g. 0.02)");
  }
  state_->pending_update_seconds = 0.0;
  // Each group has its own tallies (groups x bins), so their estimates are independent; checked
  // before the direct parts (as many, and traced per group and bin).
  detail::check_group_tallies(scene.source_file, prepared.groups.size(), prepared.bins.size());
  r.next_event = options.next_event.value_or(scene.settings.next_event);
  r.connect_reflections = options.connect_reflections.value_or(scene.settings.connect_reflections);
  r.contributions = options.contributions.value_or(scene.settings.contributions);
  // A quasi-random run: its replicates' blocks end to end (run/replicate_run.hpp); refused
  // before any shadow ray is traced for it.
  const auto qmc = detail::plan_replicates(scene, options, r, resume, *state_->backend);
  // Shadow rays stop at a cancel like photons; with several processes only at the agreed stops
  // (every process traces the same parts).
  const std::function<bool()> stop_direct = [&] {
    return !options.processes && options.cancel && options.cancel->load();
  };
  plan_direct_light(r, stop_direct);
  r.backend = state_->backend->name();
  r.total_flux_lm = prepared.total_flux_lm;
  detail::TallyBlock tallies(prepared.groups.size() * prepared.bins.size() *
                             (qmc ? qmc->replicates : 1));
  if (resume && state_->kept && state_->kept_seed == r.seed &&
      state_->kept_photons <= r.photons_requested &&
      state_->kept->bins.size() == tallies.bins.size() &&
      state_->kept_by_photons == detail::direct_by_photons_flags(prepared)) {
    tallies = *state_->kept;  // photons [0, kept_photons) are already traced
    r.photons = state_->kept_photons;
  }
  double tracing_s = 0.0;
  if (qmc) {
    tracing_s = detail::trace_replicates(*qmc, prepared, *state_->backend, state_->threads, options,
                                         progress, tallies, r);
  } else if (prepared.total_flux_lm > 0.0) {
    BatchLoop loop{scene,
                   prepared,
                   *state_->backend,
                   state_->threads,
                   options,
                   progress,
                   tallies,
                   r,
                   [&](std::uint64_t at) { return checkpoint_direct_light(r, at); }};
    tracing_s = loop.trace();
  } else {
    r.photons = r.photons_requested;  // nothing to trace: every estimate is exactly zero
  }
  const std::string direct_note = finish_direct_light(r, stop_direct);  // the planned parts
  r.partial = r.stop_reason == kStopCancelled;
  r.ray_segments = tallies.ray_segments;
  r.capped_paths = tallies.capped_paths;
  r.cut_paths = tallies.cut_paths;
  r.openings = {tallies.opening_photons, tallies.opening_blocked, tallies.opening_glass};
  // The final results give every grid its Emin/Emax/U0/Ud intervals, judged or not (a report
  // prints them always); the batch looks above compute them only when they judge.
  r.targets = detail::all_targets(scene, prepared, tallies, r.photons, r.confidence,
                                  /*grid_intervals=*/true, r.contributions);
  r.groups = detail::group_results(
      scene, prepared,
      qmc ? detail::grouped_tallies(prepared, tallies.bins, r.photons).photons
          : detail::group_photons(prepared.groups, prepared.total_flux_lm > 0.0 ? r.photons : 0));
  r.luminaires = detail::luminaire_results(scene, prepared);
  state_->kept = std::move(tallies);  // what refine() continues from
  state_->kept_photons = r.photons;
  state_->kept_seed = r.seed;
  state_->kept_by_photons = detail::direct_by_photons_flags(prepared);
  detail::add_verdicts(r);
  detail::add_to_decide(r, tracing_s > 0.0 ? double(r.photons) / tracing_s : 0.0);
  detail::add_warnings(scene, r);
  add_stop_warnings(r);
  if (!direct_note.empty()) r.warnings.push_back(direct_note);
  detail::report_effects(scene, prepared, r);  // effects simulated/skipped, dark targets
  for (const GroupResult& g : r.groups) {
    if (g.flux_lm > 0.0 && g.photons == 0 && r.photons > 0) {
      r.warnings.push_back("luminaire group \"" + g.name +
                           "\" got no photon (fewer photons than groups): its light is missing");
    }
  }
  r.warnings.insert(r.warnings.end(), prepared.warnings.begin(), prepared.warnings.end());
  r.warnings.insert(r.warnings.end(), state_->backend_notes.begin(), state_->backend_notes.end());
  if (scene.sunlight_exposure) r.sunlight_exposure = sunlight_exposure(scene);
  r.seconds = seconds_since(start);
  const int threads =
      state_->threads > 0 ? state_->threads : tbb::this_task_arena::max_concurrency();
  r.provenance = detail::run_provenance(scene, options, r, threads, state_->backend->device(),
                                        started, std::chrono::system_clock::now());
  return r;
}

}  // namespace lightsolver
