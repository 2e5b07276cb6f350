#pragma once
// validate() for a scene validated before whose meshes have not changed since (a Simulation
// built from load_scene()'s scene: Simulation::Options::scene_validated). The meshes' vertices
// and triangles, most of the work on a large scene, are not checked again; everything else
// is, as validate() does: its normalisations then give the same values, to the bit, as
// validating twice always did.
#include "lightsolver/scene.hpp"

namespace lightsolver::detail {

void validate_again(Scene& scene);

}  // namespace lightsolver::detail
