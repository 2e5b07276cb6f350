/// @file
/// π and the degree, defined once for every source file: the unity build (CMAKE_UNITY_BUILD,
/// docs/testing.md "CI time") compiles several files as one translation unit, where each
/// file's own copy of these constants would be defined twice.
#pragma once

#include <numbers>

namespace lightsolver {

/// π.
inline constexpr double kPi = std::numbers::pi;
/// Radians per degree.
inline constexpr double kDeg = std::numbers::pi / 180.0;

}  // namespace lightsolver
