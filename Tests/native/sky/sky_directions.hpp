#pragma once
// Shared by the sky tests: a direction toward the sky from an altitude and an azimuth.
#include <cmath>

#include "daylight/sky_models.hpp"
#include "lightsolver/angles.hpp"

namespace lightsolver::daylight::test {

/// The direction at `altitude_deg` above the horizon and `azimuth_deg` clockwise from north
/// (+y), east +x, up +z: the scene's convention for the sun.
inline Direction sun_at(double altitude_deg, double azimuth_deg) {
  const double a = altitude_deg * kPi / 180.0, z = azimuth_deg * kPi / 180.0;
  return {std::cos(a) * std::sin(z), std::cos(a) * std::cos(z), std::sin(a)};
}

}  // namespace lightsolver::daylight::test
