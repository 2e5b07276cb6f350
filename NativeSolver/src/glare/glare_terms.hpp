#pragma once
// An eye's glare in two steps (docs/glare.md, "Rescaling an observer grid"): (a) geometry, each
// scene luminaire's status and L, omega, p at the eye, which depend on the luminaires alone;
// (b) statistics, the eye's UGR and its interval from those terms and its traced L_b. A traced
// run and `rescale` (which dims each L by its group's factor) share (b), so a factor of 1
// rebuilds the traced numbers bit for bit.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "lightsolver/glare.hpp"
#include "lightsolver/scene.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver::detail {

/// (a) The terms of `luminaires` at every eye of `eyes`, in that order.
GlareTerms glare_terms(const std::vector<Luminaire>& luminaires,
                       const std::vector<GlareObserver>& eyes);

/// The terms with each luminaire's luminance times `factor[i]` (its group's dimming factor);
/// a luminaire dimmed to 0 is dark toward every eye ('d'), as it is when traced at 0 lm.
GlareTerms dimmed(GlareTerms terms, const std::vector<double>& factor);

/// (b) The glare of point `k` of `terms` (target `name`) from `indirect`, the traced indirect
/// illuminance at the eye (lux): L_b = E / pi, UGR at L_b and at its interval's ends.
ObserverGlare eye_glare(const std::string& name, const GlareTerms& terms, std::size_t k,
                        const Estimate& indirect);

/// UGR for luminaire sum `sum` at background luminance `lb` (absent unless both are > 0), as
/// compute_ugr evaluates it.
std::optional<double> ugr_for(double sum, double lb);

/// CIE 117's range warning for a source of `solid_angle_sr` (none inside 0.0003-0.1 sr).
std::optional<std::string> solid_angle_warning(const std::string& name, double solid_angle_sr);

/// The status character of a geometric reason not to count ('b', 'l', 'o', 'd'); 'x' for any
/// other reason (the luminaire is never rated).
char geometric_status(const std::string& why_not);
/// Why a luminaire of status `s` does not count ('x': not_rated; 'c': "").
std::string why_not_counted(const GlareTerms& terms, char s, std::size_t luminaire);

}  // namespace lightsolver::detail
