#include "model/emitters.hpp"

#include <algorithm>

namespace lightsolver::detail {

std::size_t pick_luminaire(const PreparedGroup& g, PathRng& rng) {
  const double u = rng.uniform_double();
  const auto it = std::upper_bound(g.cdf.begin(), g.cdf.end(), u);
  return g.luminaires[std::min<std::size_t>(it - g.cdf.begin(), g.cdf.size() - 1)];
}

}  // namespace lightsolver::detail
