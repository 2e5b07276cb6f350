#include "core/observer_grid_io.hpp"

namespace lightsolver::detail {

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

}  // namespace lightsolver::detail
