// `lightsolver optimize`: loads a scene with an optimization block, runs the VNS search with
// progress lines (iteration, best CI, ISOC size, photons, time split) and prints / writes the
// ISOC. Ctrl-C stops the search; the ISOC found so far is reported.
#include "optimize_command.hpp"

#include <cstdio>
#include <iostream>
#include <memory>

#include "backend_option.hpp"
#include "command_line.hpp"
#include "interrupt.hpp"
#include "lightsolver/optimizer/scene_problem.hpp"
#include "lightsolver/output_file.hpp"
#include "processes.hpp"

namespace lightsolver::cli {
namespace {

namespace opt = lightsolver::optimizer;

struct OptimizeArgs {
  std::string scene, out;
  opt::RunOverrides overrides;
  bool static_n = false, quiet = false, no_reuse = false;
};

void print_iteration(const opt::IterationStats& s) {
  std::printf("%6llu  k=%-3u ", static_cast<unsigned long long>(s.iteration), s.k);
  if (s.has_best) {
    std::printf("best %11.5g [%11.5g, %11.5g]", s.best.mean, s.best.ci_low, s.best.ci_high);
  } else {
    std::printf("best %37s", "(none feasible yet)");
  }
  std::printf("  isoc %4zu  photons %11.4g  ms: update %7.2f trace %8.2f other %6.2f\n",
              s.isoc_size, double(s.total_photons), 1e3 * s.update_seconds, 1e3 * s.trace_seconds,
              1e3 * s.other_seconds);
  std::fflush(stdout);
}

void print_summary(const opt::SceneProblem& p, const opt::OptimizationResult& r) {
  const opt::Counters& c = r.counters;
  const double it = c.iterations ? double(c.iterations) : 1.0;
  std::printf(
      "\nstop: %s after %llu iterations, %llu evaluations, %.4g photons (%.4g traced), "
      "%.2f s\n",
      opt::to_string(r.stop), static_cast<unsigned long long>(c.iterations),
      static_cast<unsigned long long>(c.evaluations), double(c.photons), double(c.photons_traced),
      c.total_seconds);
  std::printf("per iteration: update %.2f ms, tracing %.2f ms, rest %.2f ms, total %.2f ms\n",
              1e3 * c.update_seconds / it, 1e3 * c.trace_seconds / it, 1e3 * c.other_seconds / it,
              1e3 * c.total_seconds / it);
  if (r.next_event) {
    std::printf("next-event estimation (%s): %s\n", r.next_event->setting.c_str(),
                r.next_event->direct ? "direct light by shadow rays"
                                     : ("off: " + r.next_event->reason).c_str());
  }
  if (r.isoc.empty()) {
    std::printf("ISOC: empty (no configuration met the constraints)\n");
    return;
  }
  std::printf("ISOC: %zu configuration(s), SIISOC [%.6g, %.6g]\n", r.isoc.size(), r.siisoc.low,
              r.siisoc.high);
  for (const opt::ResultMember& m : r.isoc) {
    std::printf("  %.6g [%.6g, %.6g] cells", m.objective.mean, m.objective.ci_low,
                m.objective.ci_high);
    for (auto cell : m.cells) std::printf(" %u", cell);
    for (const auto& [name, v] : opt::describe_values(p, m.values)) {
      std::printf("  %s=(", name.c_str());
      for (std::size_t i = 0; i < v.size(); ++i) std::printf(i ? ", %.4g" : "%.4g", v[i]);
      std::printf(")");
    }
    std::printf("\n");
  }
}

int run_optimize(OptimizeArgs& a) {
  if (!a.out.empty()) check_writable(a.out, "results file");  // before any search
  const opt::SceneProblem problem = opt::load_problem(a.scene);
  if (a.static_n) a.overrides.screening_photons = 0;
  if (a.no_reuse) a.overrides.reuse_traces = false;
  a.overrides.processes = processes();
  a.overrides.command = command_line();
  opt::Control control;
  control.cancel = &interrupted();
  if (!a.quiet)
    control.progress = [](const opt::IterationStats& s) {
      print_iteration(s);
      return true;
    };
  const opt::OptimizationResult r = [&] {
    const InterruptScope ctrl_c;
    return opt::run_problem(problem, a.overrides, control);
  }();
  print_summary(problem, r);
  if (!a.out.empty()) write_file_atomically(a.out, opt::problem_result_json(problem, r) + "\n");
  return r.stop == opt::StopReason::kCancelled && interrupted().load() ? 130 : 0;
}

}  // namespace

void add_optimize_command(CLI::App& app) {
  auto args = std::make_shared<OptimizeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "optimize", "Search a scene's optimization block for the best configurations (ISOC)");
  cmd->add_option("scene", args->scene, "Scene file with an \"optimization\" block")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--iterations", args->overrides.iterations,
                  "VNS iterations (overrides search.max_iterations)");
  cmd->add_option("--seed", args->overrides.seed, "Search seed (overrides search.seed)");
  cmd->add_option("--out", args->out,
                  "Write the ISOC and statistics as JSON here (checked before the search)");
  cmd->add_option("--threads", args->overrides.threads, "Worker threads (0: all cores)")
      ->check(CLI::NonNegativeNumber);
  add_backend_option(cmd, args->overrides.backend);
  cmd->add_option("--screening-photons", args->overrides.screening_photons,
                  "n: photons of the first trace of every candidate");
  cmd->add_option("--confirmation-photons", args->overrides.confirmation_photons,
                  "N: photons of precise traces");
  cmd->add_option("--refine-stage-photons", args->overrides.refine_stage_photons,
                  "Strategy B: photons of the end refinement's first stage (0: every member "
                  "with N at once; default N/4)");
  cmd->add_flag("--static", args->static_n, "Always trace with N photons (no screening)");
  cmd->add_flag("--no-reuse", args->no_reuse,
                "Trace every luminaire group for every evaluation (search.reuse_traces = false)");
  cmd->add_option("--next-event", args->overrides.next_event,
                  "Direct light at the targets by shadow rays: auto, on or off (overrides "
                  "settings.next_event)")
      ->check(CLI::IsMember({"auto", "on", "off"}));
  cmd->add_option("--match-widths", args->overrides.match_widths,
                  "true (the default): with next-event estimation, scale N down to a "
                  "photon-only search's interval width; false: N as given (overrides "
                  "search.match_widths)");
  cmd->add_flag("--quiet,-q", args->quiet, "No per-iteration lines");
  cmd->callback([args] {
    int rc = 1;
    try {
      rc = run_optimize(*args);
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << "\n";
    }
    if (rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace lightsolver::cli
