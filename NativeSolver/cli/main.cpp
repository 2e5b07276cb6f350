// lightsolver: command-line front end. `lightsolver run SCENE.json` traces and prints a table.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>

#include "annual_command.hpp"
#include "command_line.hpp"
#include "interrupt.hpp"
#include "lightsolver/backends.hpp"
#include "lightsolver/cost.hpp"
#include "lightsolver/glare.hpp"
#include "lightsolver/mpi.hpp"
#include "lightsolver/output_file.hpp"
#include "lightsolver/photometry.hpp"
#include "lightsolver/run_options.hpp"
#include "lightsolver/scene_io.hpp"
#include "lightsolver/simulation.hpp"
#include "lightsolver/solver.hpp"
#include "lightsolver/timings.hpp"
#include "optimize_command.hpp"
#include "processes.hpp"
#include "report_command.hpp"
#include "rescale_command.hpp"
#include "run_option_flags.hpp"
#include "skymtx_command.hpp"
#include "study_command.hpp"
#include "sun_command.hpp"
#include "sunlight_command.hpp"
#include "verify_command.hpp"

namespace {

// Draws a bar on stderr once a run has lasted a second (short runs stay quiet), only on a
// terminal so logs are not filled with carriage returns.
class ProgressBar {
 public:
  bool operator()(std::uint64_t done, std::uint64_t total) {
    const double elapsed = std::chrono::duration<double>(clock::now() - start_).count();
    if (!tty_ || elapsed < 1.0) return true;
    const double fraction = std::min(1.0, this->fraction(done, total, elapsed));
    const int width = 40, filled = static_cast<int>(width * fraction);
    std::fprintf(stderr, "\r[%s%s] %5.1f%%  %.1f s", std::string(filled, '#').c_str(),
                 std::string(width - filled, '.').c_str(), 100.0 * fraction, elapsed);
    drawn_ = true;
    return true;
  }
  // What the run is expected to cost: an accuracy run's bar then measures the photons it is
  // expected to need (not its 1e10 budget), or the time limit when that comes first.
  void expect(const lightsolver::RunForecast& f) { forecast_ = f; }
  ~ProgressBar() {
    if (drawn_) std::fputc('\n', stderr);
  }
  // A line of its own on stderr (the bar, if drawn, continues below it).
  void note(const std::string& text) {
    if (drawn_) std::fputc('\n', stderr);
    std::fprintf(stderr, "%s\n", text.c_str());
    std::fflush(stderr);
  }

 private:
  double fraction(std::uint64_t done, std::uint64_t total, double elapsed) const {
    if (!forecast_) return double(done) / double(total);
    const double by_photons = double(done) / double(std::max<std::uint64_t>(forecast_->photons, 1));
    return forecast_->max_seconds ? std::max(by_photons, elapsed / *forecast_->max_seconds)
                                  : by_photons;
  }

