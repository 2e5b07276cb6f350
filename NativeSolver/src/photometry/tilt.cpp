// TILT tables: lamp output against luminaire tilt.
#include <algorithm>
#include <iterator>

#include "lightsolver/photometry.hpp"

namespace lightsolver {

double TiltData::factor_at(double tilt_deg) const {
  if (factors.empty()) return 1.0;
  if (tilt_deg <= angles_deg.front()) return factors.front();
  if (tilt_deg >= angles_deg.back()) return factors.back();
  // Angles strictly increase (checked by the parser): the bracket is unique.
  const auto hi = std::upper_bound(angles_deg.begin(), angles_deg.end(), tilt_deg);
  const auto i = static_cast<std::size_t>(std::distance(angles_deg.begin(), hi));
  const double t = (tilt_deg - angles_deg[i - 1]) / (angles_deg[i] - angles_deg[i - 1]);
  return factors[i - 1] + t * (factors[i] - factors[i - 1]);
}

}  // namespace lightsolver
