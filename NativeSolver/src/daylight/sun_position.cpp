// The sun's topocentric position with libnova (docs/daylight.md, "Sun").
//
// libnova gives the pieces: VSOP87 (ln_get_solar_geom_coords), IAU 1980 nutation, precession
// (ln_get_equ_prec2), apparent sidereal time and the topocentric parallax. Two of its shortcuts
// are not used because each costs more than SPA's 0.0003°, measured on SPA's worked example:
// - ln_get_solar_equ_coords keeps VSOP87's J2000 ecliptic (no precession to the date), 0.05° in
//   2003 and 0.014° more per year; ln_get_ecl_prec, which would fix that, returns zeros in
//   libnova 0.16. We rotate to the J2000 equator, precess, and rotate to the ecliptic of date.
// - ln_get_hrz_from_equ uses the mean sidereal time (0.004° of azimuth), and libnova 0.16's
//   apparent sidereal time adds Δψ where Meeus (ch. 12) and SPA add Δψ·cos ε (0.0003°).
//   We add the equation of the equinoxes to ln_get_mean_sidereal_time ourselves and pass that
//   to ln_get_hrz_from_equ_sidereal_time.
#include "daylight/sun_position.hpp"

#include <libnova/dynamical_time.h>
#include <libnova/earth.h>
#include <libnova/julian_day.h>
#include <libnova/nutation.h>
#include <libnova/parallax.h>
#include <libnova/precession.h>
#include <libnova/sidereal_time.h>
#include <libnova/solar.h>
#include <libnova/transform.h>

#include <cmath>
#include <mutex>
#include <sstream>

#include "lightsolver/angles.hpp"
#include "lightsolver/daylight.hpp"
#include "lightsolver/error.hpp"

