#include "noaa_reference.hpp"

#include <cmath>

#include "lightsolver/angles.hpp"

namespace lightsolver::test {
namespace {
double sin_d(double a) { return std::sin(a * kDeg); }
double cos_d(double a) { return std::cos(a * kDeg); }
}  // namespace

NoaaPosition noaa_position(double jd, double lat, double lon) {
  const double t = (jd - 2451545.0) / 36525.0;  // Julian century
  const double l0 = std::fmod(280.46646 + t * (36000.76983 + t * 0.0003032), 360.0);
  const double m = 357.52911 + t * (35999.05029 - 0.0001537 * t);
  const double e = 0.016708634 - t * (0.000042037 + 0.0000001267 * t);
  const double c = sin_d(m) * (1.914602 - t * (0.004817 + 0.000014 * t)) +
                   sin_d(2 * m) * (0.019993 - 0.000101 * t) + sin_d(3 * m) * 0.000289;
  const double omega = 125.04 - 1934.136 * t;
  const double apparent_long = l0 + c - 0.00569 - 0.00478 * sin_d(omega);
  const double mean_obliquity =
      23.0 + (26.0 + (21.448 - t * (46.815 + t * (0.00059 - t * 0.001813))) / 60.0) / 60.0;
  const double obliquity = mean_obliquity + 0.00256 * cos_d(omega);
  const double decl = std::asin(sin_d(obliquity) * sin_d(apparent_long)) / kDeg;
  const double y = std::pow(std::tan(obliquity / 2 * kDeg), 2);
  const double eot_min =
      4.0 / kDeg *
      (y * sin_d(2 * l0) - 2 * e * sin_d(m) + 4 * e * y * sin_d(m) * cos_d(2 * l0) -
       0.5 * y * y * sin_d(4 * l0) - 1.25 * e * e * sin_d(2 * m));
  const double ut_min = std::fmod(jd + 0.5, 1.0) * 1440.0;
  const double true_solar_min = std::fmod(ut_min + eot_min + 4 * lon + 1440.0 * 2, 1440.0);
  const double hour_angle = true_solar_min / 4.0 - 180.0;
  const double cos_zenith = sin_d(lat) * sin_d(decl) + cos_d(lat) * cos_d(decl) * cos_d(hour_angle);
  const double zenith = std::acos(std::fmax(-1.0, std::fmin(1.0, cos_zenith))) / kDeg;
  // Azimuth from north, clockwise: atan2 of the east and north components.
  const double east = -cos_d(decl) * sin_d(hour_angle);
  const double north = sin_d(decl) * cos_d(lat) - cos_d(decl) * sin_d(lat) * cos_d(hour_angle);
  double az = std::atan2(east, north) / kDeg;
  if (az < 0) az += 360.0;
  return {90.0 - zenith, az};
}

}  // namespace lightsolver::test
