#pragma once
// lightsolver.sun_position() and lightsolver.read_weather(): the sun's position
// (lightsolver/daylight.hpp) and EPW weather files (lightsolver/weather.hpp) as dicts
// (daylight_bindings.cpp).
#include <pybind11/pybind11.h>

/// Adds sun_position() and read_weather() to the module.
void bind_daylight(pybind11::module_& m);
