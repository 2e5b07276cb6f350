// The provenance of a search: the scene it started from, the solver and machine, the search's
// resolved settings and the domain (problem_provenance.hpp).
#include "optimizer/problem_provenance.hpp"

#include <algorithm>

#include "scene/provenance.hpp"

namespace lightsolver::optimizer {

Provenance search_provenance(const SceneProblem& problem, const VnsOptions& s, bool reuse_traces,
                             const std::string& next_event, const std::string& backend,
                             const std::string& device, int threads, int mpi_ranks,
                             const std::string& command,
                             std::chrono::system_clock::time_point started,
                             std::chrono::system_clock::time_point finished, bool match_widths,
                             std::optional<double> width_factor) {
  Provenance p;
  if (problem.scene.source) {
    p.scene_sha256 = problem.scene.source->sha256;
    p.files = problem.scene.source->files;
  }
  const BuildInfo build = build_info();
  p.solver_version = build.solver_version;
  p.source_commit = build.source_commit;
  p.build_type = build.build_type;
  p.backend = backend;
  p.device = device;
  p.mpi_ranks = mpi_ranks;
  p.threads = threads;
  using U = std::uint64_t;
  // The search block's settings as the run resolved them (the block's, or the overrides),
  // sorted by name as a run's options are.
  p.options = {
      {"confidence", s.confidence},
      {"confirmation_photons", U{s.confirmation_photons}},
      {"kmax", U{s.kmax}},
      {"local_search",
       std::string(s.local_search == LocalSearch::kFirstImprovement ? "first" : "best")},
      {"max_bounces", U{problem.scene.settings.max_bounces}},
      {"max_evaluations", U{s.max_evaluations}},
      {"max_iterations", U{s.max_iterations}},
      {"min_spacing_m", problem.min_spacing_m},
      {"neighbourhood",
       std::string(s.neighbourhood == Neighbourhood::kAxis ? "axis" : "chebyshev")},
      {"next_event", next_event},
      {"refine_stage_photons", U{s.refine_stage_photons}},
      {"reuse_traces", reuse_traces},
      {"screening_photons", U{s.screening_photons}},
      {"seed", U{s.seed}},
      {"starts", U{s.starts}},
      {"strategy",
       std::string(s.strategy == PhotonStrategy::kConfirm ? "confirm" : "refine_at_end")},
      {"uncertain", std::string(s.uncertain == UncertainPolicy::kReject ? "reject" : "accept")},
  };
  // Always, since it became the default: an output says whether its N was matched.
  p.options.push_back({"match_widths", match_widths});
  if (width_factor) p.options.push_back({"width_factor", *width_factor});
  std::sort(p.options.begin(), p.options.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  p.started_utc = lightsolver::detail::utc_text(started);
  p.finished_utc = lightsolver::detail::utc_text(finished);
  p.host = lightsolver::detail::host_name();
  p.command = command.empty() ? "library call" : command;
  return p;
}

nlohmann::ordered_json search_provenance_json(const SceneProblem& problem, const Provenance& p) {
  nlohmann::ordered_json j = lightsolver::detail::provenance_json(p);
  j["optimization_sha256"] = problem.block_sha256;
  nlohmann::ordered_json domain = nlohmann::ordered_json::array();
  for (const Variable& v : problem.domain.variables()) {
    nlohmann::ordered_json d = {{"name", v.name}, {"cells", v.size()}};
    if (v.levels.empty()) {
      d["min"] = v.min;
      d["max"] = v.max;
      d["periodic"] = v.periodic;
    } else {
      d["levels"] = v.levels;
    }
    domain.push_back(std::move(d));
  }
  j["domain"] = std::move(domain);
  return j;
}

}  // namespace lightsolver::optimizer
