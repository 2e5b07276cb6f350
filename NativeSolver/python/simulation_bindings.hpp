#pragma once
// lightsolver.Simulation: the incremental solver (simulation_bindings.cpp), and the two helpers
// of module.cpp it shares (one results layout, one Python-to-JSON reading).
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>
#include <string>

#include "lightsolver/solver.hpp"

/// A Python value as scene JSON (module.cpp); `where` names it in errors.
nlohmann::json to_json(const pybind11::handle& o, const std::string& where);

/// The results dict of solve(): results_to_json's layout plus numpy cell arrays (module.cpp).
pybind11::dict results_dict(const lightsolver::Results& r);

/// Adds the `Simulation` class to the module.
void bind_simulation(pybind11::module_& m);
