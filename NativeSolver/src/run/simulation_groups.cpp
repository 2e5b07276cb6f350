// Groups traced apart and combined (docs/optimization.md, "Reused traces"): light is linear in
// each group's flux and each group has its own photon stream, so a configuration's results are
// the sum of its groups' traces, each scaled to the group's flux now. The optimizer keeps the
// traces of groups a configuration did not change, and traces no photon for a flux change.
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "estimate/decide.hpp"
#include "estimate/next_event.hpp"
#include "estimate/run_results.hpp"
#include "lightsolver/simulation.hpp"
#include "model/groups.hpp"
#include "prepare/scene_effects.hpp"
#include "run/shared_tracing.hpp"
#include "run/simulation_state.hpp"
#include "scene/provenance.hpp"

namespace lightsolver {

std::string Simulation::backend_name() const { return state_->backend->name(); }

std::string Simulation::device() const { return state_->backend->device(); }

std::vector<LuminaireGroup> Simulation::groups() const {
  std::vector<LuminaireGroup> out;
  for (const detail::PreparedGroup& g : state_->prepared.groups) {
    LuminaireGroup l{g.name, {}, g.flux_lm};
    l.luminaires.assign(g.luminaires.begin(), g.luminaires.end());
    out.push_back(std::move(l));
  }
  return out;
}

void Simulation::fix_photon_shares(const std::vector<double>& weights) {
  detail::PreparedScene& p = state_->prepared;
  const std::string& file = state_->scene.source_file;
  if (!weights.empty() && weights.size() != p.groups.size()) {
    throw InputError(file, "photon share weights",
                     std::to_string(weights.size()) + " weights for " +
                         std::to_string(p.groups.size()) + " luminaire groups");
  }
  for (double w : weights) {
    if (!(std::isfinite(w) && w >= 0.0)) {
      throw InputError(file, "photon share weights", "must be finite and >= 0");
    }
  }
  p.share_weights = weights;
  detail::set_photon_shares(p.groups, weights);
  state_->kept.reset();  // photon i of a group is another photon of the run now
}

// Group `t.group`'s direct parts (next-event estimation), its points sized as run() sizes
// them for a run of `run_photons` photons (about one shadow ray per two photons over every
// planned group: estimate/next_event.hpp), so that combining every group's trace equals run().
// Only this group's points are traced: each group's points have their own random stream.
void Simulation::trace_direct_part(GroupTrace& t, const GroupTrace* prefix,
                                   std::uint64_t run_photons) {
  detail::PreparedScene& p = state_->prepared;
  const double rays = double(detail::direct_ray_count(p, 1));
  const double fit = rays > 0.0 ? std::sqrt(0.5 * double(run_photons) / rays) : 1.0;
  const auto scale = static_cast<std::uint32_t>(std::clamp(fit, 1.0, 16.0));
  std::vector<bool> planned;
  for (detail::PreparedGroup& g : p.groups) {
    planned.push_back(g.next_event);
    g.next_event = false;
  }
  p.groups[t.group].next_event = true;
  t.shadow_rays = detail::direct_ray_count(p, scale);
  t.photons_reflect = detail::analyse_effects(p).has(detail::Effect::Interreflection);
  if (prefix && !prefix->direct.empty() && prefix->shadow_rays == t.shadow_rays) {
    // The same points (seed, strata) as the prefix's: its direct parts are this trace's.
    for (std::size_t g = 0; g < planned.size(); ++g) p.groups[g].next_event = planned[g];
    t.direct = prefix->direct;
    return;
  }
  std::vector<detail::DirectPart> parts;
  tbb::task_arena arena(state_->threads > 0 ? state_->threads : tbb::task_arena::automatic);
  try {
    arena.execute([&] { parts = detail::direct_parts(p, *state_->backend, t.seed, scale); });
  } catch (...) {
    for (std::size_t g = 0; g < planned.size(); ++g) p.groups[g].next_event = planned[g];
    throw;
  }
  for (std::size_t g = 0; g < planned.size(); ++g) p.groups[g].next_event = planned[g];
  const std::size_t bins = p.bins.size(), first = t.group * bins;
  t.direct.resize(bins);
  for (std::size_t b = 0; b < bins; ++b) {
    const detail::DirectPart& d = parts[first + b];
    t.direct[b] = {d.lux, d.variance, d.lit};
  }
}

GroupTrace Simulation::trace_group(std::size_t group, std::uint64_t run_photons, std::uint64_t seed,
                                   const std::shared_ptr<ProcessGroup>& processes,
                                   const GroupTrace* prefix, std::uint64_t direct_run_photons) {
  detail::PreparedScene& p = state_->prepared;
  const Scene& scene = state_->scene;
  if (group >= p.groups.size()) {
    throw InputError(scene.source_file, "group", "no luminaire group " + std::to_string(group));
  }
  if (!(p.groups[group].flux_lm > 0.0)) {
    throw InputError(scene.source_file, "group",
                     "luminaire group \"" + p.groups[group].name + "\" has no flux to trace");
  }
  check_photon_count(run_photons, scene.settings.max_bounces, "", "photons");
  if (prefix && (prefix->group != group || prefix->seed != seed ||
                 prefix->run_photons > run_photons || prefix->bins.size() != p.bins.size())) {
    throw std::invalid_argument("trace_group: the prefix is not this group's, seed's or run's");
  }
  GroupTrace out;
  out.started = std::chrono::system_clock::now();
  out.mpi_ranks = processes ? processes->size() : 1;
  out.group = group;
  out.run_photons = run_photons;
  out.photons = detail::group_photons(p.groups, run_photons)[group];
  out.seed = seed;
  out.flux_lm = p.groups[group].flux_lm;
  // Its direct light by shadow rays where the setting plans it (the plan also tells the
  // backend to skip this group's bounce-0 deposits).
  detail::plan_next_event(p, *state_->backend, scene.settings.next_event);
  if (scene.settings.next_event == "auto") {
    // The targets a run of run_photons gives back to the photons (the same judging parts), so
    // that combining equals run(); a continued trace keeps its prefix's choice, judged for the
    // prefix's run: its tallies were deposited with it.
    Results judged;
    judged.seed = seed;
    judged.photons_requested = prefix ? prefix->run_photons : run_photons;
    detail::judge_direct_targets(*state_, judged, {});
  }
  if (prefix && prefix->next_event_off.empty() != p.groups[group].next_event) {
    // Its photons deposited their bounce-0 light, or not, as this trace's must not.
    throw std::invalid_argument("trace_group: the prefix was traced with another next_event");
  }
  if (p.groups[group].next_event) {
    trace_direct_part(out, prefix, std::max(run_photons, direct_run_photons));
  } else {
    out.next_event_off = p.next_event_off.empty()
                             ? "luminaire group \"" + p.groups[group].name +
                                   "\" has a luminaire without direct sampling (sky, sun)"
                             : p.next_event_off;
  }
  // The backends write group g's bins at g x bins: a block for every group, one group filled.
  const std::size_t bins = p.bins.size();
  detail::TallyBlock block(p.groups.size() * bins);
  // A prefix's photons are this trace's first ones (group_photons is monotone in the run's
  // photons, photon i of a group's stream is photon i): continue after them. Its tallies are
  // integers, so the sum is the trace from photon 0 bit for bit.
  const std::uint64_t from = prefix ? prefix->photons : 0;
  if (prefix) {
    out.started = prefix->started;
    for (std::size_t b = 0; b < bins; ++b) block.bins[group * bins + b] = prefix->bins[b];
    block.ray_segments = prefix->ray_segments;
    block.capped_paths = prefix->capped_paths;
    block.cut_paths = prefix->cut_paths;
    block.opening_photons = prefix->openings.photons;
    block.opening_blocked = prefix->openings.blocked;
    block.opening_glass = prefix->openings.glass;
  }
  if (out.photons > from) {
    tbb::task_arena arena(state_->threads > 0 ? state_->threads : tbb::task_arena::automatic);
    detail::SharedTracing shared(processes.get(), block.bins.size());
    shared.trace(from, out.photons - from, block,
                 [&](std::uint64_t from, std::uint64_t count, detail::TallyBlock& into) {
                   const std::vector<detail::GroupRange> range{
                       {static_cast<std::uint32_t>(group), from, count}};
                   arena.execute([&] { state_->backend->trace(range, seed, into); });
                 });
  }
  const auto first = block.bins.begin() + static_cast<std::ptrdiff_t>(group * bins);
  out.bins.assign(first, first + static_cast<std::ptrdiff_t>(bins));
  out.ray_segments = block.ray_segments;
  out.capped_paths = block.capped_paths;
  out.cut_paths = block.cut_paths;
  out.openings = {block.opening_photons, block.opening_blocked, block.opening_glass};
  out.finished = std::chrono::system_clock::now();
  return out;
}

Results Simulation::combine(const std::vector<const GroupTrace*>& traces,
                            const std::vector<double>& flux_lm, double confidence) const {
  const detail::PreparedScene& p = state_->prepared;
  const Scene& scene = state_->scene;
  const std::size_t groups = p.groups.size(), bins = p.bins.size();
  if (traces.size() != groups || flux_lm.size() != groups) {
    throw std::invalid_argument("combine: one trace and one flux per luminaire group");
  }
  if (!(confidence > 0.0 && confidence < 1.0)) {
    throw InputError("", "confidence", "must lie strictly between 0 and 1");
  }
  std::vector<Tally> all(groups * bins);
  detail::GroupedTallies tallies{&all, bins, std::vector<std::uint64_t>(groups, 0), flux_lm};
  // The traces' direct parts (groups x bins, group-major like the tallies), each scaled from
  // the flux it was traced with to the group's flux now.
  std::vector<detail::DirectPart> direct;
  std::string next_event_off;
  tallies.direct_scale.assign(groups, 0.0);
  tallies.next_event.assign(groups, 0);
  Results r;
  for (std::size_t g = 0; g < groups; ++g) {
    if (!(std::isfinite(flux_lm[g]) && flux_lm[g] >= 0.0)) {
      throw std::invalid_argument("combine: a group's flux must be finite and >= 0");
    }
    const GroupTrace* t = traces[g];
    if (t == nullptr && flux_lm[g] > 0.0) {  // its light would be missing from the results
      throw std::invalid_argument("combine: group " + std::to_string(g) +
                                  " has a flux but no trace (a dark group's flux is 0)");
    }
    if (t == nullptr) continue;
    if (t->group != g || t->bins.size() != bins) {
      throw std::invalid_argument("combine: trace " + std::to_string(g) + " is not that group's");
    }
    std::copy(t->bins.begin(), t->bins.end(), all.begin() + static_cast<std::ptrdiff_t>(g * bins));
    if (!t->direct.empty()) {
      if (t->direct.size() != bins || !(t->flux_lm > 0.0)) {
        throw std::invalid_argument("combine: trace " + std::to_string(g) +
                                    "'s direct parts do not fit the scene");
      }
      if (direct.empty()) direct.resize(groups * bins);
      for (std::size_t b = 0; b < bins; ++b) {
        const DirectLight& d = t->direct[b];
        direct[g * bins + b] = {d.lux, d.variance_lx2, d.lit};
      }
      tallies.direct_scale[g] = flux_lm[g] / t->flux_lm;
      tallies.next_event[g] = 1;
      tallies.photons_reflect = t->photons_reflect;
    } else if (next_event_off.empty()) {
      next_event_off = t->next_event_off;
    }
    tallies.photons[g] = t->photons;
    r.photons += t->photons;
    r.ray_segments += t->ray_segments;
    r.capped_paths += t->capped_paths;
    r.cut_paths += t->cut_paths;
    r.openings.add(t->openings);
    if (r.seed == 0) r.seed = t->seed;
    if (flux_lm[g] > 0.0) r.total_flux_lm += flux_lm[g];
  }
  if (!direct.empty()) tallies.direct = &direct;
  r.photons_requested = r.photons;
  r.confidence = confidence;
  r.next_event = scene.settings.next_event;
  // The scene's effects, next-event estimation as the traces had it.
  detail::SceneEffects effects = detail::analyse_effects(p);
  effects.set(detail::Effect::NextEventDirect, !direct.empty(),
              next_event_off.empty() ? "no lit luminaire group traced" : next_event_off);
  effects.set(detail::Effect::ReflectionConnection, false, "group traces have no connections yet");
  r.effects = detail::effects_report(effects);
  r.backend = state_->backend->name();
  r.judged = detail::judges_requirements(scene, false, false);
  // Observers rate each luminaire's luminance, which follows its group's flux as combined.
  std::vector<Luminaire> luminaires = scene.luminaires;
  for (std::size_t g = 0; g < groups; ++g) {
    const double traced = p.groups[g].flux_lm;
    const double factor = traced > 0.0 ? flux_lm[g] / traced : 0.0;
    for (std::uint32_t l : p.groups[g].luminaires) luminaires[l].flux_lm *= factor;
  }
  r.targets = detail::all_targets(scene, p, tallies, confidence, /*grid_intervals=*/true, false,
                                  &luminaires);
  r.groups = detail::group_results(scene, p, tallies.photons);
  std::vector<double> dimming(groups, 0.0);
  for (std::size_t g = 0; g < groups; ++g) {
    r.groups[g].flux_lm = flux_lm[g];
    if (p.groups[g].flux_lm > 0.0) dimming[g] = flux_lm[g] / p.groups[g].flux_lm;
  }
  r.luminaires = detail::luminaire_results(scene, p, dimming);
  for (std::size_t g = 0; g < groups; ++g) r.rescaled.emplace_back(p.groups[g].name, dimming[g]);
  detail::add_verdicts(r);
  detail::add_warnings(scene, r);
  r.provenance = combined_provenance(traces, r);
  return r;
}

// The provenance of combined traces: what run() records, with the traces' own run facts.
Provenance Simulation::combined_provenance(const std::vector<const GroupTrace*>& traces,
                                           const Results& r) const {
  auto started = std::chrono::system_clock::time_point::max();
  auto finished = std::chrono::system_clock::time_point::min();
  int ranks = 1;
  bool one_seed = true;
  for (const GroupTrace* t : traces) {
    if (t == nullptr) continue;
    started = std::min(started, t->started);
    finished = std::max(finished, t->finished);
    ranks = std::max(ranks, t->mpi_ranks);
    one_seed = one_seed && t->seed == r.seed;
  }
  if (started > finished) started = finished = std::chrono::system_clock::now();  // all dark
  SolveOptions options;
  options.command = "library call: Simulation::combine (group traces)";
  const int threads =
      state_->threads > 0 ? state_->threads : tbb::this_task_arena::max_concurrency();
  Provenance p = detail::run_provenance(state_->scene, options, r, threads,
                                        state_->backend->device(), started, finished);
  p.mpi_ranks = ranks;
  if (!one_seed) {  // each group's own seed (the optimizer's reused traces): no single one
    for (auto& [name, value] : p.options) {
      if (name == "seed") value = OptionValue();
    }
  }
  return p;
}

}  // namespace lightsolver
