// An observer target's UGR from the traced background luminance (docs/glare.md, "UGR in a
// traced scene"): the one eye's terms, then its glare from them, as every eye of an observer
// grid (glare_terms.cpp).
#include "glare/observer_target.hpp"

#include "glare/glare_terms.hpp"

namespace lightsolver::detail {

ObserverGlare observer_glare(const Target& t, const std::vector<Luminaire>& luminaires,
                             const Estimate& indirect) {
  const GlareObserver eye{t.position, t.view_direction, t.up};
  return eye_glare(t.name, glare_terms(luminaires, {eye}), 0, indirect);
}

}  // namespace lightsolver::detail
