#pragma once
// Photon emission: where a photon starts and where it goes, for each luminaire type. Every
// photon carries the same power, so directions are drawn exactly from each intensity profile.
#include "core/prepared_scene.hpp"
#include "lightsolver/rng.hpp"

namespace lightsolver::detail {

struct EmittedRay {
  vec3 origin, direction;
};

// Picks a luminaire with probability proportional to its flux.
std::size_t pick_luminaire(const PreparedScene& s, PathRng& rng);

EmittedRay emit(const PreparedLuminaire& l, PathRng& rng);

}  // namespace lightsolver::detail
