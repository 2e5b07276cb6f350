// EN 17037 sunlight exposure (docs/daylight.md, "Sunlight exposure (EN 17037)"): hours at a
// window's reference point against the sun's path computed here from NOAA's equations
// (noaa_reference.cpp, independent of libnova), with shadow rays through scenes built here.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>

#include "lightsolver/angles.hpp"
#include "lightsolver/error.hpp"
#include "lightsolver/results_io.hpp"
#include "lightsolver/scene.hpp"
#include "lightsolver/scene_io.hpp"
#include "lightsolver/solver.hpp"
#include "lightsolver/sunlight.hpp"
#include "noaa_reference.hpp"
#include "scene_builders.hpp"

namespace lightsolver {
namespace {

// Paris on the 2026 March equinox (20 March), UTC+1: the sun rises almost due east, so a
// south-facing window sees it from sunrise to sunset.
SunlightExposureSpec paris(glm::dvec3 normal, int month = 3, int day = 20) {
  SunlightExposureSpec s;
  s.site = {48.8566, 2.3522, 35.0};
  s.utc_offset_h = 1.0;
  s.year = 2026;
  s.month = month;
  s.day = day;
  s.min_elevation_deg = 11.0;
  s.step_minutes = 1;
  s.points = {{"window", glm::dvec3(0.0), normal}};
  return s;
}

// UT Julian day of a local civil minute of the spec's day (std::chrono's calendar, not ours).
double julian_day(const SunlightExposureSpec& s, double local_minute) {
  using namespace std::chrono;
  const sys_days d{year{s.year} / month{unsigned(s.month)} / day{unsigned(s.day)}};
  return 2440587.5 + d.time_since_epoch().count() + (local_minute / 60.0 - s.utc_offset_h) / 24.0;
}

// NOAA's geometric elevation plus Saemundsson's refraction (Meeus 16.4, at 1010 mbar, 10 °C):
// another formula than the solver's (SPA's Bennett), 0.001° apart near 11°.
struct Sky {
  double elevation_deg, azimuth_deg;
};
Sky noaa_sky(const SunlightExposureSpec& s, double local_minute) {
  const test::NoaaPosition p =
      test::noaa_position(julian_day(s, local_minute), s.site.latitude_deg, s.site.longitude_deg);
  const double h = p.elevation_deg;
  const double r_arcmin = h > -1.0 ? 1.02 / std::tan((h + 10.3 / (h + 5.11)) * kDeg) : 0.0;
  return {h + r_arcmin / 60.0, p.azimuth_deg};
}

// The sunlit minutes by the reference: the sun above the minimum altitude, in the window's
// front half-space (scene frame: north +y, east +x) and not hidden by `blocked(azimuth)`.
struct Reference {
  int minutes = 0, first = -1, last = -1;
};
Reference noaa_minutes(const SunlightExposureSpec& s, const glm::dvec3& normal,
                       const std::function<bool(const Sky&)>& blocked) {
  Reference r;
  for (int m = 0; m < 1440; ++m) {
    const Sky sky = noaa_sky(s, m + 0.5);
    const double az = sky.azimuth_deg * kDeg, el = sky.elevation_deg * kDeg;
    const glm::dvec3 d(std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el));
    if (sky.elevation_deg > s.min_elevation_deg && glm::dot(d, normal) > 0 && !blocked(sky)) {
      ++r.minutes;
      if (r.first < 0) r.first = m;
      r.last = m + 1;
    }
  }
  return r;
}

// The solar time at which NOAA's azimuth reaches `azimuth_deg` in the morning (bisection).
double noaa_minute_at_azimuth(const SunlightExposureSpec& s, double azimuth_deg) {
  double lo = 360.0, hi = 760.0;  // 06:00 … 12:40 local: the morning's azimuths 90° … 180°
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (noaa_sky(s, mid).azimuth_deg < azimuth_deg ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

Scene scene_with(const SunlightExposureSpec& spec) {
  Scene scene;
  scene.materials = {default_material("wall", Material::Type::Diffuse),
                     default_material("glass", Material::Type::Glass)};
  scene.sunlight_exposure = spec;
  return scene;
}

const glm::dvec3 kSouth(0, -1, 0), kNorth(0, 1, 0);

TEST(SunlightExposure, UnobstructedSouthWindowOnTheEquinoxMatchesNoaa) {
  const SunlightExposureSpec s = paris(kSouth);
  const SunlightExposureResult r = sunlight_exposure(s, [](auto&, auto&) { return true; });
  const Reference ref = noaa_minutes(s, kSouth, [](const Sky&) { return false; });
  ASSERT_EQ(r.points.size(), 1u);
  const SunlightPointResult& p = r.points[0];
  ASSERT_EQ(p.periods.size(), 1u);
  std::printf("[ sunlight ] Paris 2026-03-20 south: %.4f h, %d–%d min; NOAA %d min, %d–%d\n",
              p.hours, p.periods[0].start_minute, p.periods[0].end_minute, ref.minutes, ref.first,
              ref.last);
  // Each end within one step (the methods differ by 0.015°, seconds of time).
  EXPECT_NEAR(p.periods[0].start_minute, ref.first, 1);
  EXPECT_NEAR(p.periods[0].end_minute, ref.last, 1);
  EXPECT_NEAR(p.hours * 60.0, ref.minutes, 2);
  // About 9.6 h above 11° at 48.9° N on the equinox: the closed form 2·acos(sin 11°/cos φ)/15°
  // (δ = 0) gives 9.59 h; δ is −0.2° that day.
  const double closed = 2.0 * std::acos(std::sin(11 * kDeg) / std::cos(48.8566 * kDeg)) / kDeg / 15;
  EXPECT_NEAR(p.hours, closed, 0.1);
  EXPECT_EQ(p.level, "high");
  EXPECT_EQ(r.date, "2026-03-20");
}

TEST(SunlightExposure, EmbreeWithNothingOpaqueEqualsTheUnobstructedSun) {
  const SunlightExposureSpec s = paris(kSouth);
  Scene scene = scene_with(s);
  // A glass pane right in front of the point does not hide the sun (docs: glass is let through).
  scene.meshes.push_back(
      test::corner_quad({-1, -0.01, -1}, {1, -0.01, -1}, {1, -0.01, 1}, {-1, -0.01, 1}, 1));
  const SunlightExposureResult traced = sunlight_exposure(scene);
  const SunlightExposureResult free = sunlight_exposure(s, [](auto&, auto&) { return true; });
  EXPECT_EQ(traced.points[0].hours, free.points[0].hours);
  ASSERT_EQ(traced.points[0].periods.size(), 1u);
  EXPECT_EQ(traced.points[0].periods[0].start_minute, free.points[0].periods[0].start_minute);
  EXPECT_EQ(traced.points[0].periods[0].end_minute, free.points[0].periods[0].end_minute);
}

// A wall on the window's east side, square to it, 1 m away and 1 m deep (out of the room,
// southwards), hides the sun while its horizontal direction crosses the wall: azimuths from
// 90° to 180° − atan(1/1) = 135°. The morning starts when NOAA's azimuth passes 135°.
TEST(SunlightExposure, EastWallCutsTheMorningAtTheAzimuthOfItsEdge) {
  const SunlightExposureSpec s = paris(kSouth);
  Scene scene = scene_with(s);
  const double h = 1000.0;  // tall enough for any sun: only the azimuth matters
  scene.meshes.push_back(test::corner_quad({1, 0, -h}, {1, -1, -h}, {1, -1, h}, {1, 0, h}));
  const SunlightExposureResult r = sunlight_exposure(scene);
  const SunlightExposureResult free = sunlight_exposure(s, [](auto&, auto&) { return true; });
  const double edge = noaa_minute_at_azimuth(s, 135.0);
  const Reference ref = noaa_minutes(s, kSouth, [](const Sky& k) { return k.azimuth_deg < 135.0; });
  const SunlightPointResult& p = r.points[0];
  ASSERT_EQ(p.periods.size(), 1u);
  std::printf("[ sunlight ] east wall: sunlit from minute %d (azimuth 135° at %.2f), %.4f h\n",
              p.periods[0].start_minute, edge, p.hours);
  EXPECT_NEAR(p.periods[0].start_minute, edge, 1.0);
  EXPECT_NEAR(p.periods[0].start_minute, ref.first, 1);
  EXPECT_EQ(p.periods[0].end_minute, free.points[0].periods[0].end_minute);  // afternoon free
  EXPECT_NEAR(p.hours * 60.0, ref.minutes, 2);
}

// The window's own reveals: a 1.2 m wide, 2 m high opening through a 0.3 m thick wall, the
// point on the inner surface at mid-width and mid-height. The side reveals hide the sun when its
// horizontal direction is more than atan(0.6 / 0.3) = 63.43° from the window's normal (the top
// and bottom ones only above atan(1 / 0.3) = 73° of profile angle: never in Paris in March).
TEST(SunlightExposure, WindowRevealsNarrowTheDay) {
  const SunlightExposureSpec s = paris(kSouth);
  Scene scene = scene_with(s);
  const double w = 0.6, d = 0.3, h = 1.0;
  scene.meshes = {test::corner_quad({-w, 0, -h}, {-w, -d, -h}, {-w, -d, h}, {-w, 0, h}),
                  test::corner_quad({w, 0, -h}, {w, -d, -h}, {w, -d, h}, {w, 0, h}),
                  test::corner_quad({-w, 0, h}, {w, 0, h}, {w, -d, h}, {-w, -d, h}),
                  test::corner_quad({-w, 0, -h}, {w, 0, -h}, {w, -d, -h}, {-w, -d, -h})};
  const double limit = std::atan(w / d) / kDeg;
  const SunlightPointResult p = sunlight_exposure(scene).points[0];
  const Reference ref = noaa_minutes(
      s, kSouth, [&](const Sky& k) { return std::abs(k.azimuth_deg - 180.0) >= limit; });
  ASSERT_EQ(p.periods.size(), 1u);
  std::printf("[ sunlight ] reveals: %d–%d min (NOAA %d–%d), %.4f h\n", p.periods[0].start_minute,
              p.periods[0].end_minute, ref.first, ref.last, p.hours);
  EXPECT_NEAR(p.periods[0].start_minute, ref.first, 1);
  EXPECT_NEAR(p.periods[0].end_minute, ref.last, 1);
  EXPECT_NEAR(p.hours * 60.0, ref.minutes, 2);
  EXPECT_LT(p.hours, 9.0);  // the reveals cut both ends of the 9.75 h day
}

TEST(SunlightExposure, PointInsideAClosedBoxGetsNoSun) {
  SunlightExposureSpec s = paris(kSouth);
  s.points[0].position = {10, 20, 3};
  Scene scene = scene_with(s);
  const glm::dvec3 c = s.points[0].position;
  const double a = 0.5;
  auto v = [&](double x, double y, double z) { return c + a * glm::dvec3(x, y, z); };
  scene.meshes = {test::corner_quad(v(-1, -1, -1), v(1, -1, -1), v(1, 1, -1), v(-1, 1, -1)),
                  test::corner_quad(v(-1, -1, 1), v(1, -1, 1), v(1, 1, 1), v(-1, 1, 1)),
                  test::corner_quad(v(-1, -1, -1), v(1, -1, -1), v(1, -1, 1), v(-1, -1, 1)),
                  test::corner_quad(v(-1, 1, -1), v(1, 1, -1), v(1, 1, 1), v(-1, 1, 1)),
                  test::corner_quad(v(-1, -1, -1), v(-1, 1, -1), v(-1, 1, 1), v(-1, -1, 1)),
                  test::corner_quad(v(1, -1, -1), v(1, 1, -1), v(1, 1, 1), v(1, -1, 1))};
  const SunlightExposureResult r = sunlight_exposure(scene);
  EXPECT_EQ(r.points[0].hours, 0.0);
  EXPECT_EQ(r.points[0].level, "none");
  EXPECT_TRUE(r.points[0].periods.empty());
  // The same box of glass hides nothing.
  for (Mesh& m : scene.meshes) m.material = 1;
  EXPECT_GT(sunlight_exposure(scene).points[0].hours, 9.0);
}

TEST(SunlightExposure, NorthWindowInMarchInTheNorthGetsNoSun) {
  for (const int day : {1, 21}) {
    const SunlightExposureSpec s = paris(kNorth, 3, day);
    const SunlightExposureResult r = sunlight_exposure(s, [](auto&, auto&) { return true; });
    EXPECT_EQ(r.points[0].hours, 0.0) << "March " << day;
    EXPECT_EQ(noaa_minutes(s, kNorth, [](const Sky&) { return false; }).minutes, 0);
  }
  // South of the equator the same window faces the sun.
  SunlightExposureSpec south = paris(kNorth, 3, 1);
  south.site.latitude_deg = -33.87;
  EXPECT_GT(sunlight_exposure(south, [](auto&, auto&) { return true; }).points[0].hours, 8.0);
}

TEST(SunlightExposure, NorthDegTurnsTheSite) {
  // With north at +x (north_deg −90: north = (−sin n, cos n) = (1, 0)), south is −x.
  SunlightExposureSpec s = paris({-1, 0, 0});
  s.north_deg = -90.0;
  const auto free = [](auto&, auto&) { return true; };
  EXPECT_EQ(sunlight_exposure(s, free).points[0].hours,
            sunlight_exposure(paris(kSouth), free).points[0].hours);
}

TEST(SunlightExposure, StepsCoarsenTheEndsByAtMostAStep) {
  const auto free = [](auto&, auto&) { return true; };
  SunlightExposureSpec s = paris(kSouth);
  const SunlightPeriod fine = sunlight_exposure(s, free).points[0].periods[0];
  for (const int step : {5, 15, 60}) {
    s.step_minutes = step;
    const SunlightExposureResult r = sunlight_exposure(s, free);
    const SunlightPeriod q = r.points[0].periods[0];
    EXPECT_EQ(q.start_minute % step, 0);
    EXPECT_LE(std::abs(q.start_minute - fine.start_minute), step) << step;
    EXPECT_LE(std::abs(q.end_minute - fine.end_minute), step) << step;
    EXPECT_EQ(r.step_minutes, step);
  }
}

TEST(SunlightExposure, LevelsAreTheStandardsThresholds) {
  EXPECT_STREQ(sunlight_level(0.0), "none");
  EXPECT_STREQ(sunlight_level(1.49), "none");
  EXPECT_STREQ(sunlight_level(1.5), "minimum");
  EXPECT_STREQ(sunlight_level(2.99), "minimum");
  EXPECT_STREQ(sunlight_level(3.0), "medium");
  EXPECT_STREQ(sunlight_level(3.99), "medium");
  EXPECT_STREQ(sunlight_level(4.0), "high");
}

// The field named by a bad spec's InputError.
std::string error_field(const SunlightExposureSpec& s) {
  try {
    validate_sunlight_exposure(s, "f.json");
  } catch (const InputError& e) {
    return e.where();
  }
  return "(no error)";
}

TEST(SunlightExposure, BadInputNamesTheField) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  SunlightExposureSpec s = paris(kSouth);
  EXPECT_EQ(error_field(s), "(no error)");
  s.site.latitude_deg = 95;
  EXPECT_EQ(error_field(s), "sunlight_exposure.site.latitude_deg");
  s = paris(kSouth);
  s.site.longitude_deg = nan;
  EXPECT_EQ(error_field(s), "sunlight_exposure.site.longitude_deg");
  s = paris(kSouth);
  s.utc_offset_h = 15;
  EXPECT_EQ(error_field(s), "sunlight_exposure.site.utc_offset_h");
  s = paris(kSouth, 2, 30);
  EXPECT_EQ(error_field(s), "sunlight_exposure.date");
  for (const int step : {0, 7, 61, -1}) {
    s = paris(kSouth);
    s.step_minutes = step;
    EXPECT_EQ(error_field(s), "sunlight_exposure.step_minutes") << step;
  }
  s = paris(kSouth);
  s.min_elevation_deg = -5;
  EXPECT_EQ(error_field(s), "sunlight_exposure.min_elevation_deg");
  s = paris(glm::dvec3(0.0));
  EXPECT_EQ(error_field(s), "sunlight_exposure.points[0].normal");
  s = paris(kSouth);
  s.points[0].position.y = nan;
  EXPECT_EQ(error_field(s), "sunlight_exposure.points[0].position");
  s = paris(kSouth);
  s.points.push_back(s.points[0]);
  EXPECT_EQ(error_field(s), "sunlight_exposure.points[1].name");
  s.points.clear();
  EXPECT_EQ(error_field(s), "sunlight_exposure.points");
  s = paris(kSouth);
  s.north_deg = 400;
  EXPECT_EQ(error_field(s), "metadata.north_deg");
  // The computation refuses what validation refuses.
  s = paris(kSouth);
  s.step_minutes = 0;
  EXPECT_THROW(sunlight_exposure(s, [](auto&, auto&) { return true; }), InputError);
  EXPECT_THROW(sunlight_exposure(Scene{}), InputError);  // no sunlight_exposure in the scene
}

TEST(SunlightExposure, DateOutsideTheStandardsSpanIsAWarningNotAnError) {
  EXPECT_TRUE(validate_sunlight_exposure(paris(kSouth, 2, 1)).empty());
  EXPECT_TRUE(validate_sunlight_exposure(paris(kSouth, 3, 21)).empty());
  for (const auto& [m, d] : {std::pair{1, 31}, {3, 22}, {6, 21}}) {
    const Warnings w = validate_sunlight_exposure(paris(kSouth, m, d), "f.json");
    ASSERT_EQ(w.size(), 1u);
    EXPECT_NE(w[0].find("f.json: sunlight_exposure.date"), std::string::npos) << w[0];
  }
}

std::string scene_text(const std::string& sunlight) {
  return R"({"format": "lightsolver.scene/1", "materials": {"w": {"type": "diffuse"}},
             "meshes": [{"name": "m", "material": "w", "vertices": [[0,0,-1], [1,0,-1], [0,1,-1]],
                         "triangles": [[0, 1, 2]]}],
             "luminaires": [{"name": "l", "type": "point", "flux_lm": 1, "position": [0, 0, 1]}],
             "targets": [{"name": "t", "type": "surface", "mesh": "m"}],
             "metadata": {"north_deg": -90}, "sunlight_exposure": )" +
         sunlight + "}";
}

const char* kSunlight = R"({"site": {"latitude_deg": 48.8566, "longitude_deg": 2.3522,
  "utc_offset_h": 1, "elevation_m": 35}, "date": "2026-03-20", "min_elevation_deg": 11,
  "step_minutes": 1, "points": [{"name": "w", "position": [0, 0, 0], "normal": [-1, 0, 0]}]})";

