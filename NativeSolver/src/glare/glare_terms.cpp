// An eye's glare terms (geometry) and its UGR from them (statistics); docs/glare.md, "UGR in a
// traced scene" and "Rescaling an observer grid".
#include "glare/glare_terms.hpp"

#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <stdexcept>

#include "types/luminaire_types.hpp"

namespace lightsolver::detail {
namespace {

// The reasons compute_ugr gives, by status character.
constexpr std::pair<char, const char*> kReasons[] = {
    {'b', "behind the eye"},
    {'l', "below the line of sight (outside CIE 117's table)"},
    {'o', "outside the field or hidden by brow (CIE 117 Table 4.1)"},
    {'d', "dark or edge-on toward the eye"},
};

char status_of(const std::string& why_not) {
  const char c = geometric_status(why_not);
  if (c == 'x') {
    throw std::logic_error("compute_ugr gave a reason without a status character: " + why_not);
  }
  return c;
}

// One scene luminaire as a glare source, or why it is none.
struct Candidate {
  std::optional<GlareSource> source;
  std::string why_not;
};

// The luminaire's row says what it is as a source (luminaire_types.cpp); rated here.
Candidate glare_candidate(const Luminaire& l) {
  const GlareShape g = luminaire_type(l.type).glare(l);
  switch (g.kind) {
    case GlareShape::Kind::LambertianArea:
      return {lambertian_glare_source(l.name, g.centre, g.normal, g.area_m2, g.flux_lm), {}};
    case GlareShape::Kind::PhotometricBody:
      try {
        return {photometric_glare_source(l.name, l.photometry, l.sampler, g.centre, g.aim, g.c0,
                                         g.candela_scale),
                {}};
      } catch (const InputError&) {
        return {{}, "its file gives no luminous area (a point opening): no luminance to rate"};
      }
    case GlareShape::Kind::None:
      break;
  }
  return {{}, g.why_not};
}

}  // namespace

std::optional<double> ugr_for(double sum, double lb) {
  if (!(lb > 0.0) || !(sum > 0.0)) return std::nullopt;
  const double k = 0.25 / lb;
  return 8.0 * std::log10(k * sum);
}

char geometric_status(const std::string& why_not) {
  for (const auto& [c, reason] : kReasons) {
    if (why_not == reason) return c;
  }
  return 'x';
}

std::string why_not_counted(const GlareTerms& terms, char s, std::size_t luminaire) {
  if (s == 'x') return terms.not_rated.at(luminaire);
  for (const auto& [c, reason] : kReasons) {
    if (c == s) return reason;
  }
  return "";
}

GlareTerms glare_terms(const std::vector<Luminaire>& luminaires,
                       const std::vector<GlareObserver>& eyes) {
  GlareTerms out;
  std::vector<GlareSource> sources;
  std::vector<std::size_t> of;  // each source's luminaire
  for (std::size_t i = 0; i < luminaires.size(); ++i) {
    Candidate c = glare_candidate(luminaires[i]);
    out.luminaires.push_back(luminaires[i].name);
    out.not_rated.push_back(std::move(c.why_not));
    if (c.source) {
      sources.push_back(std::move(*c.source));
      of.push_back(i);
    }
  }
  // The geometry and luminance of each source do not depend on L_b: rated at 1 cd/m2.
  for (const GlareObserver& eye : eyes) {
    std::string status(luminaires.size(), 'x');
    std::vector<double> terms;
    const UgrResult unit = compute_ugr(eye, sources, 1.0);
    for (std::size_t s = 0; s < sources.size(); ++s) {
      const GlareContribution& c = unit.contributions[s];
      status[of[s]] = c.counted ? 'c' : status_of(c.why_not);
      if (c.counted)
        terms.insert(terms.end(), {c.luminance_cd_m2, c.solid_angle_sr, c.position_index});
    }
    out.status.push_back(std::move(status));
    out.terms.push_back(std::move(terms));
  }
  return out;
}

GlareTerms dimmed(GlareTerms terms, const std::vector<double>& factor) {
  for (std::size_t k = 0; k < terms.status.size(); ++k) {
    std::vector<double> kept;
    std::size_t next = 0;
    for (std::size_t i = 0; i < terms.luminaires.size(); ++i) {
      if (terms.status[k][i] != 'c') continue;
      const double* t = &terms.terms[k][3 * next++];
      const double luminance = t[0] * factor[i];
      if (!(luminance > 0.0)) {
        terms.status[k][i] = 'd';
        continue;
      }
      kept.insert(kept.end(), {luminance, t[1], t[2]});
    }
    terms.terms[k] = std::move(kept);
  }
  return terms;
}

ObserverGlare eye_glare(const std::string& name, const GlareTerms& terms, std::size_t k,
                        const Estimate& indirect) {
  ObserverGlare g;
  const double inv_pi = 1.0 / std::numbers::pi;
  g.background_luminance_cd_m2 = indirect.mean * inv_pi;
  g.background_ci_low_cd_m2 = indirect.ci_low * inv_pi;
  g.background_ci_high_cd_m2 = indirect.ci_high * inv_pi;
  const double lb = g.background_luminance_cd_m2;
  const std::string& status = terms.status.at(k);
  const std::vector<double>& t = terms.terms.at(k);
  Warnings ranges;  // after the luminaires not rated, as compute_ugr's come after them
  std::size_t next = 0;
  // Summed in scene order, as compute_ugr sums: the same bits.
  for (std::size_t i = 0; i < terms.luminaires.size(); ++i) {
    GlareContribution c;
    c.name = terms.luminaires[i];
    if (status[i] == 'c') {
      c.counted = true;
      c.luminance_cd_m2 = t.at(next);
      c.solid_angle_sr = t.at(next + 1);
      c.position_index = t.at(next + 2);
      next += 3;
      c.term = c.luminance_cd_m2 * c.luminance_cd_m2 * c.solid_angle_sr /
               (c.position_index * c.position_index);
      c.ugr_alone = ugr_for(c.term, lb);
      g.luminaire_sum += c.term;
      if (auto w = solid_angle_warning(c.name, c.solid_angle_sr)) ranges.push_back(std::move(*w));
    } else {
      c.why_not = why_not_counted(terms, status[i], i);
      if (status[i] == 'x') {
        g.warnings.push_back(name + ": luminaire \"" + c.name +
                             "\" is not rated for glare: " + c.why_not);
      }
    }
    g.contributions.push_back(std::move(c));
  }
  g.warnings.insert(g.warnings.end(), ranges.begin(), ranges.end());
  if (!(g.luminaire_sum > 0.0)) {
    g.warnings.push_back(name +
                         ": no luminaire counts toward UGR (none in the field of view "
                         "with a luminous area): no discomfort glare from luminaires");
    return g;
  }
  g.ugr = ugr_for(g.luminaire_sum, lb);
  g.ugr_ci_low = ugr_for(g.luminaire_sum, g.background_ci_high_cd_m2);
  g.ugr_ci_high = ugr_for(g.luminaire_sum, g.background_ci_low_cd_m2);
  if (!g.ugr) {
    g.warnings.push_back(name +
                         ": no reflected light reached the observer in this run "
                         "(L_b = 0): its UGR is unbounded; trace more photons");
  } else if (!g.ugr_ci_high) {
    g.warnings.push_back(name +
                         ": the background luminance's interval reaches 0, so the "
                         "UGR's interval has no upper end; trace more photons");
  }
  return g;
}

}  // namespace lightsolver::detail
