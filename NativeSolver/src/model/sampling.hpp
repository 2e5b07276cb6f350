#pragma once
// Small geometric and sampling helpers used on every photon bounce: the formulas are
// Shaders/shared/sampling.h, the text the Vulkan shaders include too (docs/solver.md, "Physics
// written once"); this header gives them their C++ names in lightsolver::detail.
#include <glm/vec3.hpp>

#include "lightsolver/rng.hpp"
#include "shared/sampling.h"

namespace lightsolver::detail {

using glm::vec3;

// Moves a surface point off its surface along n by a few float ULPs scaled to the coordinate's
// magnitude (Wächter & Binder, Ray Tracing Gems ch. 6).
using shared::offset_ray_origin;
// Orthonormal basis around a unit vector (Duff et al. 2017) and a local vector in it.
using shared::make_frame;
using shared::to_world;
// Cosine-weighted direction about n; uniform direction on the sphere.
using shared::sample_cosine;
using shared::sample_sphere;
// A point on a parallelogram; a direction on a cone about an axis.
using shared::cone_direction;
using shared::point_on_parallelogram;

using shared::reflect_dir;  // mirror direction about a normal

}  // namespace lightsolver::detail