TEST(SunlightExposureScene, ReadsTheKeyWithNorthFromTheMetadata) {
  const Scene scene = scene_from_json(scene_text(kSunlight), "s.json", "");
  ASSERT_TRUE(scene.sunlight_exposure.has_value());
  EXPECT_EQ(scene.sunlight_exposure->north_deg, -90.0);
  const auto free = [](auto&, auto&) { return true; };
  EXPECT_EQ(sunlight_exposure(scene).points[0].hours,
            sunlight_exposure(paris(kSouth), free).points[0].hours);
}

std::string scene_error(const std::string& from, const std::string& to) {
  std::string text = kSunlight;
  const auto at = text.find(from);
  if (at == std::string::npos) return "(no such text: " + from + ")";
  text.replace(at, from.size(), to);
  try {
    scene_from_json(scene_text(text), "s.json", "");
  } catch (const InputError& e) {
    return e.where();
  }
  return "(no error)";
}

TEST(SunlightExposureScene, ErrorsNameTheField) {
  EXPECT_EQ(scene_error("\"step_minutes\": 1", "\"step_minutes\": 0"),
            "sunlight_exposure.step_minutes");
  EXPECT_EQ(scene_error("\"step_minutes\": 1", "\"step_minutes\": 1.5"),
            "sunlight_exposure.step_minutes");
  EXPECT_EQ(scene_error("\"latitude_deg\": 48.8566", "\"latitude_deg\": -91"),
            "sunlight_exposure.site.latitude_deg");
  EXPECT_EQ(scene_error("2026-03-20", "2026-3-20"), "sunlight_exposure.date");
  EXPECT_EQ(scene_error("2026-03-20", "2026-02-29"), "sunlight_exposure.date");
  EXPECT_EQ(scene_error("\"normal\": [-1, 0, 0]", "\"normal\": [0, 0, 0]"),
            "sunlight_exposure.points[0].normal");
  EXPECT_EQ(scene_error("\"normal\": [-1, 0, 0]", "\"normal\": [0, 0]"),
            "sunlight_exposure.points[0].normal");
  EXPECT_EQ(scene_error("\"min_elevation_deg\": 11", "\"min_elevation_deg\": 11, \"x\": 1"),
            "sunlight_exposure.x");
  // A date outside 1 February … 21 March loads with a warning naming the field.
  std::string june = kSunlight;
  june.replace(june.find("2026-03-20"), 10, "2026-06-21");
  const Scene scene = scene_from_json(scene_text(june), "s.json", "");
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find("s.json: sunlight_exposure.date"), std::string::npos);
}

TEST(SunlightExposureScene, ResultsRoundTrip) {
  Results results;
  results.sunlight_exposure = sunlight_exposure(paris(kSouth), [](auto&, auto& d) {
    return d.x > 0.3 || d.x < -0.1;  // two periods
  });
  ASSERT_EQ(results.sunlight_exposure->points[0].periods.size(), 2u);
  const std::string text = results_to_json(results);
  const nlohmann::json j = nlohmann::json::parse(text);
  EXPECT_EQ(j["sunlight_exposure"]["points"][0]["periods"].size(), 2u);
  EXPECT_EQ(results_to_json(results_from_json(text)), text);
  EXPECT_NE(results_table(results, false).find("sunlight exposure (EN 17037)"), std::string::npos);
}

}  // namespace
}  // namespace lightsolver
