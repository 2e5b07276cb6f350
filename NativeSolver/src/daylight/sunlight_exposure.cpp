// EN 17037 exposure to sunlight (lightsolver/sunlight.hpp; docs/daylight.md, "Sunlight exposure
// (EN 17037)"): the sun's path over one day in steps, and each reference point's sunlit periods
// given a test of the sun's way. No scene and no ray tracing here (src/embree/sunlight_rays.cpp).
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>

#include "daylight/sun_position.hpp"
#include "lightsolver/sunlight.hpp"

namespace lightsolver {
namespace {

constexpr int kDayMinutes = 1440;
constexpr double kMaxCoordinate_m = 1e9;  // scene.hpp's limits::kMaxCoordinate_m

class Checker {
 public:
  explicit Checker(const std::string& file) : file_(file) {}

  void require(bool ok, const std::string& field, const std::string& what) const {
    if (!ok) throw InputError(file_, "sunlight_exposure." + field, what);
  }

  void range(double v, double lo, double hi, const std::string& field, const char* unit) const {
    std::ostringstream s;
    s << "must be a number from " << lo << " to " << hi << unit;
    if (std::isfinite(v)) s << ", got " << v;
    require(std::isfinite(v) && v >= lo && v <= hi, field, s.str());
  }

  void point(const glm::dvec3& p, const std::string& field) const {
    for (int i = 0; i < 3; ++i) {
      require(std::isfinite(p[i]), field, "every coordinate must be a finite number");
      require(std::abs(p[i]) <= kMaxCoordinate_m, field, "a coordinate beyond ±1e9 m");
    }
  }

 private:
  const std::string& file_;
};

std::string date_text(int year, int month, int day) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%04d-%02d-%02d", year, month, day);
  return buf;
}

// The sun at the middle of each step: its direction in the scene's frame, or a zero vector
// while it is not above the minimum altitude. The same for every point, so computed once.
std::vector<glm::dvec3> compute_sun_path(const SunlightExposureSpec& s) {
  const int steps = kDayMinutes / s.step_minutes;
  std::vector<glm::dvec3> path(steps, glm::dvec3(0.0));
  for (int k = 0; k < steps; ++k) {
    // Whole seconds: a step of an odd number of minutes has its middle on a half minute.
    const int mid_s = k * s.step_minutes * 60 + s.step_minutes * 30;
    const CivilTime t{
        s.year, s.month, s.day, mid_s / 3600, mid_s / 60 % 60, double(mid_s % 60), s.utc_offset_h};
    const SunPosition p = sun_position(s.site, t);  // refraction at the standard atmosphere
    if (p.elevation_deg > s.min_elevation_deg) path[k] = sun_direction(p, s.north_deg);
  }
  return path;
}

// The inputs of a day's path, for the cache below.
auto path_key(const SunlightExposureSpec& s) {
  return std::make_tuple(s.site.latitude_deg, s.site.longitude_deg, s.site.elevation_m,
                         s.utc_offset_h, s.year, s.month, s.day, s.min_elevation_deg,
                         s.step_minutes, s.north_deg);
}

// A day's path costs 1440 full sun positions (VSOP87: ~0.05 s) and is the same for every run
// of a scene: the optimizer's and a study's many runs compute it once. The last path is kept.
std::vector<glm::dvec3> sun_path(const SunlightExposureSpec& s) {
  static std::mutex mutex;
  static std::optional<decltype(path_key(s))> last_key;
  static std::vector<glm::dvec3> last_path;
  const std::lock_guard<std::mutex> lock(mutex);
  if (last_key != path_key(s)) {
    last_path = compute_sun_path(s);
    last_key = path_key(s);
  }
  return last_path;
}

SunlightPointResult point_exposure(const SunlightExposureSpec& s, const SunlightPoint& pt,
                                   const std::vector<glm::dvec3>& path,
                                   const SunlightVisibility& unobstructed) {
  SunlightPointResult r;
  r.name = pt.name;
  const glm::dvec3 n = glm::normalize(pt.normal);
  int sunlit_minutes = 0;
  bool open = false;
  for (std::size_t k = 0; k < path.size(); ++k) {
    const glm::dvec3& d = path[k];
    // The window's front half-space first: behind the window the sun is not seen, and the
    // shadow ray is the costly test.
    const bool seen = glm::dot(d, n) > 0.0 && unobstructed(pt.position, d);
    const int start = int(k) * s.step_minutes;
    if (seen) {
      sunlit_minutes += s.step_minutes;
      if (open) {
        r.periods.back().end_minute = start + s.step_minutes;
      } else {
        r.periods.push_back({start, start + s.step_minutes});
      }
    }
    open = seen;
  }
  r.hours = sunlit_minutes / 60.0;
  r.level = sunlight_level(r.hours);
  return r;
}

}  // namespace

