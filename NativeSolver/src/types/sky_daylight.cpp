// The scene's sky as a daylight-factor grid reads it (sky_daylight.hpp).
#include "types/sky_daylight.hpp"

#include "daylight/sky_sampler.hpp"

namespace lightsolver::detail {

std::optional<std::size_t> daylight_factor_sky(const Scene& s) {
  std::optional<std::size_t> found;
  for (std::size_t j = 0; j < s.luminaires.size(); ++j) {
    if (s.luminaires[j].type != Luminaire::Type::Sky) continue;
    if (found) return std::nullopt;  // two skies: no single sky to take a ratio to
    found = j;
  }
  return found;
}

double sky_outside_illuminance_lx(const Luminaire& l) {
  return l.sky_emitter ? l.sky_emitter->sky().diffuse_horizontal_lx() : 0.0;
}

}  // namespace lightsolver::detail
