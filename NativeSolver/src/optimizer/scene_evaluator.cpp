// SceneEvaluator: applies a configuration to a Simulation (luminaires replaced, movable meshes
// placed by instance transform), traces it and reduces the Results to the intention's
// estimates. Also the conservative U0 interval and the run / JSON helpers.
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <map>
#include <nlohmann/json.hpp>

#include "lightsolver/angles.hpp"
#include "lightsolver/optimizer/scene_problem.hpp"
#include "optimizer/equal_widths.hpp"
#include "optimizer/group_traces.hpp"
#include "optimizer/problem_provenance.hpp"
#include "types/luminaire_types.hpp"

namespace lightsolver::optimizer {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// Memory for kept group traces (least recently used dropped beyond it; results unchanged).
constexpr std::size_t kTraceCacheBytes = std::size_t(256) << 20;

// The field an aim variable turns (read_aim admits only types that have one).
glm::dvec3& aim_field(Luminaire& l) { return *detail::luminaire_type(l.type).aim(l); }

// Tilt from straight down and pan from +x (counter-clockwise seen from above), degrees.
std::pair<double, double> tilt_pan(const glm::dvec3& d) {
  const glm::dvec3 u = glm::normalize(d);
  return {std::acos(std::clamp(-u.z, -1.0, 1.0)) / kDeg, std::atan2(u.y, u.x) / kDeg};
}

glm::dvec3 direction_from(double tilt_deg, double pan_deg) {
  const double t = tilt_deg * kDeg, p = pan_deg * kDeg;
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), -std::cos(t)};
}

void place(Luminaire& l, const glm::dvec3& anchor) {
  detail::luminaire_type(l.type).move_to(l, anchor);
}

glm::dvec3 on_rectangle(const SceneVariable& v, const std::vector<double>& values) {
  return v.corner + values.at(v.first) * v.edge1 + values.at(v.first + 1) * v.edge2;
}

const TargetResult& find_result(const Results& r, const std::string& name) {
  for (const TargetResult& t : r.targets) {
    if (t.name == name) return t;
  }
  throw std::logic_error("optimizer: target \"" + name + "\" missing from the results");
}

}  // namespace

SceneChanges changes_for(const SceneProblem& p, const std::vector<double>& values) {
  std::map<std::size_t, Luminaire> lums;
  std::map<std::size_t, std::pair<double, double>> aims;  // luminaire -> (tilt, pan)
  auto lum = [&](std::size_t i) -> Luminaire& {
    return lums.try_emplace(i, p.scene.luminaires[i]).first->second;
  };
  // Per moved mesh: translation after rotation (T · R), whatever order the variables come in.
  std::map<std::size_t, glm::dmat4> moves;
  auto move = [&](std::size_t m) -> glm::dmat4& {
    return moves.try_emplace(m, glm::dmat4(1.0)).first->second;
  };
  SceneChanges c;
  for (const SceneVariable& v : p.variables) {
    switch (v.type) {
      case SceneVariable::Type::kPosition: {
        const glm::dvec3 at = on_rectangle(v, values);
        for (std::size_t k = 0; k < v.luminaires.size(); ++k) {
          place(lum(v.luminaires[k]), at + v.offsets[k]);
        }
        break;
      }
      case SceneVariable::Type::kTranslation:
        move(v.mesh) =
            glm::translate(glm::dmat4(1.0), on_rectangle(v, values) - v.anchor) * move(v.mesh);
        break;
      case SceneVariable::Type::kRotation: {
        const glm::dmat4 turn =
            glm::translate(glm::dmat4(1.0), v.pivot) *
            glm::rotate(glm::dmat4(1.0), glm::radians(values.at(v.first)), v.axis) *
            glm::translate(glm::dmat4(1.0), -v.pivot);
        move(v.mesh) = move(v.mesh) * turn;
        break;
      }
      case SceneVariable::Type::kAim: {
        const std::size_t i = v.luminaires[0];
        auto [it, fresh] = aims.try_emplace(i, tilt_pan(aim_field(lum(i))));
        (v.angle == SceneVariable::Angle::kTilt ? it->second.first : it->second.second) =
            values.at(v.first);
        break;
      }
      case SceneVariable::Type::kFlux:
        for (std::size_t i : v.luminaires) lum(i).flux_lm = values.at(v.first);
        break;
    }
  }
  for (const auto& [m, t] : moves) c.meshes.emplace_back(m, t);
  for (const auto& [i, tp] : aims) aim_field(lum(i)) = direction_from(tp.first, tp.second);
  for (auto& [i, l] : lums) c.luminaires.emplace_back(i, std::move(l));
  return c;
}

