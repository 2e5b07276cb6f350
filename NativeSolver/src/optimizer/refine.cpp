// Strategy B's end refinement (docs/optimization.md §6): every n-level member traced with N and
// the ISOC rebuilt from those estimates; staged, members the best beats with room to spare at
// a fraction of their N stream are left out.
#include <algorithm>
#include <cmath>
#include <optional>
#include <unordered_map>
#include <vector>

#include "search.hpp"

namespace lightsolver::optimizer::search_detail {

namespace {

// The stages' photons: N1, 2 N1, 4 N1, ... below N (each continues the one before on the same
// N stream); the last stage is N itself.
std::vector<std::uint64_t> stage_schedule(std::uint64_t n1, std::uint64_t n) {
  std::vector<std::uint64_t> stages;
  for (std::uint64_t p = n1; p > 0 && p<n; p = p> n / 2 ? n : 2 * p) stages.push_back(p);
  return stages;
}

// Whether a stage estimate of P photons is the first part of the member's N estimate in the
// sense of docs/optimization.md §6 (E_N - E_P has standard deviation sigma_P sqrt(1 - P/N)): a
// mean illuminance is an average over the stream's photons (its direct part, if any, the N
// trace's own: EvaluationRequest::seed_photons); an exact metric does not vary. A U0 or a
// custom metric is not linear in the photons: the looser bound sqrt(2) sigma_P holds there.
bool nested_objective(const Intention& in) {
  return in.objective.kind == MetricKind::kMeanIlluminance ||
         in.objective.kind == MetricKind::kInstalledFlux;
}

}  // namespace

// A stage trace of the staged refinement: `photons` of the cell's N-photon stream (its N seed),
// kept apart from the tabu cache (the screening level may have as many photons). A later stage
// of the same cell continues it (the evaluator keeps the trace).
const Evaluation* Search::evaluate_stage(std::uint64_t cell, std::uint64_t photons) {
  if (check_stop(true)) return nullptr;
  if (!call_evaluator(cell, d_.configuration(cell), photons, N_)) return nullptr;
  ++counters_.refine_stage;
  const Evaluation* stored = &(stage_[cell] = std::move(latest_));
  report_evaluation();
  return stored;
}

// Strategy B: trace every member with N and rebuild the ISOC from those estimates, in cell
// order (the result does not depend on the order anyway, see isoc.hpp). The evaluation limit
// does not apply here, because skipping the refinement would report n-photon members as final.
void Search::refine() {
  std::vector<std::uint64_t> keys;
  for (const IsocMember& m : isoc_.members()) keys.push_back(m.key);
  std::sort(keys.begin(), keys.end());
  if (const IsocMember* best = isoc_.best()) match_confirmation(best->key);
  keys = staged_members(keys);
  if (stop_ == StopReason::kCancelled) return;  // keep the unrefined ISOC
  Isoc fresh(in_.goal, opt_.confidence);
  std::unordered_map<std::uint64_t, std::uint64_t> levels;
  for (std::uint64_t key : keys) {
    const bool traced = cache_.find(key, N_) != nullptr;
    const Evaluation* e = evaluate(key, d_.configuration(key), N_, /*ignore_limit=*/true);
    if (!e) return;  // cancelled: keep the unrefined ISOC
    if (!traced) ++counters_.refined;
    if (!acceptable(*e)) {
      ++counters_.infeasible;
      continue;
    }
    const IsocUpdate u = fresh.update(key, e->objective);
    record(key, N_, u);
    if (u.admitted()) levels[key] = N_;
    for (std::uint64_t k : u.removed) levels.erase(k);
  }
  isoc_ = std::move(fresh);
  level_ = std::move(levels);
}

// A member the refinement may keep: its constraints met (or uncertain, where accepted).
bool Search::acceptable(const Evaluation& e) const {
  const Feasibility f = judge_all(e.constraints, in_);
  return f == Feasibility::kMet ||
         (f == Feasibility::kUncertain && opt_.uncertain == UncertainPolicy::kAccept);
}

// The first stage: every member without an N estimate traced with N1 photons of its N stream;
// returns b, the best by mean (N estimates where there are) among the members whose
// constraints are met, or nothing (none met, or cancelled: stop_ says which).
std::optional<std::uint64_t> Search::stage_best(const std::vector<std::uint64_t>& keys,
                                                std::uint64_t n1) {
  const bool maximize = in_.goal == Goal::kMaximize;
  std::optional<std::uint64_t> best;
  double best_mean = 0.0;
  for (std::uint64_t key : keys) {
    const Evaluation* e = cache_.find(key, N_);
    if (!e) e = evaluate_stage(key, n1);
    if (!e) return std::nullopt;  // cancelled
    if (judge_all(e->constraints, in_) != Feasibility::kMet) continue;
    const double m = e->objective.mean;
    if (!best || (maximize ? m > best_mean : m < best_mean)) {
      best = key;
      best_mean = m;
    }
  }
  return best;
}

// Whether b's N estimate beats a member's P-photon stage estimate x with room to spare:
//   gap > z sqrt(s_N(b)^2 + s_P(x)^2) + k c s_P(x),   c = sqrt(1 - P/N) (nested), else sqrt(2),
// gap = E_N(b) - E_P(x) when maximising (mirrored). See staged_members for why.
bool Search::out_of_reach(const Estimate& x, const Estimate& b, std::uint64_t photons,
                          double k) const {
  const double z = z_for_confidence(opt_.confidence);
  const double c =
      nested_objective(in_) ? std::sqrt(1.0 - double(photons) / double(N_)) : std::sqrt(2.0);
  const double reach = z * std::hypot(b.sigma, x.sigma) + k * c * x.sigma;
  const double gap = in_.goal == Goal::kMaximize ? b.mean - x.mean : x.mean - b.mean;
  return gap > reach;
}

// The staged refinement (docs/optimization.md §6, "Staged refinement"): the members to trace
// with N. Stage 1 traces every member without an N estimate with N1 photons of its N stream;
// b, the best of them (stage_best), is traced with N. At each stage P = N1, 2 N1, 4 N1, ... < N
// a member x still in is left out when b's N estimate is out of reach (out_of_reach, k from
// Phi(-k) = (1 - confidence) / (M S), M members and S stages); the others continue to the next
// stage. If b does not beat a left-out x at N (compare(), s_N(x) <= s_P(x)), then
// E_N(x) - E_P(x) > k c s_P(x). Both estimate x's value without bias; the N trace continues
// the P trace's photons with the same direct part, so E_N - E_P = (1 - P/N)(E_rest - E_P) has
// sd s_P sqrt(1 - P/N) (c = sqrt(2) bounds any correlation for a metric not linear in the
// photons): probability <= Phi(-k) per member and stage, 1 - confidence for all. When b beats
// every left-out member the ISOC of the rest is the unstaged one: a member the unstaged
// refinement keeps is not beaten by b, so it is traced; one it drops is beaten by a member, by
// one left out and so (transitivity of compare()) by b, or by a traced one. A cancelled run
// returns every key (refine() keeps the unrefined ISOC).
std::vector<std::uint64_t> Search::staged_members(const std::vector<std::uint64_t>& keys) {
  const std::vector<std::uint64_t> stages = stage_schedule(stage_photons_, N_);
  if (stages.empty() || keys.size() < 2) return keys;
  const std::optional<std::uint64_t> best = stage_best(keys, stages.front());
  if (!best) return keys;
  const bool b_traced = cache_.find(*best, N_) != nullptr;
  const Evaluation* b = evaluate(*best, d_.configuration(*best), N_, /*ignore_limit=*/true);
  if (!b) return keys;
  if (!b_traced) ++counters_.refined;
  if (!acceptable(*b)) return keys;  // b may beat nothing at N: every member traced with N
  // Phi(-k) = (1 - confidence) / (M S): z_for_confidence is two-sided.
  const double tests = double(keys.size()) * double(stages.size());
  const double k = z_for_confidence(1.0 - 2.0 * (1.0 - opt_.confidence) / tests);
  std::vector<std::uint64_t> traced, live;
  for (std::uint64_t key : keys) (cache_.find(key, N_) ? traced : live).push_back(key);
  for (std::size_t s = 0; s < stages.size() && !live.empty(); ++s) {
    std::vector<std::uint64_t> next;
    for (std::uint64_t key : live) {
      const Evaluation* x = s == 0 ? &stage_.at(key) : evaluate_stage(key, stages[s]);
      if (!x) return keys;  // cancelled
      if (out_of_reach(x->objective, b->objective, stages[s], k)) {
        ++counters_.refine_dropped;
      } else {
        next.push_back(key);
      }
    }
    live = std::move(next);
  }
  traced.insert(traced.end(), live.begin(), live.end());
  std::sort(traced.begin(), traced.end());
  return traced;
}

}  // namespace lightsolver::optimizer::search_detail