namespace lightsolver {
namespace {

constexpr double kJ2000 = 2451545.0;
constexpr double kObliquityJ2000Deg = 23.4392911;  // IAU 1980, 23°26'21.448"
constexpr double kAberrationArcsec = 20.4898;      // Meeus ch. 25, divided by R in AU

void require(bool ok, const std::string& field, const std::string& what) {
  if (!ok) throw InputError(detail::kSunInputs, field, what);
}

void require_range(double v, double lo, double hi, const std::string& field,
                   const std::string& unit) {
  std::ostringstream s;
  s << "must be a number from " << lo << " to " << hi << unit;
  if (std::isfinite(v)) s << ", got " << v;
  require(std::isfinite(v) && v >= lo && v <= hi, field, s.str());
}

void check_inputs(const Site& site, const CivilTime& t, const SunOptions& o) {
  require_range(site.latitude_deg, -90, 90, "latitude_deg", "°");
  require_range(site.longitude_deg, -180, 180, "longitude_deg", "°");
  require_range(site.elevation_m, -500, 9000, "elevation_m", " m");
  require_range(t.year, -2000, 6000, "time.year", "");
  require_range(t.month, 1, 12, "time.month", "");
  require_range(t.day, 1, detail::days_in_month(t.year, t.month), "time.day", "");
  require_range(t.hour, 0, 23, "time.hour", "");
  require_range(t.minute, 0, 59, "time.minute", "");
  require(std::isfinite(t.second) && t.second >= 0 && t.second < 61, "time.second",
          "must be a number from 0 to below 61");
  require_range(t.utc_offset_h, -14, 14, "time.utc_offset_h", " h");
  if (o.refraction) {
    require_range(o.pressure_mbar, 500, 1100, "pressure_mbar", " mbar");
    require_range(o.temperature_c, -90, 60, "temperature_c", " °C");
  }
  if (o.delta_t_s) require_range(*o.delta_t_s, -1e5, 1e5, "delta_t_s", " s");
}

void ecliptic_to_equatorial(double lambda, double beta, double eps, ln_equ_posn& out) {
  const double l = lambda * kDeg, b = beta * kDeg, e = eps * kDeg;
  double ra = std::atan2(std::sin(l) * std::cos(e) - std::tan(b) * std::sin(e), std::cos(l));
  out.ra = std::fmod(ra / kDeg + 360.0, 360.0);
  out.dec = std::asin(std::sin(b) * std::cos(e) + std::cos(b) * std::sin(e) * std::sin(l)) / kDeg;
}

void equatorial_to_ecliptic(const ln_equ_posn& in, double eps, double& lambda, double& beta) {
  const double a = in.ra * kDeg, d = in.dec * kDeg, e = eps * kDeg;
  lambda = std::atan2(std::sin(a) * std::cos(e) + std::tan(d) * std::sin(e), std::cos(a)) / kDeg;
  beta = std::asin(std::sin(d) * std::cos(e) - std::cos(d) * std::sin(e) * std::sin(a)) / kDeg;
}

// ΔT = TT − UT1 when none is given: Espenak & Meeus' polynomials (NASA, "Polynomial expressions
// for Delta T", 2006) from 1986 to 2050, within a few seconds of the observed values (69.2 s in
// 2026: they give 75 s); libnova's estimate elsewhere (it gives 137 s for 2026: 0.001° of
// azimuth). `year` is decimal, at the middle of the month.
double default_delta_t_s(const CivilTime& t, double julian_day) {
  const double y = t.year + (t.month - 0.5) / 12.0, u = y - 2000.0;
  if (y >= 2005.0 && y < 2050.0) return 62.92 + 0.32217 * u + 0.005589 * u * u;
  if (y >= 1986.0 && y < 2005.0)
    return 63.86 +
           u * (0.3345 + u * (-0.060374 + u * (0.0017275 + u * (0.000651814 + u * 0.00002373599))));
  return ln_get_dynamical_time_diff(julian_day);
}

// Julian day (UT) of a civil time: the local calendar fields, then the offset.
double julian_day_ut(const CivilTime& t) {
  ln_date d{t.year, t.month, t.day, t.hour, t.minute, t.second};
  return ln_get_julian_day(&d) - t.utc_offset_h / 24.0;
}

}  // namespace

namespace detail {

double spa_refraction_deg(double e0, double pressure_mbar, double temperature_c) {
  constexpr double kSunRadiusDeg = 0.26667, kHorizonRefractionDeg = 0.5667;
  if (e0 < -(kSunRadiusDeg + kHorizonRefractionDeg)) return 0.0;
  return (pressure_mbar / 1010.0) * (283.0 / (273.0 + temperature_c)) * 1.02 /
         (60.0 * std::tan((e0 + 10.3 / (e0 + 5.11)) * kDeg));
}

int days_in_month(int year, int month) {
  static constexpr int kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (month < 1 || month > 12) return 31;
  const bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
  return kDays[month - 1] + (month == 2 && leap ? 1 : 0);
}

}  // namespace detail

SunPosition sun_position(const Site& site, const CivilTime& time, const SunOptions& options) {
  check_inputs(site, time, options);
  SunPosition p;
  p.julian_day = julian_day_ut(time);
  p.delta_t_s = options.delta_t_s.value_or(default_delta_t_s(time, p.julian_day));
  const double jde = p.julian_day + p.delta_t_s / 86400.0;

  // libnova keeps its last nutation in static variables (read again by ln_get_parallax): one
  // caller at a time, so that positions may be asked for from any thread.
  static std::mutex libnova;
  const std::lock_guard<std::mutex> one_at_a_time(libnova);
  // Geometric sun in VSOP87's J2000 ecliptic, precessed to the mean equinox of date.
  ln_helio_posn sun;
  ln_get_solar_geom_coords(jde, &sun);
  ln_equ_posn j2000, of_date;
  ecliptic_to_equatorial(sun.L, sun.B, kObliquityJ2000Deg, j2000);
  ln_get_equ_prec2(&j2000, kJ2000, jde, &of_date);
  ln_nutation nut;
  // libnova caches the last nutation and returns it for any date within 0.1 day of it: a call
  // one day away first makes it compute this date's, so a position depends on its inputs alone,
  // not on the calls before it (ln_get_parallax's sidereal time then reads this one).
  ln_get_nutation(jde + 1.0, &nut);
  ln_get_nutation(jde, &nut);  // longitude = Δψ, obliquity = Δε, ecliptic = mean ε
  double lambda = 0, beta = 0;
  equatorial_to_ecliptic(of_date, nut.ecliptic, lambda, beta);
  // Apparent: nutation in longitude and aberration, then the true obliquity.
  lambda += nut.longitude - kAberrationArcsec / 3600.0 / sun.R;
  ln_equ_posn apparent;
  ecliptic_to_equatorial(lambda, beta, nut.ecliptic + nut.obliquity, apparent);
  p.right_ascension_deg = apparent.ra;
  p.declination_deg = apparent.dec;
  p.distance_au = sun.R;

  // Topocentric: parallax at the site's height, then the horizon by the apparent sidereal time.
  ln_lnlat_posn observer{site.longitude_deg, site.latitude_deg};
  ln_equ_posn shift;
  ln_get_parallax(&apparent, sun.R, &observer, site.elevation_m, p.julian_day, &shift);
  ln_equ_posn topo{apparent.ra + shift.ra, apparent.dec + shift.dec};
  ln_hrz_posn hrz;
  const double true_obliquity = nut.ecliptic + nut.obliquity;
  const double sidereal_h = ln_get_mean_sidereal_time(p.julian_day) +
                            nut.longitude * std::cos(true_obliquity * kDeg) / 15.0;
  ln_get_hrz_from_equ_sidereal_time(&topo, &observer, sidereal_h, &hrz);
  p.geometric_elevation_deg = hrz.alt;
  const double refraction =
      options.refraction
          ? detail::spa_refraction_deg(hrz.alt, options.pressure_mbar, options.temperature_c)
          : 0.0;
  p.elevation_deg = hrz.alt + refraction;
  p.zenith_deg = 90.0 - p.elevation_deg;
  // libnova's azimuth is from south, westward; ours from north, clockwise (eastward).
  p.azimuth_deg = std::fmod(hrz.az + 180.0, 360.0);
  if (p.azimuth_deg < 0) p.azimuth_deg += 360.0;
  return p;
}

glm::dvec3 sun_direction(const SunPosition& position, double north_deg) {
  require_range(north_deg, -360, 360, "north_deg", "°");
  const double n = north_deg * kDeg, az = position.azimuth_deg * kDeg;
  const double el = position.elevation_deg * kDeg;
  const glm::dvec3 north{-std::sin(n), std::cos(n), 0.0}, east{std::cos(n), std::sin(n), 0.0};
  return std::cos(el) * (std::sin(az) * east + std::cos(az) * north) +
         glm::dvec3{0.0, 0.0, std::sin(el)};
}

}  // namespace lightsolver
