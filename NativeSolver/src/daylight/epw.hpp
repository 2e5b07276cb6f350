#pragma once
// EPW reading's pieces (lightsolver/weather.hpp is the API): the field layout of an hourly row
// from the EnergyPlus "Auxiliary Programs" data dictionary, 0-based columns.

namespace lightsolver::detail::epw {

inline constexpr int kFields = 35;  // a data row: date and time, flags, 29 values
inline constexpr int kMonth = 1, kDay = 2, kHour = 3;
inline constexpr int kDirectNormalIrradiance = 14, kDiffuseHorizontalIrradiance = 15;
inline constexpr int kGlobalHorizontalIlluminance = 16, kDirectNormalIlluminance = 17;
inline constexpr int kDiffuseHorizontalIlluminance = 18;
// The dictionary's "\missing": a value at or above these is missing.
inline constexpr double kMissingIrradiance = 9999.0;
inline constexpr double kMissingIlluminance = 999900.0;

}  // namespace lightsolver::detail::epw