  using clock = std::chrono::steady_clock;
  std::optional<lightsolver::RunForecast> forecast_;
  clock::time_point start_ = clock::now();
  bool tty_ = isatty(STDERR_FILENO);
  bool drawn_ = false;
};

// What `run` and `cost` take: the run options (flags from the table) and the files.
struct RunArgs {
  std::string scene, out;
  bool quiet = false;
  bool effects = false;  // list each effect the scene did not need, with why
  bool timings = false;  // print where the time went (main() enabled the recorder)
  lightsolver::SolveOptions options;
};

// The options of a run from the command line: a flag left out leaves the scene's setting.
lightsolver::SolveOptions options_from(const RunArgs& a) {
  lightsolver::SolveOptions opt = a.options;
  opt.cancel = &lightsolver::cli::interrupted();
  opt.processes = lightsolver::cli::processes();
  opt.command = lightsolver::cli::command_line();
  return opt;
}

// "0.8 s", "45 s", "4 min 10 s", "3 h 20 min", "2.5 days".
std::string duration_text(double s) {
  char buf[64];
  if (s < 10) {
    std::snprintf(buf, sizeof buf, "%.2g s", s);
  } else if (s < 59.5) {
    std::snprintf(buf, sizeof buf, "%.0f s", s);
  } else if (s < 3600) {
    const long t = std::lround(s);
    std::snprintf(buf, sizeof buf, "%ld min %ld s", t / 60, t % 60);
  } else if (s < 86400) {
    const long m = std::lround(s / 60);
    std::snprintf(buf, sizeof buf, "%ld h %ld min", m / 60, m % 60);
  } else {
    std::snprintf(buf, sizeof buf, "%.3g days", s / 86400);
  }
  return buf;
}

// The line printed when a run is expected to last more than a minute, e.g. "tracing 1e+09
// photons, about 4 min 10 s at 4e+06 photons/s".
std::string forecast_text(const lightsolver::RunForecast& f, std::optional<double> accuracy) {
  char head[160];
  if (f.accuracy_goal) {
    std::snprintf(head, sizeof head, "accuracy ±%g %%: about %.3g photons needed", 100 * *accuracy,
                  double(f.photons));
  } else {
    std::snprintf(head, sizeof head, "tracing %.3g photons", double(f.photons));
  }
  char rate[64];
  std::snprintf(rate, sizeof rate, " at %.2g photons/s", f.photons_per_second);
  std::string text = head + (", about " + duration_text(f.seconds)) + rate;
  if (f.max_seconds) {
    text += f.seconds > *f.max_seconds
                ? "; the time limit (" + duration_text(*f.max_seconds) + ") will end it first"
                : " (time limit " + duration_text(*f.max_seconds) + ")";
  }
  return text;
}

// `--timings`: the recorded phases on stderr, then the run's tracing by its own clock.
void print_timings(const lightsolver::Results& results) {
  namespace t = lightsolver::timings;
  std::fprintf(stderr, "%s", t::format(t::phases()).c_str());
  std::fprintf(stderr, "  %-40s %9.2f\n", "  of which the run (trace, estimates)",
               1e3 * results.seconds);
  std::fprintf(stderr, "  %-40s %9.2f\n", "before main (process CPU time)",
               t::cpu_ms_before_enable());
  std::fprintf(stderr, "  %-40s %9.3f\n", "main at CLOCK_MONOTONIC (ms)",
               t::monotonic_ms_at_enable());
}

// lightsolver::solve() for a scene straight from load_scene(): moved into the Simulation, not
// copied, and not validated a second time (start-up: docs/BENCHMARKS.md).
lightsolver::Results solve_loaded(lightsolver::Scene scene, const lightsolver::SolveOptions& opt,
                                  const lightsolver::ProgressFn& progress) {
  lightsolver::check_run_options(opt);  // before the backend is built, as solve() does
  lightsolver::Simulation::Options sim;
  sim.backend = opt.backend;
  sim.threads = opt.threads;
  sim.scene_validated = true;
  lightsolver::Simulation simulation(std::move(scene), sim);
  return simulation.run(opt, progress);
}

int run(const RunArgs& a) {
  if (a.options.accuracy_per_cell && !a.options.target_accuracy) {
    throw lightsolver::InputError("", "--per-cell", "needs --accuracy X (the goal per cell)");
  }
  if (!a.out.empty()) lightsolver::check_writable(a.out, "results file");  // before any tracing
  lightsolver::Scene scene = [&] {
    const lightsolver::timings::Scope phase("read scene");
    return lightsolver::load_scene(a.scene);
  }();
  lightsolver::SolveOptions opt = options_from(a);
  lightsolver::Results results;
  {
    const lightsolver::cli::InterruptScope ctrl_c;
    ProgressBar bar;
    opt.forecast = [&](const lightsolver::RunForecast& f) {
      bar.expect(f);
      if (f.seconds > 60.0) bar.note(forecast_text(f, a.options.target_accuracy));
    };
    const lightsolver::timings::Scope phase("solve");
    results = solve_loaded(std::move(scene), opt, std::ref(bar));
  }
  {
    const lightsolver::timings::Scope phase("write results (table, --out)");
    if (!a.quiet) std::cout << lightsolver::results_table(results, a.effects) << std::flush;
    if (!a.out.empty())
      lightsolver::write_file_atomically(a.out, lightsolver::results_to_json(results));
  }
  lightsolver::timings::mark("end of run");
  if (a.timings) print_timings(results);
  return results.partial ? 130 : 0;  // 128 + SIGINT, as shells report an interrupted command
}

// The footer of `cost`: photons and time per accuracy goal, from the last row.
void print_goals(const lightsolver::Cost& c, const lightsolver::Results& results) {
  std::printf(
      "\none run of %s (rows: its first photons; seconds: tracing only, the scene was "
      "prepared once in %.3g s)\n",
      results.backend.c_str(), c.prepare_seconds);
  if (!std::isfinite(c.rows.back().worst_relative_half_width)) {
    std::printf(
        "a target has no hit yet: no accuracy goal can be estimated (or reached) before "
        "light reaches every target\n");
    return;
  }
  std::printf("at %.0f%% confidence, from the last row (interval width ~ 1/sqrt(photons)):\n",
              100.0 * results.confidence);
  for (const lightsolver::CostGoal& g : c.goals) {
    std::printf("  ±%4.1f%%: %12.3g photons, %10.3g s\n", 100.0 * g.accuracy, g.need.photons,
                g.need.seconds);
  }
}

// What accuracy costs in time (lightsolver/cost.hpp): one run with checkpoints, a row each.
int cost(const RunArgs& a, std::uint64_t max_photons) {
  if (!a.out.empty()) lightsolver::check_writable(a.out, "results file");
  lightsolver::check_cost_photons(max_photons, "--max-photons");
  const lightsolver::Scene scene = lightsolver::load_scene(a.scene);
  lightsolver::CostOptions o;
  o.solve = options_from(a);
  o.max_photons = max_photons;
  std::printf("%14s %10s %16s %14s\n", "photons", "seconds", "worst ±/E [%]", "photons/s");
  const lightsolver::Cost c = [&] {
    const lightsolver::cli::InterruptScope ctrl_c;
    return lightsolver::run_cost(scene, o, [](const lightsolver::Checkpoint& row) {
      std::printf("%14llu %10.3f %16.3f %14.3g\n", static_cast<unsigned long long>(row.photons),
                  row.seconds, 100.0 * row.worst_relative_half_width,
                  double(row.photons) / std::max(row.seconds, 1e-9));
      std::fflush(stdout);
    });
  }();
  if (!a.out.empty())
    lightsolver::write_file_atomically(a.out, lightsolver::results_to_json(c.results));
  if (c.rows.empty()) {
    for (const std::string& w : c.results.warnings) std::cerr << "warning: " << w << "\n";
    return c.results.partial ? 130 : 1;
  }
  print_goals(c, c.results);
  return c.results.partial ? 130 : 0;
}

// `lightsolver backends`: the registry with what this machine can start (loads GPU drivers).
int list_backends() {
  for (const lightsolver::BackendInfo& b : lightsolver::available_backends()) {
    std::printf("%-8s %-9s %-13s %s\n", b.name.c_str(), b.gpu ? "GPU" : "",
                b.available.value_or(false) ? "available" : "not available", b.description.c_str());
  }
  return 0;
}

int photometry(const std::string& file, const std::string& plot, bool ugr_table) {
  if (!plot.empty()) lightsolver::check_writable(plot, "plot");
  const lightsolver::PhotometricData data = lightsolver::load_photometry(file);
  std::cout << lightsolver::photometry_summary(data);
  if (ugr_table) std::cout << "\n" << lightsolver::format_ugr_table(lightsolver::ugr_table(data));
  if (!plot.empty()) {
    lightsolver::write_polar_plot_png(data, plot);
    std::cout << "polar plot written to " << plot << "\n";
  }
  return 0;
}

}  // namespace

