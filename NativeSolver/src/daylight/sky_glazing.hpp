#pragma once
// Glazing on a daylight opening (docs/daylight.md, "Glazing"): τv at normal incidence with the
// clear-glass angular shape of Shaders/shared/glazing.h (single or double thin panes), and the
// EN 17037 / DIALux frame factor (the opening's glazed fraction) and maintenance factor (dirt).
// Pure mathematics: the CPU's double evaluation of the one text both backends include.
#include "shared/glazing.h"

namespace lightsolver::daylight {

/// An opening's glazing. panes 0: an open hole (τ = 1 at every angle).
struct Glazing {
  double transmittance = 1.0;       ///< τv at normal incidence, (0, 1]
  unsigned panes = 0;               ///< 0 (none), 1 (single) or 2 (double glazing)
  double frame_factor = 1.0;        ///< the glazed fraction of the opening, (0, 1]
  double maintenance_factor = 1.0;  ///< dirt on the glass, (0, 1]

  /// τv / T(0): the factor on clear glass's transmittance (shared::glazing_transmittance).
  double scale() const {
    return panes == 0 ? 1.0
                      : transmittance / shared::glazing_clear_transmittance<double>(1.0, 2 * panes);
  }
  /// τ(θ) at cos θ = `cos_i` (θ from the opening's normal).
  double tau(double cos_i) const {
    return panes == 0 ? 1.0 : shared::glazing_transmittance<double>(cos_i, scale(), panes);
  }
  /// The constant factor on the opening's light: frame × maintenance (× τv for panes 0).
  double factor() const {
    return frame_factor * maintenance_factor * (panes == 0 ? transmittance : 1.0);
  }
};

}  // namespace lightsolver::daylight
