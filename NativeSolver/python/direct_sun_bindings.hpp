#pragma once
// lightsolver.direct_sun(): direct sunlight at points for every hour of a year
// (lightsolver/direct_sun.hpp) with numpy arrays (direct_sun_bindings.cpp).
#include <pybind11/pybind11.h>

/// Adds direct_sun() to the module.
void bind_direct_sun(pybind11::module_& m);
