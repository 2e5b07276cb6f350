// Photon counts for equal interval widths under next-event estimation (equal_widths.hpp).
#include "optimizer/equal_widths.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace lightsolver::optimizer {

namespace {

Evaluation trace_at(SceneEvaluator& ev, const SceneProblem& problem, const VnsOptions& search,
                    const Configuration& cells, std::uint64_t photons) {
  const std::vector<double> values = problem.domain.values(cells);
  const std::uint64_t index = problem.domain.index(cells);
  const EvaluationRequest r{
      cells, values, index, photons, evaluation_seed(search.seed, index, photons), search.seed, 0};
  return ev.evaluate(r);
}

}  // namespace

double width_factor(const SceneProblem& problem, SceneEvaluator& with,
                    const RunOverrides& overrides, const VnsOptions& search, std::uint64_t photons,
                    const Configuration& cells) {
  const Evaluation on = trace_at(with, problem, search, cells, photons);
  if (!with.next_event_use().direct) return 1.0;  // every photon carries its own light
  SceneEvaluator without(problem, overrides.threads, overrides.backend, overrides.processes,
                         overrides.reuse_traces, std::string("off"));
  const Evaluation off = trace_at(without, problem, search, cells, photons);
  const double v_on = on.objective.sigma * on.objective.sigma;
  const double v_off = off.objective.sigma * off.objective.sigma;
  if (!(v_off > 0.0) || !std::isfinite(v_on / v_off)) return 1.0;
  return std::clamp(v_on / v_off, 1e-6, 1.0);
}

std::uint64_t scaled_photons(std::uint64_t photons, double factor) {
  return std::max<std::uint64_t>(1, std::llround(double(photons) * std::clamp(factor, 1e-9, 1.0)));
}

}  // namespace lightsolver::optimizer
