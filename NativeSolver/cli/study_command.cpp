// `lightsolver study`: one run with checkpoints at doubling photon counts; per row the tracing
// time, the per-cell interval widths and (with --reference) the actual error; then the photons
// and seconds per-cell accuracy goals need. CSV and JSON through the library
// (lightsolver/study.hpp); the plot is drawn by matplotlib in
// NativeSolver/python/tools/plot_study.py, run with the system Python: no plotting in C++.
#include "study_command.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>

#include "command_line.hpp"
#include "interrupt.hpp"
#include "lightsolver/output_file.hpp"
#include "lightsolver/scene_io.hpp"
#include "lightsolver/study.hpp"
#include "processes.hpp"
#include "run_option_flags.hpp"

namespace lightsolver::cli {
namespace {

namespace fs = std::filesystem;

struct StudyArgs {
  std::string scene, reference, csv, json, plot, out;
  SolveOptions solve;  // seed, confidence, threads, backend (flags from the run options table)
  std::uint64_t max_photons = StudyOptions{}.max_photons;
};

std::string percent(std::optional<double> v) {
  if (!v) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", 100.0 * *v);
  return buf;
}

void print_header(bool reference) {
  std::printf("%12s %9s %14s %14s", "photons", "seconds", "mean ±/E [%]", "worst ±/E [%]");
  if (reference) std::printf(" %13s %13s", "mean err [%]", "max err [%]");
  std::printf("\n");
}

void print_row(const StudyRow& r, bool reference) {
  const StudyStats& a = r.stats[0];
  std::printf("%12llu %9.3f %14s %14s", static_cast<unsigned long long>(r.photons), r.seconds,
              percent(a.mean_relative_half_width).c_str(),
              percent(a.worst_relative_half_width).c_str());
  if (reference) {
    std::printf(" %13s %13s", percent(a.mean_relative_error).c_str(),
                percent(a.max_relative_error).c_str());
  }
  std::printf("\n");
  std::fflush(stdout);
}

// Em, Emin and U0 of each target at the last row, then the goals.
void print_summary(const Study& st) {
  if (st.rows.empty()) return;
  const StudyRow& last = st.rows.back();
  std::printf("\nat %llu photons (%.0f%% confidence):\n",
              static_cast<unsigned long long>(last.photons), 100.0 * st.results.confidence);
  for (std::size_t i = 1; i < last.stats.size(); ++i) {
    const StudyStats& s = last.stats[i];
    std::printf("  %-24s Em %.2f [%.2f, %.2f] lx", s.target.substr(0, 24).c_str(), *s.em_lux,
                *s.em_ci_low_lux, *s.em_ci_high_lux);
    if (s.u0) std::printf(", Emin %.2f lx, U0 %.3f", *s.emin_lux, *s.u0);
    std::printf("\n");
  }
  if (!st.fit.coefficient) {
    std::printf("a target has no hit yet: no per-cell goal can be estimated\n");
    return;
  }
  std::printf(
      "per-cell accuracy (worst cell), fitted as width = %.3g / sqrt(photons) over the last %zu "
      "rows; time at the run's rate (%s backend, scene prepared once in %.3g s):\n",
      *st.fit.coefficient, st.fit.rows, st.results.backend.c_str(), st.prepare_seconds);
  for (const StudyGoal& g : st.goals) {
    std::printf("  ±%4.1f%%: %12.3g photons, %10.3g s%s\n", 100.0 * g.accuracy, *g.photons,
                *g.seconds, g.extrapolated ? "  (extrapolated beyond the last checkpoint)" : "");
  }
  for (const std::string& w : st.warnings) std::printf("warning: %s\n", w.c_str());
}

// The plotting script: $LIGHTSOLVER_TOOLS_DIR, the installed copy, or the source tree's.
fs::path plot_script() {
  std::vector<fs::path> dirs;
  if (const char* env = std::getenv("LIGHTSOLVER_TOOLS_DIR")) dirs.emplace_back(env);
  dirs.emplace_back(LIGHTSOLVER_INSTALL_TOOLS_DIR);
  dirs.emplace_back(LIGHTSOLVER_SOURCE_TOOLS_DIR);
  for (const fs::path& d : dirs) {
    if (fs::is_regular_file(d / "plot_study.py")) return d / "plot_study.py";
  }
  std::string looked;
  for (const fs::path& d : dirs) looked += (looked.empty() ? "" : ", ") + d.string();
  throw std::runtime_error("plot_study.py not found (looked in " + looked +
                           "; set LIGHTSOLVER_TOOLS_DIR)");
}

// Runs `python3 plot_study.py STUDY.json PLOT` (argv, no shell) and waits for it.
void draw_plot(const std::string& study_json, const std::string& plot) {
  const char* env_python = std::getenv("LIGHTSOLVER_PYTHON");
  const std::string python = env_python ? env_python : "/usr/bin/python3";
  const std::string script = plot_script().string();
  std::fflush(stdout);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("cannot start " + python + " to draw the plot");
  if (pid == 0) {
    execl(python.c_str(), python.c_str(), script.c_str(), study_json.c_str(), plot.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error(plot + ": the plot was not drawn (" + python + " " + script +
                             " exited with status " + std::to_string(WEXITSTATUS(status)) + ")");
  }
}

void check_outputs(const StudyArgs& a) {
  if (study_checkpoints(a.max_photons).empty()) {
    throw InputError("", "--max-photons", "must be >= 10000");
  }
  if (!a.plot.empty()) {
    const std::string ext = fs::path(a.plot).extension().string();
    if (ext != ".png" && ext != ".svg") {
      throw InputError(a.plot, "--plot", "must end in .png or .svg");
    }
    check_writable(a.plot, "plot");
  }
  if (!a.csv.empty()) check_writable(a.csv, "CSV file");
  if (!a.json.empty()) check_writable(a.json, "study JSON file");
  if (!a.out.empty()) check_writable(a.out, "results file");
}

int run_study_command(const StudyArgs& a) {
  check_outputs(a);  // before any tracing
  const Scene scene = load_scene(a.scene);
  StudyOptions o;
  o.solve = a.solve;
  o.solve.cancel = &interrupted();
  o.solve.processes = processes();
  o.solve.command = command_line();
  o.max_photons = a.max_photons;
  o.reference_file = a.reference;
  const bool reference = !a.reference.empty();
  bool header = false;
  const Study st = [&] {
    const InterruptScope ctrl_c;
    return run_study(scene, o, [&](const StudyRow& r) {
      if (!header) print_header(reference), header = true;
      print_row(r, reference);
    });
  }();
  print_summary(st);
  const std::string json = study_to_json(st);
  if (!a.csv.empty()) write_file_atomically(a.csv, study_to_csv(st));
  if (!a.json.empty()) write_file_atomically(a.json, json);
  if (!a.out.empty()) write_file_atomically(a.out, results_to_json(st.results));
  if (!a.plot.empty() && reports()) {
    // The script reads the study JSON: the one asked for, else a temporary copy.
    std::string path = a.json;
    if (path.empty()) {
      path =
          (fs::temp_directory_path() / ("lightsolver-study-" + std::to_string(getpid()) + ".json"))
              .string();
      write_file_atomically(path, json);
    }
    try {
      draw_plot(path, a.plot);
    } catch (...) {
      if (a.json.empty()) fs::remove(path);
      throw;
    }
    if (a.json.empty()) fs::remove(path);
    std::printf("plot written to %s\n", a.plot.c_str());
  }
  return st.results.partial ? 130 : 0;
}

}  // namespace

void add_study_command(CLI::App& app) {
  auto a = std::make_shared<StudyArgs>();
  CLI::App* cmd = app.add_subcommand(
      "study",
      "What accuracy costs, shown: per-cell widths (and errors against a reference) at "
      "doubling photon counts of one run, the photons and seconds per accuracy");
  cmd->add_option("scene", a->scene, "Scene file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--max-photons", a->max_photons,
                  "Photons of the run; rows at 1e4, 2e4, 4e4, ... up to this")
      ->capture_default_str();
  cmd->add_option("--reference", a->reference,
                  "Results JSON of a long run of the same scene (or a closed form written as "
                  "one): rows then give the actual error");
  cmd->add_option("--csv", a->csv, "Write the rows as CSV here (one line per row and target)");
  cmd->add_option("--json", a->json, "Write the study as JSON here (lightsolver.study/1)");
  cmd->add_option("--plot", a->plot,
                  "Draw error and interval width against seconds (log-log) here: .png or .svg");
  cmd->add_option("--out", a->out, "Write the run's results JSON here (the last row's photons)");
  add_run_option_flags(cmd, a->solve, true);
  cmd->callback([a] {
    int rc = 1;
    try {
      rc = run_study_command(*a);
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << "\n";
    }
    if (rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace lightsolver::cli
