#include "lightsolver/optimizer/vns.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

#include "search.hpp"

namespace lightsolver::optimizer {

namespace search_detail {

namespace {

void check_options(const Domain& d, const VnsOptions& o) {
  if (d.dimensions() == 0) throw std::invalid_argument("optimize: the domain has no variable");
  if (!(o.confidence > 0.0 && o.confidence < 1.0))
    throw std::invalid_argument("optimize: confidence must lie in (0, 1)");
  if (o.confirmation_photons == 0)
    throw std::invalid_argument("optimize: confirmation_photons (N) must be >= 1");
  if (o.starts == 0) throw std::invalid_argument("optimize: starts must be >= 1");
  for (const Configuration& c : o.initial) {
    if (!d.contains(c)) throw std::invalid_argument("optimize: initial configuration off the grid");
    if (o.admissible && !o.admissible(c))
      throw std::invalid_argument("optimize: initial configuration not admissible");
  }
}

std::uint32_t auto_kmax(const Domain& d) {
  // Radius that reaches every cell from any cell: the cycle k = 1..kmax then ranges from the
  // local ring to a global jump, so no basin is out of reach of the shake.
  std::uint32_t largest = 1;
  for (const Variable& v : d.variables()) largest = std::max(largest, v.size());
  return std::max<std::uint32_t>(1, largest - 1);
}

}  // namespace

Search::Search(const Domain& d, const Intention& in, Evaluator& ev, const VnsOptions& o,
               const Control& ctl)
    : d_(d), in_(in), ev_(ev), opt_(o), ctl_(ctl), rng_(o.seed), isoc_(in.goal, o.confidence) {
  N_ = o.confirmation_photons;
  two_levels_ = o.screening_photons > 0 && o.screening_photons < N_;
  n_ = two_levels_ ? o.screening_photons : N_;
  kmax_ = o.kmax > 0 ? o.kmax : auto_kmax(d);
  stage_photons_ = o.refine_stage_photons;
}

// Before the first trace with N: N (and the first stage) scaled by confirmation_factor at the
// cell about to be traced (docs/optimization.md §6, "Equal widths").
void Search::match_confirmation(std::uint64_t cell) {
  if (matched_ || !opt_.confirmation_factor) return;
  matched_ = true;
  const double f = std::clamp(opt_.confirmation_factor(cell), 1e-9, 1.0);
  const auto scaled = [f](std::uint64_t p) {
    return std::max<std::uint64_t>(1, std::llround(double(p) * f));
  };
  if (!two_levels_) n_ = scaled(n_);
  N_ = scaled(N_);
  if (stage_photons_ > 0) stage_photons_ = scaled(stage_photons_);
}

bool Search::check_stop(bool ignore_limit) {
  if (stop_ == StopReason::kCancelled) return true;
  if (ctl_.cancel && ctl_.cancel->load(std::memory_order_relaxed)) stop_ = StopReason::kCancelled;
  if (ignore_limit) return stop_ == StopReason::kCancelled;
  if (!stop_ && opt_.max_evaluations > 0 && counters_.evaluations >= opt_.max_evaluations)
    stop_ = StopReason::kEvaluationLimit;
  return stop_.has_value();
}

const Evaluation* Search::evaluate(std::uint64_t cell, const Configuration& c,
                                   std::uint64_t photons, bool ignore_limit) {
  if (const Evaluation* hit = cache_.find(cell, photons)) {
    ++counters_.cache_hits;
    return hit;
  }
  if (check_stop(ignore_limit)) return nullptr;
  if (!call_evaluator(cell, c, photons, 0)) return nullptr;
  if (photons == N_) ++counters_.confirmations;
  const Evaluation* stored = &cache_.insert(cell, photons, std::move(latest_));
  report_evaluation();
  return stored;
}

// One evaluator call, counted; its result in latest_.
const Evaluation* Search::call_evaluator(std::uint64_t cell, const Configuration& c,
                                         std::uint64_t photons, std::uint64_t seed_photons) {
  const std::vector<double> values = d_.values(c);
  const std::uint64_t level = seed_photons ? seed_photons : photons;
  const EvaluationRequest req{
      c, values, cell, photons, evaluation_seed(opt_.seed, cell, level), opt_.seed, seed_photons};
  Evaluation e = ev_.evaluate(req);
  if (e.constraints.size() != in_.constraints.size())
    throw std::invalid_argument(
        "optimize: the evaluator returned " + std::to_string(e.constraints.size()) +
        " constraint estimates, the intention has " + std::to_string(in_.constraints.size()));
  ++counters_.evaluations;
  counters_.photons += photons;
  counters_.photons_traced += e.photons_traced.value_or(photons);
  counters_.update_seconds += e.update_seconds;
  counters_.trace_seconds += e.trace_seconds;
  ++it_.evaluations;
  it_.photons += photons;
  it_.update += e.update_seconds;
  it_.trace += e.trace_seconds;
  latest_ = std::move(e);
  return &latest_;
}

// The run so far, for the per-evaluation callback: an iteration's descent may trace dozens of
// cells (2 per variable and step), so per-iteration progress alone can stay silent for minutes.
void Search::report_evaluation() {
  if (!ctl_.on_evaluation) return;
  IterationStats st = snapshot();
  st.iteration = counters_.iterations;
  if (!ctl_.on_evaluation(st)) stop_ = StopReason::kCancelled;
}

IterationStats Search::snapshot() const {
  IterationStats st;
  st.update_seconds = it_.update;
  st.trace_seconds = it_.trace;
  st.other_seconds = std::max(0.0, seconds_since(it_.t0) - it_.update - it_.trace);
  st.evaluations = it_.evaluations;
  st.photons = it_.photons;
  st.total_photons = counters_.photons;
  st.total_evaluations = counters_.evaluations;
  st.elapsed_seconds = seconds_since(t0_);
  st.isoc_size = isoc_.size();
  st.siisoc = isoc_.siisoc();
  if (const IsocMember* b = isoc_.best()) {
    st.has_best = true;
    st.best = b->estimate;
  }
  return st;
}

// Traces a cell (cache first) and, the first time, offers it to the ISOC. False when the run
// must stop before the cell could be traced.
bool Search::visit(const Configuration& c) {
  const std::uint64_t cell = d_.index(c);
  if (!admissible(c)) {
    if (judged_.insert(cell).second) ++counters_.inadmissible;
    return !stop_;
  }
  if (!two_levels_) match_confirmation(cell);
  const Evaluation* screen = evaluate(cell, c, n_);
  if (!screen) return false;
  if (judged_.insert(cell).second) judge(cell, c, *screen);
  return !stop_;
}

void Search::judge(std::uint64_t cell, const Configuration& c, const Evaluation& screen) {
  if (!two_levels_) return admit(cell, N_, screen);
  const Feasibility f = judge_all(screen.constraints, in_);
  if (f == Feasibility::kViolated) {
    ++counters_.infeasible;  // violated even with the wide n-photon CI: N cannot rescue it
    return;
  }
  bool precise;
  if (opt_.strategy == PhotonStrategy::kConfirm) {
    precise = isoc_.empty() || !isoc_.dominated(screen.objective);
    if (!precise) ++counters_.screened_out;
  } else {
    // Strategy B admits n estimates, but an uncertain verdict is settled with N right away:
    // otherwise a possibly-infeasible member could evict feasible ones and vanish at refinement.
    precise = f == Feasibility::kUncertain;
    if (!precise) return admit(cell, n_, screen);
  }
  if (!precise) return;
  match_confirmation(cell);
  if (const Evaluation* e = evaluate(cell, c, N_)) admit(cell, N_, *e);
}

void Search::admit(std::uint64_t cell, std::uint64_t photons, const Evaluation& e) {
  const Feasibility f = judge_all(e.constraints, in_);
  if (f == Feasibility::kViolated ||
      (f == Feasibility::kUncertain && opt_.uncertain == UncertainPolicy::kReject)) {
    ++counters_.infeasible;
    return;
  }
  const IsocUpdate u = isoc_.update(cell, e.objective);
  record(cell, photons, u);
  if (u.admitted()) level_[cell] = photons;
  for (std::uint64_t k : u.removed) level_.erase(k);
}

void Search::record(std::uint64_t cell, std::uint64_t photons, const IsocUpdate& u) {
  ++counters_.cases[static_cast<std::size_t>(u.result)];
  if (ctl_.on_update) ctl_.on_update(d_.configuration(cell), photons, u);
}

// Navigation only: fewer constraint misses first, then the better mean. Statistical caution
// lives in the ISOC; demanding >α here would freeze the walk on the plateau of
// indistinguishable cells that surrounds every optimum.
bool Search::better(const Configuration& a, const Configuration& b) const {
  const Evaluation* ea = cache_.most_precise(d_.index(a));
  const Evaluation* eb = cache_.most_precise(d_.index(b));
  if (!ea) return false;  // untraced (inadmissible) cells lose against anything traced
  if (!eb) return true;
  const double va = violation(ea->constraints, in_), vb = violation(eb->constraints, in_);
  if (va != vb) return va < vb;
  return in_.goal == Goal::kMaximize ? ea->objective.mean > eb->objective.mean
                                     : ea->objective.mean < eb->objective.mean;
}

Configuration Search::descend(Configuration cur) {
  // Terminates: a visited cell's estimates never change during the search, so each move is a
  // strict improvement of a fixed function over a finite grid.
  for (;;) {
    std::vector<Configuration> nbrs = d_.neighbours(cur, opt_.neighbourhood);
    const bool first = opt_.local_search == LocalSearch::kFirstImprovement;
    if (first)
      for (std::size_t i = nbrs.size(); i > 1; --i)
        std::swap(nbrs[i - 1], nbrs[uniform_below(rng_, i)]);
    Configuration best = cur;
    for (const Configuration& nb : nbrs) {
      if (!visit(nb)) return cur;
      if (better(nb, best)) {
        best = nb;
        if (first) break;
      }
    }
    if (best == cur) return cur;
    cur = std::move(best);
  }
}

void Search::run_start(std::uint32_t s, std::uint64_t budget) {
  Configuration x = s < opt_.initial.size() ? opt_.initial[s] : random_start();
  begin_iteration();
  if (visit(x)) x = descend(x);
  end_iteration(s, 0);
  std::uint32_t k = 1;
  for (std::uint64_t used = 1; used < budget && !stop_; ++used) {
    begin_iteration();
    const std::uint32_t k_used = k;
    const Configuration shaken = d_.shake(x, k, rng_);
    if (visit(shaken)) {
      Configuration y = descend(shaken);
      if (!stop_ && better(y, x)) {
        x = std::move(y);
        k = 1;
      } else {
        k = k >= kmax_ ? 1 : k + 1;
      }
    }
    end_iteration(s, k_used);
  }
}

// A random admissible cell: uniform by rejection while that succeeds quickly, then (for sparse
// filters) the first admissible cell after a random one. The scan is bounded: with several
// luminaires the grid has far too many cells to walk (6 luminaires on 48 places: 1.2e10), and a
// filter that admits nothing there (luminaires that cannot keep their spacing) must fail, not
// hang.
Configuration Search::random_start() {
  for (int tries = 0; tries < 4096; ++tries) {
    Configuration c = d_.random(rng_);
    if (admissible(c)) return c;
  }
  constexpr std::uint64_t kScanLimit = std::uint64_t{1} << 24;
  const std::uint64_t cells = d_.cell_count();
  const std::uint64_t first = uniform_below(rng_, cells);
  for (std::uint64_t i = 0; i < std::min(cells, kScanLimit); ++i) {
    Configuration c = d_.configuration((first + i) % cells);
    if (admissible(c)) return c;
  }
  throw std::invalid_argument(
      "optimize: no admissible configuration found (placement regions too small for the "
      "luminaires, or their minimum spacing too large?)");
}

void Search::end_iteration(std::uint32_t start, std::uint32_t k) {
  ++counters_.iterations;
  IterationStats st = snapshot();
  st.iteration = counters_.iterations;
  st.start = start;
  st.k = k;
  if (opt_.keep_history) history_.push_back(st);
  if (ctl_.progress && !ctl_.progress(st)) stop_ = StopReason::kCancelled;
  if (!stop_ && judged_.size() >= d_.cell_count()) stop_ = StopReason::kExhausted;
}

OptimizationResult Search::build_result(Clock::time_point t0) {
  OptimizationResult r;
  r.goal = in_.goal;
  r.confidence = opt_.confidence;
  for (const Variable& v : d_.variables()) r.variable_names.push_back(v.name);
  for (const IsocMember& m : isoc_.members()) {
    ResultMember rm;
    rm.cells = d_.configuration(m.key);
    rm.values = d_.values(rm.cells);
    rm.photons = level_.at(m.key);
    rm.objective = m.estimate;
    rm.constraints = cache_.find(m.key, rm.photons)->constraints;
    rm.feasibility = judge_each(rm.constraints, in_);
    r.isoc.push_back(std::move(rm));
  }
  const bool maximize = in_.goal == Goal::kMaximize;
  std::sort(r.isoc.begin(), r.isoc.end(), [&](const ResultMember& a, const ResultMember& b) {
    if (a.objective.mean != b.objective.mean)
      return maximize ? a.objective.mean > b.objective.mean : a.objective.mean < b.objective.mean;
    return d_.index(a.cells) < d_.index(b.cells);
  });
  r.siisoc = isoc_.siisoc();
  r.stop = stop_.value_or(StopReason::kIterationLimit);
  r.counters = counters_;
  r.counters.total_seconds = seconds_since(t0);
  r.counters.other_seconds = std::max(
      0.0, r.counters.total_seconds - r.counters.update_seconds - r.counters.trace_seconds);
  r.history = std::move(history_);
  return r;
}

OptimizationResult Search::run() {
  const Clock::time_point t0 = t0_;
  const std::uint64_t per_start = opt_.max_iterations / opt_.starts;
  const std::uint64_t extra = opt_.max_iterations % opt_.starts;
  for (std::uint32_t s = 0; s < opt_.starts && !stop_; ++s) {
    const std::uint64_t budget = per_start + (s < extra ? 1 : 0);
    if (budget > 0) run_start(s, budget);
  }
  if (two_levels_ && opt_.strategy == PhotonStrategy::kRefineAtEnd &&
      stop_ != StopReason::kCancelled)
    refine();
  return build_result(t0);
}

}  // namespace search_detail

const char* to_string(StopReason r) {
  switch (r) {
    case StopReason::kIterationLimit:
      return "iteration_limit";
    case StopReason::kEvaluationLimit:
      return "evaluation_limit";
    case StopReason::kExhausted:
      return "exhausted";
    case StopReason::kCancelled:
      return "cancelled";
  }
  return "?";
}

OptimizationResult optimize(const Domain& domain, const Intention& intention, Evaluator& evaluator,
                            const VnsOptions& options, const Control& control) {
  search_detail::check_options(domain, options);
  search_detail::Search search(domain, intention, evaluator, options, control);
  return search.run();
}

}  // namespace lightsolver::optimizer
