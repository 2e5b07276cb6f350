#pragma once
// lightsolver.optimize(): the inverse-lighting search (optimize_bindings.cpp).
#include <pybind11/pybind11.h>

/// Adds `optimize` to the module.
void bind_optimizer(pybind11::module_& m);
