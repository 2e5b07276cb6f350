#pragma once
// lightsolver.annual (docs/daylight.md, "A year of daylight").
#include <pybind11/pybind11.h>

/// Adds lightsolver.annual.
void bind_annual(pybind11::module_& m);