Scene apply_values(const SceneProblem& problem, const std::vector<double>& values) {
  Scene s = problem.scene;
  const SceneChanges c = changes_for(problem, values);
  for (const auto& [i, l] : c.luminaires) s.luminaires[i] = l;
  for (const auto& [m, t] : c.meshes) {
    for (glm::dvec3& v : s.meshes[m].vertices) v = glm::dvec3(t * glm::dvec4(v, 1.0));
  }
  validate(s);
  return s;
}

std::map<std::string, std::vector<double>> describe_values(const SceneProblem& p,
                                                           const std::vector<double>& values) {
  std::map<std::string, std::vector<double>> out;
  auto vec = [](const glm::dvec3& v) { return std::vector<double>{v.x, v.y, v.z}; };
  const SceneChanges c = changes_for(p, values);
  auto changed = [&](std::size_t i) -> Luminaire {
    for (const auto& [k, l] : c.luminaires) {
      if (k == i) return l;
    }
    return p.scene.luminaires[i];
  };
  for (const SceneVariable& v : p.variables) {
    const std::string mesh =
        v.type == SceneVariable::Type::kTranslation ? p.scene.meshes[v.mesh].name : std::string();
    if (!mesh.empty()) out[mesh] = vec(on_rectangle(v, values));
    if (v.type == SceneVariable::Type::kRotation) {
      out[p.scene.meshes[v.mesh].name + ".rotation_deg"] = {values.at(v.first)};
    }
    for (std::size_t i : v.luminaires) {
      Luminaire l = changed(i);
      if (v.type == SceneVariable::Type::kPosition) out[l.name] = vec(detail::anchor_of(l));
      if (v.type == SceneVariable::Type::kAim) out[l.name + ".direction"] = vec(aim_field(l));
      if (v.type == SceneVariable::Type::kFlux) out[l.name + ".flux_lm"] = {l.flux_lm};
    }
  }
  return out;
}

double uniformity_confidence(std::size_t cells, double confidence) {
  return 1.0 - (1.0 - confidence) / (double(cells) + 1.0);
}

Estimate uniformity_estimate(const TargetResult& grid, const TargetResult& wide,
                             double confidence) {
  Estimate u;
  if (grid.cells.empty() || grid.cells.size() != wide.cells.size()) return u;
  // m cells + the mean, each interval at uniformity_confidence(m): all hold at once with
  // probability >= confidence, so the min over cells is covered by [min low, min high].
  double min_low = INFINITY, min_high = INFINITY, min_mean = INFINITY;
  std::uint64_t min_hits = 0;
  for (std::size_t j = 0; j < grid.cells.size(); ++j) {
    min_low = std::min(min_low, wide.cells[j].ci_low);
    min_high = std::min(min_high, wide.cells[j].ci_high);
    const Estimate& c = grid.cells[j];
    if (c.mean < min_mean) min_mean = c.mean, min_hits = c.hits;
  }
  const Estimate& em = wide.estimate;
  u.mean = grid.estimate.mean > 0.0 ? min_mean / grid.estimate.mean : 0.0;
  u.ci_low = em.ci_high > 0.0 ? min_low / em.ci_high : 0.0;
  u.ci_high = em.ci_low > 0.0 ? std::min(1.0, min_high / em.ci_low) : 1.0;  // min <= mean always
  u.ci_low = std::min(u.ci_low, u.mean);
  u.ci_high = std::max(u.ci_high, u.mean);
  // compare() works on sigma: the half-width of this interval at the run's critical value.
  u.sigma = (u.ci_high - u.ci_low) / (2.0 * z_for_confidence(confidence));
  u.hits = min_hits;
  return u;
}

struct SceneEvaluator::Reuse {
  reuse::TracePlan plan;
  reuse::TraceCache cache;
  // The last evaluation's traces and fluxes: metrics that need another confidence level
  // (U0's simultaneous intervals) combine them again.
  std::vector<std::shared_ptr<const GroupTrace>> traces;
  std::vector<double> flux_lm;
  double installed_lm = 0.0;

  // The last evaluation's traces as Simulation::combine takes them (null: a dark group).
  std::vector<const GroupTrace*> parts() const {
    std::vector<const GroupTrace*> out;
    for (const auto& t : traces) out.push_back(t.get());
    return out;
  }
};

namespace {

// The problem's scene with the search's next-event setting (the Simulation validates it).
Scene with_next_event(const Scene& scene, const std::optional<std::string>& next_event) {
  Scene s = scene;
  if (next_event) s.settings.next_event = *next_event;
  return s;
}

}  // namespace

