#pragma once
// lightsolver.Scene: a scene built in memory, entry by entry, read by the scene file's own
// readers (scene_bindings.cpp).
#include <pybind11/pybind11.h>

/// Adds the Scene class (add_material, add_mesh, add_light, add_target, validate, the run
/// settings) to the module.
void bind_scene(pybind11::module_& m);
