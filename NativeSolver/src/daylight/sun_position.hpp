#pragma once
// The sun's position: the pieces of sun_position.cpp that tests check alone. The public API is
// include/lightsolver/daylight.hpp.

namespace lightsolver::detail {

/// The "file" of the sun's InputErrors: they name a field of its inputs, not of a file.
inline constexpr const char* kSunInputs = "sun position";

/// SPA's atmospheric refraction (Reda & Andreas 2004, eq. 42; Bennett's formula scaled by
/// pressure and temperature), degrees to add to the geometric elevation. 0 below −0.8334°
/// (SPA's own cut: the sun's radius plus the refraction at the horizon, 0.5667°).
double spa_refraction_deg(double geometric_elevation_deg, double pressure_mbar,
                          double temperature_c);

/// Days of a month in the (proleptic) Gregorian calendar.
int days_in_month(int year, int month);

}  // namespace lightsolver::detail
