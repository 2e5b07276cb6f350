#pragma once
/// \file sunlight.hpp
/// EN 17037:2018 exposure to sunlight (docs/daylight.md, "Sunlight exposure (EN 17037)"): the
/// hours on one date during which the sun, above a minimum altitude, is seen from a reference
/// point on a window's inner surface. The sun's path comes from sun_position(); what hides it
/// comes from shadow rays through the scene's opaque meshes (glass lets it through).
///
/// Deterministic: the day is cut into steps of `step_minutes`, the sun taken at each step's
/// middle. Each reported period's ends are the edges of the steps where the state changed, so
/// each end is within half a step of the true instant when the sun's visibility changes at
/// most once between two step middles; a gap or a sunlit spell shorter than a step can be
/// missed, so in general each end is known to ± one step.

#include <functional>
#include <glm/vec3.hpp>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "lightsolver/daylight.hpp"
#include "lightsolver/error.hpp"

namespace lightsolver {

struct Scene;  // scene.hpp

/// One reference point (EN 17037: on the window's inner surface, at the middle of its width,
/// at least 1.2 m above the floor and 0.3 m above the sill).
struct SunlightPoint {
  std::string name;
  glm::dvec3 position{0.0};
  glm::dvec3 normal{0.0};  ///< out of the room through the window; any length but zero
};

/// The scene's `sunlight_exposure` object (docs/scene-format.md).
struct SunlightExposureSpec {
  Site site;
  double utc_offset_h = 0.0;  ///< the local civil time of the day's steps, hours from UTC
  int year = 2026, month = 3, day = 21;
  /// The site's minimum solar altitude (EN 17037 tabulates one per location); the apparent
  /// (refracted) altitude must exceed it.
  double min_elevation_deg = 11.0;
  int step_minutes = 1;    ///< 1 … 60, dividing the day's 1440 minutes
  double north_deg = 0.0;  ///< true north from +y, counter-clockwise (metadata.north_deg)
  std::vector<SunlightPoint> points;
};

/// The default minimum altitude when the scene gives none (docs/daylight.md says why).
inline constexpr double kDefaultSunlightMinElevation_deg = 11.0;

/// A sunlit period: local civil time, minutes from the day's midnight, start < end ≤ 1440.
struct SunlightPeriod {
  int start_minute = 0;
  int end_minute = 0;
};

/// One point's exposure.
struct SunlightPointResult {
  std::string name;
  double hours = 0.0;
  std::string level;  ///< "high" (≥ 4 h), "medium" (≥ 3 h), "minimum" (≥ 1.5 h) or "none"
  std::vector<SunlightPeriod> periods;
};

/// Every point's exposure on the date.
struct SunlightExposureResult {
  std::string date;  ///< YYYY-MM-DD
  int step_minutes = 1;
  double min_elevation_deg = kDefaultSunlightMinElevation_deg;
  std::vector<SunlightPointResult> points;
};

/// Is the way from `origin` toward the sun (`toward_sun`, unit) free of obstructions?
using SunlightVisibility =
    std::function<bool(const glm::dvec3& origin, const glm::dvec3& toward_sun)>;

/// Throws InputError(file, "sunlight_exposure.<field>") for a value out of range or not
/// finite: the site, `utc_offset_h`, the date (a real day), `min_elevation_deg` (−1 … 90),
/// `step_minutes`, each point's `position` and `normal` (not zero). A date outside EN 17037's
/// 1 February … 21 March is no error: it is returned as a warning.
Warnings validate_sunlight_exposure(const SunlightExposureSpec& spec, const std::string& file = "");

/// EN 17037's level for a number of hours: "high", "medium", "minimum" or "none".
const char* sunlight_level(double hours);

/// The exposure with a given test of the sun's way (pure geometry: no scene). Validates first.
SunlightExposureResult sunlight_exposure(const SunlightExposureSpec& spec,
                                         const SunlightVisibility& unobstructed);

/// The exposure of `scene.sunlight_exposure`: shadow rays through the scene's meshes (Embree),
/// every material but glass opaque. InputError when the scene has no `sunlight_exposure`.
SunlightExposureResult sunlight_exposure(const Scene& scene);

/// A scene file read for its sunlight exposure alone: validated as load_scene() does, but it
/// may have no luminaire and no target. InputError naming the file and field, or saying it has
/// no `sunlight_exposure`.
Scene load_sunlight_scene(const std::string& path);

/// "HH:MM" of a minute of the day (0 … 1440).
std::string clock_text(int minute);

/// The results' `sunlight_exposure` object (docs/scene-format.md, "Results").
nlohmann::json sunlight_exposure_json(const SunlightExposureResult& r);

/// The inverse of sunlight_exposure_json(); InputError naming `file` and the field.
SunlightExposureResult sunlight_exposure_from_json(const nlohmann::json& j,
                                                   const std::string& file = "");

/// A readable table: one line per point (hours, level, periods).
std::string sunlight_exposure_table(const SunlightExposureResult& r);

}  // namespace lightsolver
