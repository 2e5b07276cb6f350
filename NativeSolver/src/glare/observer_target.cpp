// An observer target's UGR from the traced background luminance (docs/glare.md, "UGR in a
// traced scene").
#include "glare/observer_target.hpp"

#include <glm/geometric.hpp>
#include <numbers>
#include <optional>
#include <string>

namespace lightsolver::detail {
namespace {

// One scene luminaire as a glare source, or why it is none.
struct Candidate {
  std::optional<GlareSource> source;
  std::string why_not;
};

Candidate glare_candidate(const Luminaire& l) {
  switch (l.type) {
    case Luminaire::Type::Area: {
      const glm::dvec3 n = glm::cross(l.edge1, l.edge2);
      return {lambertian_glare_source(l.name, l.corner + 0.5 * (l.edge1 + l.edge2), n,
                                      glm::length(n), l.flux_lm),
              {}};
    }
    case Luminaire::Type::Photometric: {
      if (!l.sampler || !(l.sampler->integrated_flux_lm() > 0.0)) return {{}, "emits nothing"};
      // Intensity as traced: the file's candela scaled to the emitted flux, at its tilt.
      const double scale = l.flux_lm / l.sampler->integrated_flux_lm() * photometric_tilt_factor(l);
      try {
        return {photometric_glare_source(l.name, l.photometry, l.sampler, l.position,
                                         glm::normalize(l.aim), photometric_c0(l), scale),
                {}};
      } catch (const InputError&) {
        return {{}, "its file gives no luminous area (a point opening): no luminance to rate"};
      }
    }
    case Luminaire::Type::Point:
    case Luminaire::Type::Spot:
      return {{},
              "a point or spot luminaire has no luminous area (CIE 117 needs one; CIE 147's "
              "small-source rating is not implemented)"};
    case Luminaire::Type::Directional:
      break;
  }
  return {{}, "a directional beam (daylight) is not a luminaire in the field of view"};
}

std::optional<double> ugr_at(const GlareObserver& o, const std::vector<GlareSource>& sources,
                             double background_cd_m2) {
  if (!(background_cd_m2 > 0.0)) return std::nullopt;
  return compute_ugr(o, sources, background_cd_m2).ugr;
}

}  // namespace

ObserverGlare observer_glare(const Target& t, const std::vector<Luminaire>& luminaires,
                             const Estimate& indirect) {
  ObserverGlare g;
  const double inv_pi = 1.0 / std::numbers::pi;
  g.background_luminance_cd_m2 = indirect.mean * inv_pi;
  g.background_ci_low_cd_m2 = indirect.ci_low * inv_pi;
  g.background_ci_high_cd_m2 = indirect.ci_high * inv_pi;
  const GlareObserver o{t.position, t.view_direction, t.up};
  std::vector<GlareSource> sources;
  std::vector<std::string> excluded(luminaires.size());
  for (std::size_t i = 0; i < luminaires.size(); ++i) {
    Candidate c = glare_candidate(luminaires[i]);
    if (c.source) {
      sources.push_back(std::move(*c.source));
    } else {
      excluded[i] = std::move(c.why_not);
      g.warnings.push_back(t.name + ": luminaire \"" + luminaires[i].name +
                           "\" is not rated for glare: " + excluded[i]);
    }
  }
  // The geometry and luminance of each source do not depend on L_b: evaluate at 1 cd/m2 and
  // take the sum; the UGR values themselves come from compute_ugr at each L_b.
  const UgrResult unit = compute_ugr(o, sources, 1.0);
  std::size_t next = 0;
  for (std::size_t i = 0; i < luminaires.size(); ++i) {
    GlareContribution c;
    if (excluded[i].empty()) {
      c = unit.contributions[next++];
      if (c.counted) c.ugr_alone = ugr_at(o, {sources[next - 1]}, g.background_luminance_cd_m2);
    } else {
      c.name = luminaires[i].name;
      c.why_not = excluded[i];
    }
    g.contributions.push_back(std::move(c));
  }
  g.warnings.insert(g.warnings.end(), unit.warnings.begin(), unit.warnings.end());
  g.luminaire_sum = unit.sum;
  if (!(unit.sum > 0.0)) {
    g.warnings.push_back(t.name +
                         ": no luminaire counts toward UGR (none in the field of view "
                         "with a luminous area): no discomfort glare from luminaires");
    return g;
  }
  g.ugr = ugr_at(o, sources, g.background_luminance_cd_m2);
  g.ugr_ci_low = ugr_at(o, sources, g.background_ci_high_cd_m2);
  g.ugr_ci_high = ugr_at(o, sources, g.background_ci_low_cd_m2);
  if (!g.ugr) {
    g.warnings.push_back(t.name +
                         ": no reflected light reached the observer in this run "
                         "(L_b = 0): its UGR is unbounded; trace more photons");
  } else if (!g.ugr_ci_high) {
    g.warnings.push_back(t.name +
                         ": the background luminance's interval reaches 0, so the "
                         "UGR's interval has no upper end; trace more photons");
  }
  return g;
}

}  // namespace lightsolver::detail
