// Glazing on a daylight opening (docs/daylight.md, "Glazing"): the visible transmittance of
// single or double glazing at incidence cos_i, one text for the CPU (daylight/sky_glazing.hpp, in
// double: the sky's direction tables, its flux and the sun's) and the shaders (sky.glsl, in float:
// the acceptance test against those tables). Written in the subset of prelude.h.
//
// Model: a stack of 2·panes clear air/glass interfaces (n = 1.52, soda-lime float glass, the glass
// material's default) with incoherent inter-reflections between them, per polarisation
// T = (1 − R) / (1 + (N − 1) R) for N interfaces of Fresnel reflectance R (Stokes' pile of
// plates; N = 2 is scatter.h's thin_slab with no absorption, (1 − R)² / (1 − R²)), averaged over
// s and p (unpolarised daylight). The result is scaled so that normal incidence gives the
// glazing's τv: τ(θ) = τv · T(θ) / T(0). So absorption and coatings keep clear glass's angular
// shape (the longer path through tinted glass at oblique incidence is not modelled).
#ifndef LIGHTSOLVER_SHARED_GLAZING_H
#define LIGHTSOLVER_SHARED_GLAZING_H

#include "prelude.h"

#ifdef __cplusplus
namespace lightsolver::shared {
#define LS_GLAZING_TEMPLATE template <typename Real>
#else
#define LS_GLAZING_TEMPLATE
#define Real float
#endif

// Unpolarised transmittance of `interfaces` clear air/glass interfaces (n = 1.52) at incidence
// cos_i in [0, 1]; 1 for none. At grazing incidence R = 1 and the result is 0 (no 0/0: cos_t > 0).
LS_GLAZING_TEMPLATE
LS_FN Real glazing_clear_transmittance(Real cos_i, uint interfaces) {
  if (interfaces == 0u) return Real(1.0);
  const Real n = Real(1.52);
  const Real c = min(max(cos_i, Real(0.0)), Real(1.0));
  const Real cos_t = sqrt(Real(1.0) - (Real(1.0) - c * c) / (n * n));
  const Real s = (c - n * cos_t) / (c + n * cos_t);
  const Real p = (n * c - cos_t) / (n * c + cos_t);
  const Real rs = s * s, rp = p * p;
  const Real k = Real(interfaces) - Real(1.0);
  return Real(0.5) *
         ((Real(1.0) - rs) / (Real(1.0) + k * rs) + (Real(1.0) - rp) / (Real(1.0) + k * rp));
}

// τ(θ) = scale · T(θ), scale = τv / T(0) (the record carries the scale; panes 0: no glazing).
LS_GLAZING_TEMPLATE
LS_FN Real glazing_transmittance(Real cos_i, Real scale, uint panes) {
#ifdef __cplusplus
  return scale * glazing_clear_transmittance<Real>(cos_i, 2u * panes);
#else
  return scale * glazing_clear_transmittance(cos_i, 2u * panes);
#endif
}

#undef LS_GLAZING_TEMPLATE
#ifdef __cplusplus
}  // namespace lightsolver::shared
#else
#undef Real
#endif

#endif
