#pragma once
// lightsolver.luminaire_types() and lightsolver.target_types(): the solver's type tables
// (lightsolver/type_tables.hpp) as lists of dicts (types_bindings.cpp).
#include <pybind11/pybind11.h>

/// Adds luminaire_types() and target_types() to the module.
void bind_types(pybind11::module_& m);
