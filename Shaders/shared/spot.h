// The spot luminaire's relative intensity, one text for the CPU (types/luminaire_types.cpp, in
// double) and the shaders (emit.glsl, in float): piecewise linear in the angle theta from the
// axis through (0, 1), (half beam, 0.5), (half field, 0.1), and 0 beyond half the field angle
// (the CIE definitions of beam and field angle). Written in the subset of prelude.h.
#ifndef LIGHTSOLVER_SHARED_SPOT_H
#define LIGHTSOLVER_SHARED_SPOT_H

#include "prelude.h"

#ifdef __cplusplus
namespace lightsolver::shared {
template <typename Real>
#else
#define Real float
#endif

LS_FN Real spot_profile(Real theta, Real half_beam, Real half_field) {
  if (theta <= half_beam) return Real(1.0) - Real(0.5) * theta / half_beam;
  if (theta <= half_field) {
    return Real(0.5) - Real(0.4) * (theta - half_beam) / (half_field - half_beam);
  }
  return Real(0.0);
}

#ifdef __cplusplus
}  // namespace lightsolver::shared
#else
#undef Real
#endif

#endif
