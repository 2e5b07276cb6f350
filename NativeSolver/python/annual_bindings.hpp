#pragma once
// lightsolver.annual (docs/daylight.md, "Daylight coefficients: a year in one trace").
#include <pybind11/pybind11.h>

/// Adds lightsolver.annual.
void bind_annual(pybind11::module_& m);
