#pragma once
// --backend for `run`, `cost` and `optimize`: the choices and their help come from the library's
// registry (lightsolver/backends.hpp), so they list exactly the backends built.
#include <CLI/CLI.hpp>
#include <string>

#include "lightsolver/backends.hpp"

namespace lightsolver::cli {

inline void add_backend_option(CLI::App* command, std::string& backend) {
  std::string help = "Tracing backend:";
  for (const BackendInfo& b : backends()) help += " " + b.name + " (" + b.description + ");";
  help.back() = '.';
  command->add_option("--backend", backend, help)->check(CLI::IsMember(backend_names()));
}

}  // namespace lightsolver::cli
