#pragma once
// Photon emission: which luminaire a photon leaves and, through that luminaire's type row
// (luminaire_types.cpp), where it starts and where it goes. Every photon carries the same
// power, so directions are drawn exactly from each intensity profile.
#include "model/prepared_scene.hpp"
#include "lightsolver/rng.hpp"

namespace lightsolver::detail {

// Picks one of the group's luminaires with probability proportional to its flux (one draw,
// whatever the group's size, so a group's stream does not depend on how many it holds).
std::size_t pick_luminaire(const PreparedGroup& g, PathRng& rng);

inline EmittedRay emit(const PreparedLuminaire& l, PathRng& rng) { return l.emit(l, rng); }

}  // namespace lightsolver::detail
