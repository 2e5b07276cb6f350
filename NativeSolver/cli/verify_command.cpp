// `lightsolver verify` and `lightsolver check`: the scene and results checks the report and the
// workbench run, from the command line. The same C++ functions as Python's
// lightsolver.verify_results and lightsolver.check_scene_file.
#include "verify_command.hpp"

#include <exception>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "lightsolver/provenance.hpp"
#include "lightsolver/scene_check.hpp"

namespace lightsolver::cli {
namespace {

struct VerifyArgs {
  std::string scene, results;
};

std::string read_text(const std::string& path, const char* what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", std::string("cannot read the ") + what);
  std::stringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path, "", std::string("cannot read the ") + what);
  return text.str();
}

int run_verify(const VerifyArgs& a) {
  try {
    const Verification v =
        verify_document(a.scene, read_text(a.results, "results file"), a.results);
    const char* what = v.optimization ? "optimizer output" : "results";
    if (v.differences.empty()) {
      std::cout << a.results << ": " << what << " belong" << (v.optimization ? "s" : "") << " to "
                << a.scene << "\n";
      for (const std::string& n : v.notes) std::cout << "  note: " << n << "\n";
      return 0;
    }
    std::cout << a.results << ": " << what << " do" << (v.optimization ? "es" : "")
              << " not belong to " << a.scene << ":\n";
    for (const std::string& d : v.differences) std::cout << "  " << d << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}

// "error: office.json: luminaires[2].flux_lm: must be >= 0", the line of a file where known.
// Warnings that begin with their field are printed as they are.
void print_issue(const char* kind, const SceneIssue& i) {
  const bool field_said = i.field.empty() || i.message.rfind(i.field, 0) == 0;
  std::cout << kind << ": " << (i.file.empty() ? "" : i.file + ": ")
            << (i.line > 0 ? "line " + std::to_string(i.line) + ": " : "")
            << (field_said ? "" : i.field + ": ") << i.message << "\n";
}

int run_check(const std::string& scene) {
  try {
    const SceneCheck c = check_scene_file(scene);
    for (const SceneIssue& i : c.errors) print_issue("error", i);
    for (const SceneIssue& i : c.warnings) print_issue("warning", i);
    std::cout << scene << ": " << c.errors.size()
              << (c.errors.size() == 1 ? " error, " : " errors, ") << c.warnings.size()
              << (c.warnings.size() == 1 ? " warning" : " warnings")
              << (c.errors.empty() ? "" : " (warnings are complete only without errors)") << "\n";
    return c.errors.empty() ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace

void add_verify_command(CLI::App& app) {
  auto args = std::make_shared<VerifyArgs>();
  CLI::App* cmd = app.add_subcommand(
      "verify",
      "Say whether a results file (or an optimizer's output) belongs to a scene: the scene's "
      "content and every file it reads (meshes, photometric files, requirements table) "
      "unchanged since the results were traced, and their flux record the solver's (rescaled "
      "groups are noted)");
  cmd->add_option("scene", args->scene, "Scene file (lightsolver.scene/1 JSON)")->required();
  cmd->add_option("results", args->results,
                  "Results file (lightsolver.results/1) or optimizer output "
                  "(lightsolver.optimization/1)")
      ->required();
  cmd->callback([args] {
    if (const int rc = run_verify(*args); rc != 0) throw CLI::RuntimeError(rc);
  });
}

void add_check_command(CLI::App& app) {
  auto scene = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "check", "List every error and warning of a scene without tracing it (exit 1 on errors)");
  cmd->add_option("scene", *scene, "Scene file (lightsolver.scene/1 JSON)")->required();
  cmd->callback([scene] {
    if (const int rc = run_check(*scene); rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace lightsolver::cli