int run_command_line(int argc, char** argv) {
  CLI::App app{"lightsolver: photon-tracing illuminance solver (lux with confidence intervals)"};
  app.set_version_flag("--version", std::string("lightsolver ") + lightsolver::version());
  app.require_subcommand(1);

  RunArgs ra;
  CLI::App* run_cmd = app.add_subcommand("run", "Trace a scene and report illuminance per target");
  run_cmd->add_option("scene", ra.scene, "Scene file (lightsolver.scene/1 JSON)")
      ->required()
      ->check(CLI::ExistingFile);
  lightsolver::cli::add_run_option_flags(run_cmd, ra.options);
  run_cmd->add_option("--out", ra.out,
                      "Write results JSON here (checked before tracing, written atomically)");
  run_cmd->add_flag("--quiet,-q", ra.quiet, "Do not print the table");
  run_cmd->add_flag("--effects", ra.effects,
                    "After the table, list each effect the scene does not need (not simulated), "
                    "with why");
  run_cmd->add_flag("--timings", ra.timings,
                    "Print on stderr where the time went (ms): reading the scene, checks, "
                    "prepare, backend choice and build, the run, writing results");

  RunArgs ca;
  std::uint64_t max_photons = lightsolver::CostOptions{}.max_photons;
  CLI::App* cost_cmd =
      app.add_subcommand("cost", "Show what accuracy costs in time for a scene (photons vs CI)");
  cost_cmd->add_option("scene", ca.scene, "Scene file")->required()->check(CLI::ExistingFile);
  cost_cmd
      ->add_option("--max-photons", max_photons,
                   "Photons of the run; rows at 1e4, 4e4, ... up to this")
      ->capture_default_str();
  lightsolver::cli::add_run_option_flags(cost_cmd, ca.options, true);
  cost_cmd->add_option("--out", ca.out,
                       "Write the run's results JSON here (its photons are the last row's)");

  std::string photometry_file, plot_file;
  CLI::App* photometry_cmd = app.add_subcommand(
      "photometry", "Summarise an IES or EULUMDAT file (lumens, peak, beam and field angles)");
  photometry_cmd->add_option("file", photometry_file, "IES (.ies) or EULUMDAT (.ldt) file")
      ->required()
      ->check(CLI::ExistingFile);
  photometry_cmd->add_option("--plot", plot_file, "Write a polar diagram (PNG) here");
  bool ugr_table = false;
  photometry_cmd->add_flag("--ugr-table", ugr_table,
                           "Print the luminaire's UGR table (CIE 190 tabular method)");

  CLI::App* backends_cmd = app.add_subcommand(
      "backends", "List the tracing backends of this build and whether each can start here");

  lightsolver::cli::add_optimize_command(app);  // runs from its own callback
  lightsolver::cli::add_study_command(app);     // runs from its own callback
  lightsolver::cli::add_rescale_command(app);   // runs from its own callback
  lightsolver::cli::add_report_command(app);    // execs python3 -m lightsolver_report
  lightsolver::cli::add_verify_command(app);    // runs from its own callback
  lightsolver::cli::add_check_command(app);     // runs from its own callback
  lightsolver::cli::add_sun_command(app);       // runs from its own callback
  lightsolver::cli::add_weather_command(app);   // runs from its own callback
  lightsolver::cli::add_sunlight_command(app);  // runs from its own callback
  lightsolver::cli::add_skymtx_command(app);    // runs from its own callback
  lightsolver::cli::add_annual_command(app);    // runs from its own callback
  CLI11_PARSE(app, argc, argv);
  try {
    if (*run_cmd) return run(ra);
    if (*cost_cmd) return cost(ca, max_photons);
    if (*photometry_cmd) return photometry(photometry_file, plot_file, ugr_table);
    if (*backends_cmd) return list_backends();
  } catch (const lightsolver::InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

// `run ... --timings`: looked for before CLI11 parses, so the record starts at main.
bool wants_timings(int argc, char** argv) {
  if (argc < 2 || std::string(argv[1]) != "run") return false;
  for (int i = 2; i < argc; ++i) {
    if (std::string(argv[i]) == "--timings") return true;
  }
  return false;
}

// Under mpirun (docs/cluster.md) every process runs the same command: each traces a slice of
// every batch, rank 0 prints and writes. A failing process ends the whole job, so none is left
// waiting for it.
int main(int argc, char** argv) {
  std::optional<lightsolver::mpi::Session> session;
  // `report` execs Python, which joins the job through mpi4py (lightsolver_report.mpi_comm).
  const bool execs_python = argc > 1 && std::string(argv[1]) == "report";
  if (lightsolver::mpi::launched() && !execs_python) {
    try {
      session.emplace(&argc, &argv);
    } catch (const std::exception& e) {
      std::cerr << "error: started by an MPI launcher, but " << e.what()
                << ": every process would run the whole job alone\n";
      return 1;
    }
    lightsolver::cli::processes() = session->world();
    if (!lightsolver::cli::reports()) {
      lightsolver::skip_file_writes(true);
      if (std::freopen("/dev/null", "w", stdout) == nullptr) std::fclose(stdout);
    }
  }
  lightsolver::cli::command_line() = lightsolver::cli::quoted_command_line(argc, argv);
  if (wants_timings(argc, argv)) lightsolver::timings::enable();  // before the flags are parsed
  const int rc = run_command_line(argc, argv);
  if (session && rc == 1) session->abort("ending every process after the error above", rc);
  return rc;
}
