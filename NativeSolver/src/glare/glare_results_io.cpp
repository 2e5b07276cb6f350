// Glare read back from results (glare_results_io.hpp). The observer's terms and the dimming
// factors came from rescale.cpp: moved up here so that core never includes glare.
#include "glare/glare_results_io.hpp"

#include <cmath>
#include <string>

#include "glare/glare_terms.hpp"
#include "lightsolver/error.hpp"

namespace lightsolver::detail {
namespace {

// A plain observer's luminaires in the results as the glare terms of one eye (status, and
// L, omega, p of the counted ones), for the statistics step traced runs use (eye_glare).
GlareTerms observer_terms(const ObserverGlare& glare, const std::string& source,
                          const std::string& field) {
  GlareTerms terms;
  std::string status;
  std::vector<double> values;
  for (std::size_t k = 0; k < glare.contributions.size(); ++k) {
    const GlareContribution& c = glare.contributions[k];
    terms.luminaires.push_back(c.name);
    terms.not_rated.emplace_back();
    if (c.counted) {
      status += 'c';
      const std::pair<const char*, double> parts[] = {{"luminance_cd_m2", c.luminance_cd_m2},
                                                      {"solid_angle_sr", c.solid_angle_sr},
                                                      {"position_index", c.position_index}};
      for (const auto& [key, x] : parts) {
        if (!(x > 0.0 && std::isfinite(x))) {
          throw InputError(source, field + ".luminaires[" + std::to_string(k) + "]." + key,
                           "must be > 0");
        }
        values.push_back(x);
      }
      continue;
    }
    // A geometric reason has its status character; any other says why it is never rated.
    const char ch = geometric_status(c.why_not);
    if (ch == 'x') terms.not_rated.back() = c.why_not;
    status += ch;
  }
  terms.status.push_back(std::move(status));
  terms.terms.push_back(std::move(values));
  return terms;
}

// Each luminaire's dimming factor (its group's; 1 for a name no group lists), in `terms` order.
std::vector<double> luminaire_factors(const GlareTerms& terms, const LuminaireFactors& factors) {
  std::vector<double> out;
  for (const std::string& name : terms.luminaires) {
    const auto f = factors.find(name);
    out.push_back(f == factors.end() ? 1.0 : f->second);
  }
  return out;
}

}  // namespace

std::shared_ptr<const ObserverGridGeometry> dimmed_observer_grid(const ObserverGridGlare& grid,
                                                                 const LuminaireFactors& factors) {
  ObserverGridGeometry g{grid.positions, grid.view_directions, grid.terms};
  g.terms = dimmed(std::move(g.terms), luminaire_factors(g.terms, factors));
  return std::make_shared<const ObserverGridGeometry>(std::move(g));
}

std::size_t observer_grid_points(const ObserverGridGeometry& geometry) {
  return geometry.terms.status.size();
}

ObserverGlare dimmed_observer_glare(const ObserverGlare& glare, const LuminaireFactors& factors,
                                    const std::string& name, const Estimate& indirect,
                                    const std::string& source, const std::string& field) {
  const GlareTerms terms = observer_terms(glare, source, field);
  const GlareTerms dimmed_terms = dimmed(terms, luminaire_factors(terms, factors));
  return eye_glare(name, dimmed_terms, 0, indirect);
}

}  // namespace lightsolver::detail
