#pragma once
// NOAA's solar calculator equations (NOAA Global Monitoring Laboratory, "Solar Calculation
// Details", the spreadsheet NOAA_Solar_Calculations_day.xls), written here independently of the
// solver: Meeus' low-accuracy sun (Astronomical Algorithms ch. 25, stated accuracy 0.01°) and
// the equation of time (Meeus 28.3), geocentric, without refraction.

namespace lightsolver::test {

struct NoaaPosition {
  double elevation_deg;  ///< geometric, no refraction
  double azimuth_deg;    ///< from north, clockwise
};

/// `julian_day` is UT; latitude north positive, longitude east positive.
NoaaPosition noaa_position(double julian_day, double latitude_deg, double longitude_deg);

}  // namespace lightsolver::test
