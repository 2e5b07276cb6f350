// `lightsolver report`: hands the work to the report generator in Python (Jinja2, matplotlib,
// WeasyPrint: lightsolver_report, docs/report.md), which traces through the `lightsolver`
// module when no results are given. This file only finds Python and the package and execs.
#include "report_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "backend_option.hpp"

#ifndef LIGHTSOLVER_REPORT_PYTHONPATH
#define LIGHTSOLVER_REPORT_PYTHONPATH ""
#endif

namespace lightsolver::cli {
namespace {

constexpr const char* kDefaultPython = "/usr/bin/python3";

struct ReportArgs {
  std::string scene, results, out, date, title, save_results, backend = kAutoBackend;
  std::string annual;  // annual.json of `lightsolver annual`: the section "A year of daylight"
  std::string project, author, checked_by, project_number, client;  // the sign-off block
  std::optional<std::uint64_t> photons, seed;
  bool allow_partial = false, allow_unverified = false;
};

std::string env_or(const char* name, const std::string& fallback) {
  const char* value = std::getenv(name);
  return value != nullptr && *value != '\0' ? std::string(value) : fallback;
}

std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t end = std::min(path.find(':', start), path.size());
    if (end > start) parts.push_back(path.substr(start, end - start));
    start = end + 1;
  }
  return parts;
}

// The folders that hold lightsolver_report (and the lightsolver module), or an error.
std::string package_path() {
  const std::string path = env_or("LIGHTSOLVER_PYTHONPATH", LIGHTSOLVER_REPORT_PYTHONPATH);
  for (const std::string& dir : split_path(path)) {
    std::error_code ec;
    if (std::filesystem::exists(std::filesystem::path(dir) / "lightsolver_report" / "__init__.py",
                                ec))
      return path;
  }
  throw std::runtime_error("the report generator (Python package lightsolver_report) is not in '" +
                           path +
                           "'; build the project (cmake --build build) or set "
                           "LIGHTSOLVER_PYTHONPATH to the folder holding it");
}

std::vector<std::string> python_arguments(const std::string& python, const ReportArgs& a) {
  std::vector<std::string> argv{python, "-m", "lightsolver_report", "--out", a.out};
  const auto add = [&argv](const char* flag, const std::string& value) {
    if (!value.empty()) argv.insert(argv.end(), {flag, value});
  };
  add("--results", a.results);
  add("--annual", a.annual);
  add("--date", a.date);
  add("--title", a.title);
  add("--save-results", a.save_results);
  add("--backend", a.backend);
  if (a.photons) add("--photons", std::to_string(*a.photons));
  if (a.seed) add("--seed", std::to_string(*a.seed));
  add("--project", a.project);
  add("--author", a.author);
  add("--checked-by", a.checked_by);
  add("--project-number", a.project_number);
  add("--client", a.client);
  if (a.allow_partial) argv.emplace_back("--allow-partial");
  if (a.allow_unverified) argv.emplace_back("--allow-unverified");
  argv.insert(argv.end(), {"--", a.scene});  // a scene named "-x.json" is still the scene
  return argv;
}

[[noreturn]] void exec_report(const ReportArgs& a) {
  const std::string python = env_or("LIGHTSOLVER_PYTHON", kDefaultPython);
  if (access(python.c_str(), X_OK) != 0)
    throw std::runtime_error("lightsolver report needs Python 3: '" + python +
                             "' cannot be run (install python3, or set LIGHTSOLVER_PYTHON)");
  const std::string path = package_path();
  const std::string inherited = env_or("PYTHONPATH", "");
  const std::string full = inherited.empty() ? path : path + ":" + inherited;
  setenv("PYTHONPATH", full.c_str(), 1);
  std::vector<std::string> args = python_arguments(python, a);
  std::vector<char*> argv;
  for (std::string& s : args) argv.push_back(s.data());
  argv.push_back(nullptr);
  std::cout.flush();
  execv(python.c_str(), argv.data());
  throw std::runtime_error("cannot run '" + python + "': " + std::strerror(errno));
}

}  // namespace

void add_report_command(CLI::App& app) {
  auto args = std::make_shared<ReportArgs>();
  CLI::App* cmd = app.add_subcommand(
      "report",
      "Write the calculation report (HTML or PDF: luminaires, surfaces, Em/Emin/U0 with their "
      "intervals, verdicts, false-colour plans); traces first when no results are given");
  cmd->add_option("scene", args->scene, "Scene file (lightsolver.scene/1 JSON)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--results", args->results,
                  "Results of the scene (lightsolver run --out); without it the scene is traced "
                  "with its settings")
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", args->out, "Report file: .html or .pdf")->required();
  cmd->add_option("--annual", args->annual,
                  "Annual results of the scene (annual.json of lightsolver annual --out-dir): "
                  "the report gets a section on its year of daylight")
      ->check(CLI::ExistingFile);
  cmd->add_option("--date", args->date,
                  "Date printed on the report, YYYY-MM-DD (default: SOURCE_DATE_EPOCH, else "
                  "today), for reproducible output");
  cmd->add_option("--title", args->title, "Title (default: the scene's metadata or file name)");
  cmd->add_option("--photons", args->photons, "Photons when tracing (overrides settings.photons)");
  cmd->add_option("--seed", args->seed, "Seed when tracing (overrides settings.seed)");
  add_backend_option(cmd, args->backend);
  cmd->add_option("--save-results", args->save_results,
                  "When tracing, also write the results JSON here");
  cmd->add_flag("--allow-partial", args->allow_partial,
                "Report the results of a cancelled run (refused otherwise); every page then "
                "says they are partial");
  cmd->add_flag("--allow-unverified", args->allow_unverified,
                "Accept results that do not say which scene they were traced from (written "
                "before the solver recorded it); results shown to be of another scene are "
                "refused anyway");
  cmd->add_option("--project", args->project, "Project name for the sign-off block");
  cmd->add_option("--author", args->author, "Who made the calculation (sign-off block)");
  cmd->add_option("--checked-by", args->checked_by, "Who checked it (sign-off block)");
  cmd->add_option("--project-number", args->project_number,
                  "The project's number (sign-off block and cover; printed when given)");
  cmd->add_option("--client", args->client, "The client (sign-off block and cover; printed when given)");
  cmd->callback([args] {
    try {
      exec_report(*args);
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << "\n";
    }
    throw CLI::RuntimeError(1);
  });
}

}  // namespace lightsolver::cli