SceneEvaluator::SceneEvaluator(const SceneProblem& problem, int threads, const std::string& backend,
                               std::shared_ptr<ProcessGroup> processes,
                               std::optional<bool> reuse_traces,
                               const std::optional<std::string>& next_event)
    : problem_(problem),
      simulation_(with_next_event(problem.scene, next_event),
                  Simulation::Options{backend, threads, problem.movable_meshes()}),
      confidence_(problem.search.confidence),
      processes_(std::move(processes)) {
  next_event_.setting = simulation_.scene().settings.next_event;
  next_event_.reason = "no evaluation yet";
  const bool reuse = reuse_traces.value_or(problem.reuse_traces);
  reuse_ = std::make_unique<Reuse>(Reuse{reuse::plan_traces(problem, simulation_.groups(), reuse),
                                         reuse::TraceCache(reuse ? kTraceCacheBytes : 0),
                                         {},
                                         {},
                                         0.0});
  if (reuse) {
    // Photons shared by each group's flux at the largest levels, fixed for the search: a
    // group's photons (and so its trace) must not move when another group's flux does.
    apply(
        reuse::trace_values(problem, reuse_->plan,
                            problem.domain.values(Configuration(problem.domain.dimensions(), 0))));
    std::vector<double> weights;
    for (const LuminaireGroup& g : simulation_.groups()) weights.push_back(g.flux_lm);
    simulation_.fix_photon_shares(weights);
  }
}

SceneEvaluator::~SceneEvaluator() = default;

void SceneEvaluator::apply(const std::vector<double>& values) {
  const SceneChanges c = changes_for(problem_, values);
  for (const auto& [i, l] : c.luminaires) simulation_.set_luminaire(i, l);
  for (const auto& [m, t] : c.meshes) simulation_.set_mesh_transform(m, t);
}

Estimate SceneEvaluator::metric(const Metric& m) const {
  switch (m.kind) {
    case MetricKind::kMeanIlluminance:
      return find_result(last_, m.target).estimate;
    case MetricKind::kUniformity: {
      const TargetResult& grid = find_result(last_, m.target);
      const Results wide = simulation_.combine(
          reuse_->parts(), reuse_->flux_lm, uniformity_confidence(grid.cells.size(), confidence_));
      return uniformity_estimate(grid, find_result(wide, m.target), confidence_);
    }
    case MetricKind::kInstalledFlux: {
      const double f = reuse_->installed_lm;
      return Estimate{f, 0.0, f, f, 0};
    }
    case MetricKind::kCustom:
      break;
  }
  throw std::logic_error("optimizer: the scene evaluator has no custom metrics");
}

// Whether this evaluation had direct parts: once one had, the search did.
void SceneEvaluator::note_next_event(const Results& r) {
  if (next_event_.direct) return;
  for (const SkippedEffect& e : r.effects.skipped) {
    if (e.effect == "next_event_direct") {
      next_event_.reason = e.reason;
      return;
    }
  }
  next_event_.direct = true;
  next_event_.reason.clear();
}

Evaluation SceneEvaluator::evaluate(const EvaluationRequest& r) {
  Evaluation e;
  const auto start = Clock::now();
  apply(reuse::trace_values(problem_, reuse_->plan, r.values));
  e.update_seconds = seconds_since(start);
  const auto trace_start = Clock::now();
  const std::vector<LuminaireGroup> groups = simulation_.groups();
  Reuse& k = *reuse_;
  k.traces.assign(groups.size(), nullptr);
  k.flux_lm.assign(groups.size(), 0.0);
  std::uint64_t traced = 0;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    k.flux_lm[g] = groups[g].flux_lm * reuse::flux_factor(problem_, k.plan, g, r.values);
    if (!(k.flux_lm[g] > 0.0)) continue;  // dark: its part is exactly zero, nothing to trace
    const std::uint64_t sub = reuse::sub_configuration(problem_.domain, k.plan, g, r.cells);
    const std::uint64_t level = r.seed_photons ? r.seed_photons : r.photons;
    const reuse::TraceCache::Key key{g, sub, r.photons, level};
    k.traces[g] = k.cache.find(key);
    if (k.traces[g]) continue;
    // A group that depends on the whole configuration gets the request's own seed.
    const std::uint64_t seed =
        sub == r.cell_index ? r.seed : evaluation_seed(r.run_seed, sub, level);
    // A staged refinement's earlier stage of this trace: continue it (same photons, bit for
    // bit). A stage's direct parts are its level's, which every later stage keeps: the level's
    // estimate then continues the stage's (docs/optimization.md §6, "Staged refinement").
    const std::shared_ptr<const GroupTrace> prefix = k.cache.find_prefix(key);
    k.traces[g] = std::make_shared<const GroupTrace>(
        simulation_.trace_group(g, r.photons, seed, processes_, prefix.get(), level));
    traced += k.traces[g]->photons - (prefix ? prefix->photons : 0);
    k.cache.insert(key, k.traces[g]);
  }
  last_ = simulation_.combine(k.parts(), k.flux_lm, confidence_);
  note_next_event(last_);
  k.installed_lm = reuse::installed_flux_lm(problem_, k.plan, simulation_.scene(), r.values);
  e.trace_seconds = seconds_since(trace_start);
  e.photons_traced = traced;
  e.objective = metric(problem_.intention.objective);
  for (const Constraint& c : problem_.intention.constraints)
    e.constraints.push_back(metric(c.metric));
  return e;
}

