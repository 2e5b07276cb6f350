// The one-shot solve(): a Simulation used once (backends are chosen in model/backends.cpp).
#include "lightsolver/solver.hpp"

#include "lightsolver/run_options.hpp"
#include "lightsolver/simulation.hpp"

namespace lightsolver {

const char* version() { return LIGHTSOLVER_VERSION; }

Results solve(const Scene& scene, const SolveOptions& options, const ProgressFn& progress) {
  check_run_options(options);  // before the backend is built with `threads` and `backend`
  Simulation::Options sim;
  sim.backend = options.backend;
  sim.threads = options.threads;
  Simulation simulation(scene, sim);
  return simulation.run(options, progress);
}

}  // namespace lightsolver
