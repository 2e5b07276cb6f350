#pragma once
// The search behind optimize() (vns.hpp), shared by its two sources: vns.cpp (the walk: visits,
// descents, shakes, the ISOC) and refine.cpp (strategy B's end refinement, staged). Internal.
#include <chrono>
#include <optional>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "lightsolver/optimizer/vns.hpp"

namespace lightsolver::optimizer::search_detail {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Photons and time spent since the current iteration began.
struct IterationAccumulator {
  Clock::time_point t0 = Clock::now();
  double update = 0.0, trace = 0.0;
  std::uint64_t evaluations = 0, photons = 0;
};

class Search {
 public:
  Search(const Domain& d, const Intention& in, Evaluator& ev, const VnsOptions& o,
         const Control& ctl);

  OptimizationResult run();

 private:
  const Evaluation* evaluate(std::uint64_t cell, const Configuration& c, std::uint64_t photons,
                             bool ignore_limit = false);
  const Evaluation* evaluate_stage(std::uint64_t cell, std::uint64_t photons);
  const Evaluation* call_evaluator(std::uint64_t cell, const Configuration& c,
                                   std::uint64_t photons, std::uint64_t seed_photons);
  std::vector<std::uint64_t> staged_members(const std::vector<std::uint64_t>& keys);
  std::optional<std::uint64_t> stage_best(const std::vector<std::uint64_t>& keys, std::uint64_t n1);
  bool out_of_reach(const Estimate& x, const Estimate& b, std::uint64_t photons, double k) const;
  bool acceptable(const Evaluation& e) const;
  bool visit(const Configuration& c);
  void judge(std::uint64_t cell, const Configuration& c, const Evaluation& screen);
  void admit(std::uint64_t cell, std::uint64_t photons, const Evaluation& e);
  void record(std::uint64_t cell, std::uint64_t photons, const IsocUpdate& u);
  bool better(const Configuration& a, const Configuration& b) const;
  bool admissible(const Configuration& c) const { return !opt_.admissible || opt_.admissible(c); }
  Configuration random_start();
  bool check_stop(bool ignore_limit = false);
  void run_start(std::uint32_t s, std::uint64_t budget);
  Configuration descend(Configuration x);
  void begin_iteration() { it_ = {}; }
  void end_iteration(std::uint32_t start, std::uint32_t k);
  IterationStats snapshot() const;
  void report_evaluation();
  void refine();
  void match_confirmation(std::uint64_t cell);
  OptimizationResult build_result(Clock::time_point t0);

  const Domain& d_;
  const Intention& in_;
  Evaluator& ev_;
  const VnsOptions& opt_;
  const Control& ctl_;
  std::uint64_t n_ = 0, N_ = 0;
  bool two_levels_ = false;
  std::uint64_t stage_photons_ = 0;  // the staged refinement's first stage, N1
  bool matched_ = false;             // confirmation_factor has been asked
  std::uint32_t kmax_ = 1;
  std::mt19937_64 rng_;
  TabuCache cache_;
  std::unordered_set<std::uint64_t> judged_;                // cells already offered (tabu)
  std::unordered_map<std::uint64_t, std::uint64_t> level_;  // member -> photons of its estimate
  // The staged refinement's first-stage estimates (their own level: not the tabu cache's).
  std::unordered_map<std::uint64_t, Evaluation> stage_;
  Evaluation latest_;  // the last evaluator call's result, before it is stored
  Isoc isoc_;
  Counters counters_;
  IterationAccumulator it_;
  std::vector<IterationStats> history_;
  std::optional<StopReason> stop_;
  Clock::time_point t0_ = Clock::now();
};

}  // namespace lightsolver::optimizer::search_detail
