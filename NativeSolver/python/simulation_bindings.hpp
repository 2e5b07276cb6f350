#pragma once
// lightsolver.Simulation: the incremental solver (simulation_bindings.cpp), and the two helpers
// of module.cpp it shares (one results layout, one Python-to-JSON reading).
#include <pybind11/pybind11.h>

#include <exception>
#include <nlohmann/json.hpp>
#include <string>

#include "lightsolver/solver.hpp"

/// A Python value as scene JSON (module.cpp); `where` names it in errors.
nlohmann::json to_json(const pybind11::handle& o, const std::string& where);

/// The results dict of solve(): results_to_json's layout plus numpy cell arrays (module.cpp).
pybind11::dict results_dict(const lightsolver::Results& r);

/// A ProgressFn that calls the Python callable `progress` (None: no callback) with the GIL
/// held; returning False stops the run. An exception it raises stops the run too and is kept
/// in `error`, for the caller to re-raise once tracing has stopped (module.cpp). `progress`
/// and `error` are referenced, not copied: both must outlive the run.
lightsolver::ProgressFn python_progress(const pybind11::object& progress,
                                        std::exception_ptr& error);

/// Adds the `Simulation` class to the module.
void bind_simulation(pybind11::module_& m);
