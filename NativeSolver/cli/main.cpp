// lightsolver: command-line front end. `lightsolver run SCENE.json` traces and prints a table.
#include <CLI/CLI.hpp>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>

#include "lightsolver/scene_io.hpp"
#include "lightsolver/solver.hpp"

namespace {

std::atomic<bool> g_interrupted{false};

void on_sigint(int) { g_interrupted.store(true); }

// Draws a bar on stderr once a run has lasted a second (short runs stay quiet), only on a
// terminal so logs are not filled with carriage returns.
class ProgressBar {
 public:
  bool operator()(std::uint64_t done, std::uint64_t total) {
    const double elapsed = std::chrono::duration<double>(clock::now() - start_).count();
    if (!tty_ || elapsed < 1.0) return true;
    const int width = 40, filled = static_cast<int>(width * double(done) / double(total));
    std::fprintf(stderr, "\r[%s%s] %5.1f%%  %.1f s", std::string(filled, '#').c_str(),
                 std::string(width - filled, '.').c_str(), 100.0 * double(done) / double(total),
                 elapsed);
    drawn_ = true;
    return true;
  }
  ~ProgressBar() {
    if (drawn_) std::fputc('\n', stderr);
  }

 private:
  using clock = std::chrono::steady_clock;
  clock::time_point start_ = clock::now();
  bool tty_ = isatty(STDERR_FILENO);
  bool drawn_ = false;
};

struct RunArgs {
  std::string scene, out, backend = "auto";
  std::optional<std::uint64_t> photons, seed;
  std::optional<double> confidence;
  int threads = 0;
  bool quiet = false;
};

int run(const RunArgs& a) {
  const lightsolver::Scene scene = lightsolver::load_scene(a.scene);
  lightsolver::SolveOptions opt;
  opt.photons = a.photons;
  opt.seed = a.seed;
  opt.confidence = a.confidence;
  opt.threads = a.threads;
  opt.backend = a.backend;
  opt.cancel = &g_interrupted;
  std::signal(SIGINT, on_sigint);
  lightsolver::Results results;
  {
    ProgressBar bar;
    results = lightsolver::solve(scene, opt, std::ref(bar));
  }
  std::signal(SIGINT, SIG_DFL);
  if (!a.quiet) std::cout << lightsolver::results_table(results);
  if (!a.out.empty()) {
    std::ofstream out(a.out);
    out << lightsolver::results_to_json(results);
    if (!out) throw std::runtime_error("cannot write " + a.out);
  }
  return results.partial ? 130 : 0;  // 128 + SIGINT, as shells report an interrupted command
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"lightsolver: photon-tracing illuminance solver (lux with confidence intervals)"};
  app.set_version_flag("--version", std::string("lightsolver ") + lightsolver::version());
  app.require_subcommand(1);

  RunArgs ra;
  CLI::App* run_cmd = app.add_subcommand("run", "Trace a scene and report illuminance per target");
  run_cmd->add_option("scene", ra.scene, "Scene file (lightsolver.scene/1 JSON)")
      ->required()
      ->check(CLI::ExistingFile);
  run_cmd->add_option("--photons", ra.photons, "Photon paths (overrides settings.photons)");
  run_cmd->add_option("--seed", ra.seed, "Random seed (overrides settings.seed)");
  run_cmd->add_option("--confidence", ra.confidence, "Confidence level, e.g. 0.95")
      ->check(CLI::Range(0.0, 1.0));
  run_cmd->add_option("--threads", ra.threads, "Worker threads (0: all cores)")
      ->check(CLI::NonNegativeNumber);
  run_cmd->add_option("--backend", ra.backend, "auto or embree")
      ->check(CLI::IsMember({"auto", "embree"}));
  run_cmd->add_option("--out", ra.out, "Write results JSON here");
  run_cmd->add_flag("--quiet,-q", ra.quiet, "Do not print the table");

  CLI11_PARSE(app, argc, argv);
  try {
    if (*run_cmd) return run(ra);
  } catch (const lightsolver::InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
