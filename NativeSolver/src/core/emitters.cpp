#include "core/emitters.hpp"

#include <algorithm>

namespace lightsolver::detail {

std::size_t pick_luminaire(const PreparedScene& s, PathRng& rng) {
  const double u = rng.uniform_double();
  const auto it = std::upper_bound(s.luminaire_cdf.begin(), s.luminaire_cdf.end(), u);
  return std::min<std::size_t>(it - s.luminaire_cdf.begin(), s.luminaire_cdf.size() - 1);
}

}  // namespace lightsolver::detail