Warnings validate_sunlight_exposure(const SunlightExposureSpec& s, const std::string& file) {
  const Checker c(file);
  c.range(s.site.latitude_deg, -90, 90, "site.latitude_deg", "°");
  c.range(s.site.longitude_deg, -180, 180, "site.longitude_deg", "°");
  c.range(s.site.elevation_m, -500, 9000, "site.elevation_m", " m");
  c.range(s.utc_offset_h, -14, 14, "site.utc_offset_h", " h");
  const std::string date = date_text(s.year, s.month, s.day);
  c.require(s.year >= 1 && s.year <= 6000 && s.month >= 1 && s.month <= 12 && s.day >= 1 &&
                s.day <= detail::days_in_month(s.year, s.month),
            "date", "no such day: " + date);
  c.range(s.min_elevation_deg, 0, 89, "min_elevation_deg", "°");
  c.require(s.step_minutes >= 1 && s.step_minutes <= 60 && kDayMinutes % s.step_minutes == 0,
            "step_minutes",
            "must be a whole number of minutes from 1 to 60 that divides the day's 1440 (1, 2, "
            "3, 4, 5, 6, 10, 12, 15, 20, 30, 60), got " +
                std::to_string(s.step_minutes));
  c.require(!s.points.empty(), "points", "give at least one reference point");
  // North is the scene's metadata.north_deg (sun_direction's range).
  if (!(std::isfinite(s.north_deg) && std::abs(s.north_deg) <= 360.0)) {
    throw InputError(file, "metadata.north_deg", "must be a number from -360 to 360°");
  }
  std::set<std::string> names;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const SunlightPoint& p = s.points[i];
    const std::string at = "points[" + std::to_string(i) + "]";
    c.require(!p.name.empty(), at + ".name", "must not be empty");
    c.require(names.insert(p.name).second, at + ".name",
              "\"" + p.name + "\" names an earlier point too: each point needs its own name");
    c.point(p.position, at + ".position");
    c.point(p.normal, at + ".normal");
    c.require(glm::length(p.normal) > 1e-12, at + ".normal",
              "must not be zero: it points out of the room through the window");
  }
  Warnings w;
  // EN 17037 assesses a day from 1 February to 21 March; another day is computed the same way.
  if (s.month < 2 || s.month > 3 || (s.month == 3 && s.day > 21)) {
    w.push_back((file.empty() ? std::string("<scene>") : file) +
                ": sunlight_exposure.date: " + date +
                " is outside EN 17037's 1 February to 21 March: the hours are computed for it, "
                "but they are not the standard's assessment");
  }
  return w;
}

const char* sunlight_level(double hours) {
  // Hours are whole steps of whole minutes: exact to far below this margin.
  constexpr double kEps = 1e-9;
  if (hours >= 4.0 - kEps) return "high";
  if (hours >= 3.0 - kEps) return "medium";
  if (hours >= 1.5 - kEps) return "minimum";
  return "none";
}

SunlightExposureResult sunlight_exposure(const SunlightExposureSpec& spec,
                                         const SunlightVisibility& unobstructed) {
  validate_sunlight_exposure(spec);
  SunlightExposureResult r;
  r.date = date_text(spec.year, spec.month, spec.day);
  r.step_minutes = spec.step_minutes;
  r.min_elevation_deg = spec.min_elevation_deg;
  const std::vector<glm::dvec3> path = sun_path(spec);
  for (const SunlightPoint& p : spec.points)
    r.points.push_back(point_exposure(spec, p, path, unobstructed));
  return r;
}

std::string clock_text(int minute) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%02d:%02d", minute / 60, minute % 60);
  return buf;
}

std::string sunlight_exposure_table(const SunlightExposureResult& r) {
  std::ostringstream out;
  out << "sunlight exposure (EN 17037) on " << r.date << ", sun above " << r.min_elevation_deg
      << "°, steps of " << r.step_minutes << " min (each period's ends ± " << r.step_minutes
      << " min)\n";
  for (const SunlightPointResult& p : r.points) {
    char head[64];
    std::snprintf(head, sizeof head, "%5.2f h  %-8s", p.hours, p.level.c_str());
    out << "  " << head << p.name;
    std::string sep = ": ";
    for (const SunlightPeriod& q : p.periods) {
      out << sep << clock_text(q.start_minute) << "–" << clock_text(q.end_minute);
      sep = ", ";
    }
    out << "\n";
  }
  return out.str();
}

}  // namespace lightsolver
