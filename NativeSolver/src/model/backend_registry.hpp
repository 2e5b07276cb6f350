#pragma once
// How a backend module makes itself known, so that core never includes a backend. Each module
// defines `BackendEntry <name>_backend_entry()` and calls lightsolver_add_backend(<name>) in its
// CMakeLists.txt; CMake then generates backend_list.cpp (from src/backend_list.cpp.in) calling
// exactly the modules that were built. An explicit generated list rather than self-registering
// static objects: those depend on static-initialisation order and a static library drops the
// object files nobody references.
#include <memory>
#include <vector>

#include "model/backend.hpp"

namespace lightsolver::detail {

struct BackendEntry {
  const char* name;
  const char* description;  // one line for help texts
  bool gpu;                 // traces through a GPU API; "auto" tries these before CPU backends
  bool (*available)();      // a device it can start on exists here (never throws)
  bool (*auto_picks)();     // "auto" may take it here: for a GPU backend, a real GPU (no throw)
  std::unique_ptr<Backend> (*make)(const PreparedScene& scene);  // std::runtime_error on failure
};

/// Every backend built into the library, in build order (the generated backend_list.cpp).
const std::vector<BackendEntry>& backend_entries();

}  // namespace lightsolver::detail
