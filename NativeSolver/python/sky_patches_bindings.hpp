#pragma once
// lightsolver.sky_patches() and lightsolver.sky_vectors(): Reinhart sky patches and a year of
// sky vectors from a weather file (lightsolver/sky_patches.hpp) as numpy arrays
// (sky_patches_bindings.cpp).
#include <pybind11/pybind11.h>

/// Adds sky_patches() and sky_vectors() to the module.
void bind_sky_patches(pybind11::module_& m);
