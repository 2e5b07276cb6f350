#include "results/observer_grid_io.hpp"

#include <algorithm>
#include <cstring>
#include <string>

namespace lightsolver::detail {
namespace {

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

}  // namespace

nlohmann::json glare_terms_json(const GlareTerms& terms) {
  nlohmann::json not_rated = nlohmann::json::object();
  for (std::size_t i = 0; i < terms.luminaires.size(); ++i) {
    if (!terms.not_rated[i].empty()) not_rated[terms.luminaires[i]] = terms.not_rated[i];
  }
  return {{"luminaires", terms.luminaires},
          {"not_rated", std::move(not_rated)},
          {"status", terms.status},
          {"terms", terms.terms}};
}

GlareTerms read_glare_terms(const JsonNode& n, std::size_t points) {
  GlareTerms t;
  const JsonNode names = n.at("luminaires"), not_rated = n.at("not_rated");
  not_rated.object();
  for (std::size_t i = 0; i < names.array_size(); ++i) {
    t.luminaires.push_back(names[i].string());
    const char* name = t.luminaires.back().c_str();
    t.not_rated.push_back(not_rated.has(name) ? not_rated.at(name).string() : "");
  }
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
  return t;
}

}  // namespace lightsolver::detail
