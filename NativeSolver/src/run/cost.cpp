// `lightsolver cost` and Python's `lightsolver.cost`: one checkpointed run (lightsolver/cost.hpp).
#include "lightsolver/cost.hpp"

#include <chrono>

#include "lightsolver/simulation.hpp"

namespace lightsolver {

void check_cost_photons(std::uint64_t max_photons, const std::string& where) {
  if (cost_checkpoints(max_photons).empty()) throw InputError("", where, "must be >= 10000");
}

Cost run_cost(const Scene& scene, const CostOptions& options,
              const std::function<void(const Checkpoint&)>& on_row) {
  check_cost_photons(options.max_photons, "max_photons");
  Cost cost;
  SolveOptions opt = options.solve;
  opt.checkpoints = cost_checkpoints(options.max_photons);
  opt.photons = opt.checkpoints.back();
  opt.checkpoint = [&](const Checkpoint& c) {
    cost.rows.push_back({c.photons, c.seconds, c.worst_relative_half_width, {}});
    if (on_row) on_row(cost.rows.back());
  };
  const auto start = std::chrono::steady_clock::now();
  Simulation simulation(scene, {opt.backend, opt.threads, {}});
  cost.prepare_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  cost.results = simulation.run(opt);
  if (!cost.rows.empty()) {
    for (const double goal : kCostGoals) {
      cost.goals.push_back({goal, accuracy_cost(cost.rows.back(), goal)});
    }
  }
  return cost;
}

}  // namespace lightsolver
