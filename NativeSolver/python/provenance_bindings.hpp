#pragma once
// lightsolver.verify_results(scene_path, results): whether results belong to a scene file, by
// their provenance (lightsolver/provenance.hpp; provenance_bindings.cpp).
#include <pybind11/pybind11.h>

/// Adds verify_results() to the module.
void bind_provenance(pybind11::module_& m);
