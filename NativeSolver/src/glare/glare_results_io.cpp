// Glare read back from a results document (glare_results_io.hpp). The geometry reader came from
// core's observer_grid_io.cpp, the observer's terms and the dimming factors from rescale.cpp:
// moved up here so that core never includes glare.
#include "glare/glare_results_io.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "glare/glare_terms.hpp"

namespace lightsolver::detail {
namespace {

std::vector<glm::dvec3> read_points(const JsonNode& list) {
  if (list.array_size() == 0) list.fail("must list at least one");
  std::vector<glm::dvec3> out;
  for (std::size_t i = 0; i < list.array_size(); ++i) out.push_back(list[i].vec3());
  return out;
}

// Point k's status: one known character per luminaire, 'x' exactly where not_rated says why.
void check_status(const JsonNode& n, const std::string& status, const GlareTerms& terms) {
  if (status.size() != terms.luminaires.size()) {
    n.fail("has " + std::to_string(status.size()) + " characters, expected one per luminaire (" +
           std::to_string(terms.luminaires.size()) + ")");
  }
  for (std::size_t i = 0; i < status.size(); ++i) {
    if (std::strchr(kGlareStatus, status[i]) == nullptr || status[i] == '\0') {
      n.fail(std::string("has '") + status[i] + "': expected one of \"" + kGlareStatus + "\"");
    }
    if ((status[i] == 'x') != !terms.not_rated[i].empty()) {
      n.fail("luminaire \"" + terms.luminaires[i] +
             "\" is 'x' (not rated) exactly when not_rated names it");
    }
  }
}

// Point k's terms: L > 0, omega > 0 and p >= 1 for each counted luminaire.
std::vector<double> read_terms(const JsonNode& n, std::size_t counted) {
  if (n.array_size() != 3 * counted) {
    n.fail("has " + std::to_string(n.array_size()) +
           " numbers, expected 3 per counted luminaire (" + std::to_string(3 * counted) + ")");
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < n.array_size(); ++i) {
    const double v = n[i].number();
    if (!(i % 3 == 2 ? v >= 1.0 : v > 0.0)) {
      n[i].fail(i % 3 == 2 ? "a position index must be >= 1" : "must be > 0");
    }
    out.push_back(v);
  }
  return out;
}

// A plain observer's luminaires in the results as the glare terms of one eye (status, and
// L, omega, p of the counted ones), for the statistics step traced runs use (eye_glare).
GlareTerms observer_terms(const JsonNode& n) {
  GlareTerms terms;
  std::string status;
  std::vector<double> values;
  const JsonNode parts = n.at("luminaires");
  for (std::size_t i = 0; i < parts.array_size(); ++i) {
    const JsonNode p = parts[i];
    terms.luminaires.push_back(p.at("name").string());
    terms.not_rated.emplace_back();
    if (p.at("counted").boolean()) {
      status += 'c';
      for (const char* key : {"luminance_cd_m2", "solid_angle_sr", "position_index"}) {
        const double x = p.at(key).number();
        if (!(x > 0.0 && std::isfinite(x))) p.at(key).fail("must be > 0");
        values.push_back(x);
      }
      continue;
    }
    // A geometric reason has its status character; any other says why it is never rated.
    const std::string why = p.at("why_not").string();
    const char c = geometric_status(why);
    if (c == 'x') terms.not_rated.back() = why;
    status += c;
  }
  terms.status.push_back(std::move(status));
  terms.terms.push_back(std::move(values));
  return terms;
}

// Each luminaire's dimming factor (its group's; 1 for a name no group lists), in `terms` order.
std::vector<double> luminaire_factors(const GlareTerms& terms,
                                      const LuminaireFactors& luminaire_factor) {
  std::vector<double> out;
  for (const std::string& name : terms.luminaires) {
    const auto f = luminaire_factor.find(name);
    out.push_back(f == luminaire_factor.end() ? 1.0 : f->second);
  }
  return out;
}

}  // namespace

ObserverGridGeometry read_observer_grid_geometry(const JsonNode& target) {
  const JsonNode grid = target.at("observer_grid");
  ObserverGridGeometry g;
  g.positions = read_points(grid.at("positions"));
  g.view_directions = read_points(grid.at("view_directions"));
  if (!grid.has("glare_terms")) {
    grid.fail("no glare_terms: trace with --contributions (scene: settings.contributions)");
  }
  const JsonNode n = grid.at("glare_terms");
  GlareTerms& t = g.terms;
  const JsonNode names = n.at("luminaires"), not_rated = n.at("not_rated");
  not_rated.object();
  for (std::size_t i = 0; i < names.array_size(); ++i) {
    t.luminaires.push_back(names[i].string());
    const char* name = t.luminaires.back().c_str();
    t.not_rated.push_back(not_rated.has(name) ? not_rated.at(name).string() : "");
  }
  const std::size_t points = g.positions.size() * g.view_directions.size();
  const JsonNode status = n.at("status"), terms = n.at("terms");
  for (const JsonNode& list : {status, terms}) {
    if (list.array_size() != points) {
      list.fail("has " + std::to_string(list.array_size()) + " entries, expected one per point (" +
                std::to_string(points) + ")");
    }
  }
  for (std::size_t k = 0; k < points; ++k) {
    t.status.push_back(status[k].string());
    check_status(status[k], t.status.back(), t);
    const auto counted =
        static_cast<std::size_t>(std::count(t.status.back().begin(), t.status.back().end(), 'c'));
    t.terms.push_back(read_terms(terms[k], counted));
  }
  return g;
}

std::shared_ptr<const ObserverGridGeometry> dimmed_observer_grid(const JsonNode& target,
                                                                 const LuminaireFactors& factors) {
  ObserverGridGeometry g = read_observer_grid_geometry(target);
  const std::vector<double> f = luminaire_factors(g.terms, factors);
  g.terms = dimmed(std::move(g.terms), f);
  return std::make_shared<const ObserverGridGeometry>(std::move(g));
}

std::size_t observer_grid_points(const ObserverGridGeometry& geometry) {
  return geometry.terms.status.size();
}

ObserverGlare dimmed_observer_glare(const JsonNode& target, const LuminaireFactors& factors,
                                    const std::string& name, const Estimate& indirect) {
  const GlareTerms terms = observer_terms(target);
  const GlareTerms dimmed_terms = dimmed(terms, luminaire_factors(terms, factors));
  return eye_glare(name, dimmed_terms, 0, indirect);
}

}  // namespace lightsolver::detail
