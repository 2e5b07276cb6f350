// Next-event estimation of direct light for a run (docs/statistics.md, "Next-event
// estimation"): which groups get it (estimate/next_event.hpp), how finely their direct parts
// are sampled for the run, when they are traced, and the parts kept for the next run with the
// same seed.
//
// A run without an accuracy goal traces the coarsest parts (the default strata) before its
// photons and the parts planned for its photon count after them: a run stopped during its
// photons still has whole direct parts, and the shadow rays it would have spent on the finer
// ones are not spent. A checkpoint (cost, study) gets the parts a plain run of its photons has.
// The connected reflected light (estimate/reflection_connection.hpp) follows the same plan: its
// fewest paths before the photons (the photons leave it their far reflected crossings, so a run
// stopped during them must have it whole), the planned paths after them.
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "estimate/direct_choice.hpp"
#include "estimate/next_event.hpp"
#include "estimate/reflection_connection.hpp"
#include "lightsolver/simulation.hpp"
#include "lightsolver/statistics.hpp"
#include "model/backend.hpp"  // DeviceLimitError
#include "prepare/scene_effects.hpp"
#include "run/simulation_state.hpp"

namespace lightsolver {

namespace {

using Clock = std::chrono::steady_clock;

// auto never costs a run far more than its photons: the fewest points (every cell's 32, every
// surface's 512) each send a ray to every luminaire of their group, which for thousands of
// luminaires in one group would be billions of rays for a small run.
constexpr double kAutoRaysPerPhoton = 4.0;
constexpr std::uint32_t kMaxStrataScale = 16;

// The strata scale of a run of `photons` photons without an accuracy goal: about one shadow ray
// per two photons (a shadow ray costs about a photon segment), at least the default strata.
std::uint32_t strata_scale_for(const detail::PreparedScene& p, std::uint64_t photons) {
  const double rays = double(detail::direct_ray_count(p, 1));
  const double fit = rays > 0.0 ? std::sqrt(0.5 * double(photons) / rays) : 1.0;
  return static_cast<std::uint32_t>(std::clamp(fit, 1.0, double(kMaxStrataScale)));
}

// Points for the judging parts: every target's, at the default strata.
constexpr std::uint32_t kJudgingScale = 1;

// A direct part whose interval is wider than half the accuracy goal.
bool too_wide(const std::vector<detail::DirectPart>& parts, const Results& r) {
  if (!r.target_accuracy) return false;
  const double z = z_for_confidence(r.confidence), half_goal = 0.5 * *r.target_accuracy;
  return std::any_of(parts.begin(), parts.end(), [&](const detail::DirectPart& d) {
    return d.lux > 0.0 && z * std::sqrt(d.variance) > half_goal * d.lux;
  });
}

// The parts in use: the direct parts plus, where the run connects, the connected ones.
void use_parts(detail::SimulationState& st) {
  st.prepared.direct = st.direct;
  if (st.connect_paths == 0) return;
  for (std::size_t i = 0; i < st.connected.size() && i < st.prepared.direct.size(); ++i) {
    st.prepared.direct[i].lux += st.connected[i].lux;
    st.prepared.direct[i].variance += st.connected[i].variance;
    st.prepared.direct[i].lit += st.connected[i].lit;
  }
}

// What use_connection() did: the connection asked for is in use; `stop` asked between two
// batches; or a device limit cut its paths (lavapipe's loop limit: model/backend.hpp).
enum class Connection { kUsed, kStopped, kCut };

// The connection of `paths` paths per group for the run's seed in use (the one kept when it is
// already traced); otherwise the connection in use stays unchanged. A device limit is passed on
// under "on" and, under "auto" (which can do without the connection), said in `why`.
Connection use_connection(detail::SimulationState& st, const Results& r, std::uint64_t paths,
                          const std::function<bool()>& stop, std::string& why) {
  if (!(st.connected_seed == r.seed && st.connected_paths == paths)) {
    const auto start = Clock::now();
    std::vector<detail::DirectPart> connected(st.prepared.groups.size() * st.prepared.bins.size());
    bool whole = false;
    try {
      tbb::task_arena arena(st.threads > 0 ? st.threads : tbb::task_arena::automatic);
      arena.execute([&] {
        whole = detail::add_connected_reflection(st.prepared, *st.backend, r.seed, paths, connected,
                                                 stop);
      });
    } catch (const detail::DeviceLimitError& e) {
      if (r.connect_reflections != "auto") {
        throw detail::DeviceLimitError(std::string(e.what()) +
                                       ", or connect_reflections \"auto\" or \"off\"");
      }
      why = std::string("auto: ") + e.what();
      return Connection::kCut;
    }
    if (!whole) return Connection::kStopped;
    st.connected = std::move(connected);
    st.connected_seed = r.seed;
    st.connected_paths = paths;
    st.connected_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  }
  st.connect_paths = paths;
  use_parts(st);
  return Connection::kUsed;
}

// The warning of a run whose connection a device limit kept at fewer paths than it wanted.
std::string connected_short(std::uint64_t paths, std::uint64_t wanted, const std::string& why) {
  return "reflected light connected from " + std::to_string(paths) +
         " paths per luminaire group (" + std::to_string(wanted) +
         " wanted), with wider intervals: " + why;
}

// A connected part whose half-width passes half the accuracy goal of its group's light at the
// bin (the direct and connected parts: the photons' near crossings only add to it).
bool connection_too_wide(const detail::SimulationState& st, const Results& r) {
  const double z = z_for_confidence(r.confidence), half_goal = 0.5 * *r.target_accuracy;
  for (std::size_t i = 0; i < st.connected.size() && i < st.direct.size(); ++i) {
    const detail::DirectPart& c = st.connected[i];
    if (c.lux > 0.0 && z * std::sqrt(c.variance) > half_goal * (c.lux + st.direct[i].lux)) {
      return true;
    }
  }
  return false;
}

// The connection before the photons, after the direct parts: an accuracy goal doubles its paths
// from the fewest until no connected part is too wide (at most kConnectMaxGoalPaths), deciding
// traces kConnectDecidePaths, a plain run the fewest (or the planned ones kept from the last run
// with its seed) and plans the rest after its photons (st.connect_final). Stopped before any
// connection was whole, or judged by `auto` not to pay: none, and the photons count every
// reflected crossing.
void plan_connected_light(detail::SimulationState& st, const Results& r,
                          const std::function<bool()>& stop) {
  detail::PreparedScene& p = st.prepared;
  const std::uint64_t planned = detail::connection_paths(p, r.photons_requested);
  if (planned == 0) return;
  const bool plain = !r.target_accuracy && !r.decide;
  std::uint64_t paths =
      r.decide && !r.target_accuracy ? detail::kConnectDecidePaths : detail::kConnectMinPaths;
  if (plain && st.connected_seed == r.seed && st.connected_paths == planned) paths = planned;
  std::string why;
  const Connection first = use_connection(st, r, paths, stop, why);
  if (first != Connection::kUsed) {
    detail::drop_connection(
        p, first == Connection::kCut
               ? why
               : "the run was stopped before its connected reflected light was traced");
    return;
  }
  if (r.connect_reflections == "auto" &&
      !detail::connection_pays(p, st.direct, st.connected, why)) {
    st.connect_paths = 0;
    detail::drop_connection(p, why);
    use_parts(st);
    return;
  }
  if (r.target_accuracy) {
    // Stopped half-way: the last whole connection stays (the run is cancelled); cut by a
    // device limit, it stays too and the warnings say why.
    while (paths < detail::kConnectMaxGoalPaths && connection_too_wide(st, r)) {
      const Connection more = use_connection(st, r, 2 * paths, stop, why);
      if (more == Connection::kCut) st.connect_note = connected_short(paths, 2 * paths, why);
      if (more != Connection::kUsed) break;
      paths *= 2;
    }
  }
  st.connect_final = plain ? planned : 0;
}

// A plain run's connection sized to the photons it traced (as its direct parts); stopped, the one
// traced before the photons stays and the note says so.
std::string finish_connection(detail::SimulationState& st, Results& r,
                              const std::function<bool()>& stop) {
  if (st.connect_final == 0 || st.connect_paths == 0) return {};
  const std::uint64_t paths =
      std::min(st.connect_final, detail::connection_paths(st.prepared, r.photons));
  std::string why;
  if (r.stop_reason != kStopCancelled) {
    const Connection planned = use_connection(st, r, paths, stop, why);
    if (planned == Connection::kUsed) return {};
    if (planned == Connection::kCut) return connected_short(st.connect_paths, paths, why);
  }
  if (st.connect_paths >= paths) return {};
  r.stop_reason = kStopCancelled;
  return "stopped before its reflected light was connected as planned: connected from " +
         std::to_string(st.connect_paths) + " paths per luminaire group (" + std::to_string(paths) +
         " planned), with wider intervals";
}

}  // namespace

// auto, per target (estimate/direct_choice.hpp): from parts of every target at the default
// strata, drawn from their own seed (the choice must not depend on the parts the run keeps, nor
// on its photons), against the photons planned: the run's, or for an accuracy goal those its
// direct light would need from the photons alone (its shadow rays judged at the default strata,
// where the goal's refinement starts). False when no target is left to the shadow rays or the
// judging was stopped: then no group has next-event estimation, and the reason says why.
bool detail::judge_direct_targets(detail::SimulationState& st, const Results& r,
                                  const std::function<bool()>& stop) {
  detail::PreparedScene& p = st.prepared;
  if (st.judging_seed != r.seed) {  // traced once per seed: the choice needs no photons
    std::optional<std::vector<detail::DirectPart>> parts;
    tbb::task_arena arena(st.threads > 0 ? st.threads : tbb::task_arena::automatic);
    arena.execute([&] {
      parts = detail::direct_parts_unless(p, *st.backend, detail::judging_seed(r.seed),
                                          kJudgingScale, stop);
    });
    if (parts) {
      st.judging = std::move(*parts);
      st.judging_seed = r.seed;
    }
  }
  const std::vector<detail::DirectPart>* judging =
      st.judging_seed == r.seed ? &st.judging : nullptr;  // null: stopped
  std::string why;
  if (judging) {
    std::uint64_t photons = r.photons_requested;
    std::uint32_t scale = kJudgingScale;
    if (r.target_accuracy) {
      photons =
          detail::goal_photons(p, *judging, *r.target_accuracy, z_for_confidence(r.confidence),
                               r.accuracy_per_cell, r.photons_requested);
    } else {
      scale = strata_scale_for(p, r.photons_requested);  // every target's rays: no more strata
    }
    std::vector<std::string> names;
    for (const Target& t : st.scene.targets) names.push_back(t.name);
    p.next_event_targets = detail::choose_direct_targets(p, *judging, photons, scale, names);
    const bool mixed = detail::any_target_by_photons(p) && detail::any_target_by_shadow_rays(p);
    if (mixed && !detail::analyse_effects(p).has(detail::Effect::Interreflection)) {
      // Where nothing reflects, the photons of a next-event group deposit nothing at the targets
      // with shadow rays (exactly zero, no interval); one target by photons would give every
      // other the photons' zero-hit bound, which the per-target rule does not weigh.
      detail::clear_direct_by_photons(p);
      p.next_event_targets =
          "shadow rays at every target: nothing reflects, and a target left to "
          "the photons would widen the others' intervals (" +
          p.next_event_targets + ")";
    }
    if (detail::any_target_by_shadow_rays(p)) return true;
    why = "auto: the photons are expected to be tighter at every target (" + p.next_event_targets +
          ")";
  } else {
    why = "the run was stopped before its direct light was traced";
  }
  detail::plan_next_event(p, *st.backend, "off");
  p.next_event_off = why;
  detail::plan_connection(p, *st.backend, r.connect_reflections, false, 0);
  return false;
}

bool Simulation::use_direct_parts(std::uint64_t seed, std::uint32_t scale,
                                  const std::function<bool()>& stop) {
  detail::SimulationState& st = *state_;
  if (!(st.direct_seed == seed && st.direct_strata_scale == scale)) {
    const auto start = Clock::now();
    std::optional<std::vector<detail::DirectPart>> parts;
    tbb::task_arena arena(st.threads > 0 ? st.threads : tbb::task_arena::automatic);
    arena.execute(
        [&] { parts = detail::direct_parts_unless(st.prepared, *st.backend, seed, scale, stop); });
    if (!parts) return false;  // stopped: the parts in use stay as they were
    st.direct = std::move(*parts);
    st.direct_seed = seed;
    st.direct_strata_scale = scale;
    st.direct_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  }
  use_parts(st);  // the connection in use, if any, stays
  return true;
}

// Which groups, and their first direct parts. An accuracy goal refines the parts before the
// photons until no direct part's half-width passes half the goal, and deciding keeps the
// default points (their stopping rules read them); any other run starts with the coarsest
// parts and finish_direct_light() traces the planned ones.
void Simulation::plan_direct_light(const Results& r, const std::function<bool()>& stop) {
  detail::SimulationState& st = *state_;
  detail::PreparedScene& p = st.prepared;
  st.direct_final_scale = 0;
  st.connect_paths = st.connect_final = 0;
  st.connect_note.clear();
  // A sobol run shares these parts among its replicates (model/replicates.hpp).
  detail::plan_next_event(p, *st.backend, r.next_event);
  // Connected reflected light (estimate/reflection_connection.hpp) builds on these groups.
  const bool goal_run = r.target_accuracy.has_value() || r.decide;
  detail::plan_connection(p, *st.backend, r.connect_reflections, goal_run, r.photons_requested);
  if (!std::any_of(p.groups.begin(), p.groups.end(),
                   [](const detail::PreparedGroup& g) { return g.next_event; })) {
    return;
  }
  const std::uint64_t fewest = detail::direct_ray_count(p, 1);
  if (r.next_event == "auto" && double(fewest) > kAutoRaysPerPhoton * double(r.photons_requested)) {
    detail::plan_next_event(p, *st.backend, "off");
    p.next_event_off = "its direct light would take " + std::to_string(fewest) +
                       " shadow rays, more than 4 per photon of the run (\"on\" traces them)";
    detail::plan_connection(p, *st.backend, r.connect_reflections, false, 0);  // on: refused
    return;
  }
  if (r.next_event == "auto" && !r.decide && !detail::judge_direct_targets(st, r, stop)) return;
  // Parts traced with other targets given back to the photons are not this run's.
  if (st.direct_by_photons != detail::direct_by_photons_flags(p)) {
    st.direct_seed.reset();
    st.direct_by_photons = detail::direct_by_photons_flags(p);
  }
  p.photons_reflect = detail::analyse_effects(p).has(detail::Effect::Interreflection);
  bool whole = true;
  if (r.target_accuracy) {
    for (std::uint32_t scale = 1;; scale *= 2) {
      whole = use_direct_parts(r.seed, scale, stop);
      if (!whole || scale >= kMaxStrataScale || !too_wide(p.direct, r)) break;
    }
  } else if (r.decide) {
    // Deciding judges its looks with the parts its results end with, so they are fixed before
    // the photons: the default points, whatever the budget (an open budget is 10^10 photons,
    // and the scene file must reproduce a run made with an explicit one).
    whole = use_direct_parts(r.seed, 1, stop);
  } else {
    st.direct_final_scale = strata_scale_for(p, r.photons_requested);
    const bool kept = st.direct_seed == r.seed && st.direct_strata_scale == st.direct_final_scale;
    whole = use_direct_parts(r.seed, kept ? st.direct_final_scale : 1, stop);
  }
  if (!whole) {  // stopped before any part was whole: the photons carry the direct light
    detail::plan_next_event(p, *st.backend, "off");
    p.next_event_off = "the run was stopped before its direct light was traced";
    st.direct_final_scale = 0;
    return;
  }
  plan_connected_light(st, r, stop);
}

double Simulation::checkpoint_direct_light(const Results& r, std::uint64_t photons) {
  detail::SimulationState& st = *state_;
  // none, or the parts an accuracy goal or deciding reads before the photons
  if (st.direct_final_scale == 0) return 0.0;
  const std::uint32_t scale = strata_scale_for(st.prepared, photons);
  // Never stopped half-way: a row is a whole estimate. A plain run of `photons` connects the
  // paths sized to them.
  if (st.connect_final > 0 && st.connect_paths > 0) {
    std::string why;  // cut by a device limit: the connection traced before the photons stays
    use_connection(st, r, detail::connection_paths(st.prepared, photons), {}, why);
  }
  use_direct_parts(r.seed, scale, {});
  return st.direct_seconds + (st.connect_paths > 0 ? st.connected_seconds : 0.0);
}

std::string Simulation::finish_direct_light(Results& r, const std::function<bool()>& stop) {
  detail::SimulationState& st = *state_;
  if (st.direct_final_scale == 0)
    return st.connect_note;  // a goal's parts are fixed before the photons
  // Sized to the photons traced: a run its time limit ended gets the parts of a plain run of
  // its photons (fewer than planned), not the shadow rays of the photons it did not trace.
  const std::uint32_t scale =
      std::min(st.direct_final_scale, strata_scale_for(st.prepared, r.photons));
  std::string note = st.connect_note;
  if (!(r.stop_reason != kStopCancelled && use_direct_parts(r.seed, scale, stop))) {
    // Stopped: the coarsest parts, traced before the photons, stay (whole, and honest).
    use_direct_parts(r.seed, 1, {});
    if (st.direct_final_scale > 1) {
      r.stop_reason = kStopCancelled;
      note += std::string(note.empty() ? "" : "; ") +
              "stopped before its direct light was sampled as planned: direct parts from the "
              "default points (32 per cell, 512 per surface target), with wider intervals";
    }
  }
  const std::string connected = finish_connection(st, r, stop);
  if (!connected.empty()) note += (note.empty() ? "" : "; ") + connected;
  return note;
}

}  // namespace lightsolver
