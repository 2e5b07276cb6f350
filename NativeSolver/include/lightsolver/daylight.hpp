#pragma once
/// \file daylight.hpp
/// The sun's position (docs/daylight.md, "Sun"): topocentric zenith, elevation and azimuth for a
/// site and a civil time, and the unit direction toward the sun in a scene's frame.
///
/// Angles are degrees. Azimuth is measured from true north, clockwise seen from above (east 90°,
/// south 180°, west 270°), in [0, 360). Longitude is positive east of Greenwich. The algorithm
/// is libnova's (VSOP87 sun, IAU 1980 nutation, Meeus' precession, apparent sidereal time) with
/// the topocentric parallax and NREL SPA's refraction formula; against SPA's own worked example
/// (Reda & Andreas 2004) it agrees within 0.0005° (docs/daylight.md, "Sun").

#include <glm/vec3.hpp>
#include <optional>
#include <string>
#include <string_view>

namespace lightsolver {

/// Where on Earth a scene stands.
struct Site {
  double latitude_deg = 0.0;   ///< −90 … 90, positive north
  double longitude_deg = 0.0;  ///< −180 … 180, positive east of Greenwich
  double elevation_m = 0.0;    ///< height above sea level, −500 … 9000 m
};

/// A civil date and time with its offset from UTC (hours, −14 … 14; 0 for UTC). UT1 is taken as
/// UTC (|UT1 − UTC| < 0.9 s: at most 0.004° of hour angle).
struct CivilTime {
  int year = 2000;            ///< −2000 … 6000 (SPA's range)
  int month = 1;              ///< 1 … 12
  int day = 1;                ///< 1 … days of the month
  int hour = 0;               ///< 0 … 23
  int minute = 0;             ///< 0 … 59
  double second = 0.0;        ///< 0 … < 61 (a leap second allowed)
  double utc_offset_h = 0.0;  ///< local time − UTC, hours (−7 for Denver in winter)
};

/// Optional inputs of the position.
struct SunOptions {
  /// Atmospheric refraction (SPA's formula, Reda & Andreas 2004 eq. 42) at this pressure and
  /// temperature; off: the geometric (airless) topocentric position.
  bool refraction = true;
  double pressure_mbar = 1010.0;  ///< annual mean local pressure, 500 … 1100 mbar
  double temperature_c = 10.0;    ///< annual mean local temperature, −90 … 60 °C
  /// ΔT = TT − UT1 in seconds; absent: Espenak & Meeus' polynomial for 1986 … 2050 (a few
  /// seconds off: about 0.0001° of the sun's position), libnova's estimate outside it.
  std::optional<double> delta_t_s;
};

/// The sun seen from a site at a time.
struct SunPosition {
  double zenith_deg = 0.0;     ///< topocentric zenith angle, refraction included when asked
  double elevation_deg = 0.0;  ///< 90 − zenith
  double azimuth_deg = 0.0;    ///< from true north, clockwise seen from above, [0, 360)
  double geometric_elevation_deg = 0.0;  ///< topocentric elevation without refraction
  double right_ascension_deg = 0.0;      ///< geocentric apparent, [0, 360)
  double declination_deg = 0.0;          ///< geocentric apparent
  double julian_day = 0.0;               ///< UT
  double delta_t_s = 0.0;                ///< the ΔT used
  double distance_au = 0.0;              ///< Earth–Sun distance
};

/// The sun's topocentric position. Throws InputError naming the field (`latitude_deg`,
/// `time.month`, `pressure_mbar`, ...) for a value out of range or not finite. Thread-safe
/// (libnova's calls are serialised).
SunPosition sun_position(const Site& site, const CivilTime& time, const SunOptions& options = {});

/// The unit vector toward the sun in a scene's frame (z up), whose true north is `north_deg`
/// from +y, counter-clockwise seen from above (the scene's `metadata.north_deg`): north is
/// (−sin n, cos n, 0), east (cos n, sin n, 0).
glm::dvec3 sun_direction(const SunPosition& position, double north_deg);

/// Reads an ISO 8601 date-time: `YYYY-MM-DDThh:mm[:ss[.fff]]` with an optional zone, `Z` or
/// `±hh[:mm]`. Without a zone in the text, `utc_offset_h` gives it; with neither, or with both
/// disagreeing, InputError naming `field`.
CivilTime parse_iso8601(std::string_view text, std::optional<double> utc_offset_h,
                        const std::string& field = "time");

}  // namespace lightsolver