std::uint64_t stage_photons(const SceneProblem& problem, const RunOverrides& o,
                            const VnsOptions& search) {
  if (search.strategy != PhotonStrategy::kRefineAtEnd) return 0;
  const std::uint64_t n1 = o.refine_stage_photons.value_or(
      problem.refine_stage_photons.value_or(search.confirmation_photons / 4));
  return n1 < search.confirmation_photons ? n1 : 0;  // as many as N: unstaged
}

OptimizationResult run_problem(const SceneProblem& problem, const RunOverrides& o,
                               const Control& control) {
  VnsOptions opt = problem.search;
  if (o.iterations) opt.max_iterations = *o.iterations;
  if (o.seed) opt.seed = *o.seed;
  if (o.screening_photons) opt.screening_photons = *o.screening_photons;
  if (o.confirmation_photons) opt.confirmation_photons = *o.confirmation_photons;
  opt.refine_stage_photons = stage_photons(problem, o, opt);
  const auto started = std::chrono::system_clock::now();
  SceneEvaluator evaluator(problem, o.threads, o.backend, o.processes, o.reuse_traces,
                           o.next_event);
  std::optional<double> factor;
  double calibration_seconds = 0.0;
  if (o.match_widths.value_or(problem.match_widths)) {
    // docs/optimization.md §6, "Equal widths": measured with C = N/8 photons (at least 2 n)
    // at the first configuration the search traces with N; never below C photons (the ratio
    // is a large-count property, measured there), so N stays above n.
    const std::uint64_t photons =
        std::min(opt.confirmation_photons,
                 std::max(opt.confirmation_photons / 8, 2 * opt.screening_photons));
    opt.confirmation_factor = [&, photons](std::uint64_t cell) {
      const auto t0 = Clock::now();
      const double ratio =
          width_factor(problem, evaluator, o, opt, photons, problem.domain.configuration(cell));
      factor = std::max(ratio, double(photons) / double(opt.confirmation_photons));
      calibration_seconds = seconds_since(t0);
      return *factor;
    };
  }
  OptimizationResult r = optimize(problem.domain, problem.intention, evaluator, opt, control);
  const bool match = o.match_widths.value_or(problem.match_widths);
  if (factor) {  // the search's photon counts as it used them, for the provenance
    opt.confirmation_photons = scaled_photons(opt.confirmation_photons, *factor);
    if (opt.refine_stage_photons > 0) {
      opt.refine_stage_photons = scaled_photons(opt.refine_stage_photons, *factor);
    }
  }
  // The calibration's traces are the search's tracing too (they ran inside its total time).
  r.counters.trace_seconds += calibration_seconds;
  r.counters.other_seconds = std::max(0.0, r.counters.other_seconds - calibration_seconds);
  r.next_event = evaluator.next_event_use();
  const int threads = o.threads > 0 ? o.threads : tbb::this_task_arena::max_concurrency();
  r.provenance = search_provenance(
      problem, opt, o.reuse_traces.value_or(problem.reuse_traces), r.next_event->setting,
      evaluator.backend_name(), evaluator.device(), threads, o.processes ? o.processes->size() : 1,
      o.command, started, std::chrono::system_clock::now(), match, factor);
  return r;
}

std::string problem_result_json(const SceneProblem& problem, const OptimizationResult& result,
                                int indent) {
  nlohmann::ordered_json j = nlohmann::ordered_json::parse(to_json(result, -1));
  j["scene_file"] = problem.file;
  for (std::size_t i = 0; i < result.isoc.size(); ++i) {
    j["isoc"][i]["scene"] = describe_values(problem, result.isoc[i].values);
  }
  if (result.provenance) j["provenance"] = search_provenance_json(problem, *result.provenance);
  return j.dump(indent);
}

}  // namespace lightsolver::optimizer
