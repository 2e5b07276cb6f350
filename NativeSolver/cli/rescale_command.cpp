// `lightsolver rescale`: reads a results file traced with --contributions, multiplies each named
// group's flux by its factor (lightsolver/rescale.hpp) and prints or writes the new results.
#include "rescale_command.hpp"

#include <cstdlib>
#include <exception>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "lightsolver/output_file.hpp"
#include "lightsolver/rescale.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver::cli {
namespace {

struct RescaleArgs {
  std::string results, out;
  std::vector<std::string> dims;  // "G=0.5"
};

// "G=0.5" -> (G, 0.5); the factor's range is checked by rescale_results_json.
std::pair<std::string, double> parse_dim(const std::string& text, const std::string& file) {
  const auto eq = text.rfind('=');
  if (eq == std::string::npos || eq == 0) {
    throw InputError(file, "--dim " + text, "expected GROUP=FACTOR, e.g. --dim hall=0.5");
  }
  const std::string value = text.substr(eq + 1);
  char* end = nullptr;
  const double factor = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0') {
    throw InputError(file, "--dim " + text, "the factor \"" + value + "\" is not a number");
  }
  return {text.substr(0, eq), factor};
}

int run_rescale(const RescaleArgs& a) {
  try {
    GroupFactors factors;
    for (const std::string& d : a.dims) factors.push_back(parse_dim(d, a.results));
    if (!a.out.empty()) check_writable(a.out, "--out");
    std::ifstream in(a.results, std::ios::binary);
    if (!in) throw InputError(a.results, "", "cannot read the results file");
    std::stringstream text;
    text << in.rdbuf();
    const std::string json = rescale_results_json(text.str(), factors, a.results);
    if (a.out.empty()) {
      std::cout << json;
    } else {
      write_file_atomically(a.out, json);
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace

void add_rescale_command(CLI::App& app) {
  auto args = std::make_shared<RescaleArgs>();
  CLI::App* cmd = app.add_subcommand(
      "rescale",
      "Dim luminaire groups in a results file traced with --contributions: new estimates, "
      "intervals and verdicts without tracing");
  cmd->add_option("results", args->results, "Results file (lightsolver.results/1)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--dim", args->dims,
                  "GROUP=FACTOR: multiply the group's flux by FACTOR (0: off; repeatable)")
      ->take_all();
  cmd->add_option("--out", args->out, "Write the new results here (default: print them)");
  cmd->callback([args] {
    if (const int rc = run_rescale(*args); rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace lightsolver::cli
