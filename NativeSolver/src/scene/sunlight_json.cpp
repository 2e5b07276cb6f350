// The `sunlight_exposure` objects of a scene and of its results (docs/scene-format.md,
// "Sunlight exposure (EN 17037)"; lightsolver/sunlight.hpp).
#include "scene/sunlight_json.hpp"

#include <cctype>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "lightsolver/scene.hpp"
#include "scene/scene_document.hpp"

namespace lightsolver {
namespace detail {
namespace {

// "YYYY-MM-DD" into the spec; the day's existence is validate_sunlight_exposure()'s.
void read_date(const JsonNode& n, SunlightExposureSpec& s) {
  const std::string text = n.string();
  bool ok = text.size() == 10 && text[4] == '-' && text[7] == '-';
  for (std::size_t i = 0; ok && i < text.size(); ++i)
    ok = i == 4 || i == 7 || std::isdigit(static_cast<unsigned char>(text[i]));
  if (!ok) n.fail("expected a date YYYY-MM-DD (2026-03-21), got \"" + text + "\"");
  s.year = std::stoi(text.substr(0, 4));
  s.month = std::stoi(text.substr(5, 2));
  s.day = std::stoi(text.substr(8, 2));
}

// "HH:MM", 00:00 … 24:00.
int read_clock(const JsonNode& n) {
  const std::string text = n.string();
  const bool ok = text.size() == 5 && text[2] == ':' && std::isdigit((unsigned char)text[0]) &&
                  std::isdigit((unsigned char)text[1]) && std::isdigit((unsigned char)text[3]) &&
                  std::isdigit((unsigned char)text[4]);
  const int minute = ok ? std::stoi(text.substr(0, 2)) * 60 + std::stoi(text.substr(3, 2)) : -1;
  if (!ok || std::stoi(text.substr(3, 2)) > 59 || minute > 1440)
    n.fail("expected a time of day HH:MM (00:00 to 24:00), got \"" + text + "\"");
  return minute;
}

}  // namespace

SunlightExposureSpec read_sunlight_exposure(const JsonNode& n, double north_deg,
                                            Warnings& warnings) {
  n.require_object({"site", "date", "min_elevation_deg", "step_minutes", "points"});
  SunlightExposureSpec s;
  const JsonNode site = n.at("site");
  site.require_object({"latitude_deg", "longitude_deg", "utc_offset_h", "elevation_m"});
  s.site.latitude_deg = site.at("latitude_deg").number();
  s.site.longitude_deg = site.at("longitude_deg").number();
  s.utc_offset_h = site.at("utc_offset_h").number();
  s.site.elevation_m = site.number_or("elevation_m", 0.0);
  read_date(n.at("date"), s);
  s.min_elevation_deg = n.number_or("min_elevation_deg", kDefaultSunlightMinElevation_deg);
  if (n.has("step_minutes")) {
    const std::uint64_t step = n.at("step_minutes").unsigned_integer();
    if (step < 1 || step > 60)
      n.at("step_minutes").fail("must be from 1 to 60 minutes, got " + std::to_string(step));
    s.step_minutes = int(step);
  }
  s.north_deg = north_deg;
  const JsonNode points = n.at("points");
  for (std::size_t i = 0; i < points.array_size(); ++i) {
    const JsonNode p = points[i];
    p.require_object({"name", "position", "normal"});
    s.points.push_back({p.at("name").string(), p.at("position").vec3(), p.at("normal").vec3()});
  }
  const Warnings w = validate_sunlight_exposure(s, n.file());
  warnings.insert(warnings.end(), w.begin(), w.end());
  return s;
}

SunlightExposureResult read_sunlight_exposure_result(const JsonNode& n) {
  n.require_object({"date", "step_minutes", "min_elevation_deg", "points"});
  SunlightExposureResult r;
  r.date = n.at("date").string();
  r.step_minutes = int(n.at("step_minutes").unsigned_integer());
  r.min_elevation_deg = n.at("min_elevation_deg").number();
  const JsonNode points = n.at("points");
  for (std::size_t i = 0; i < points.array_size(); ++i) {
    const JsonNode p = points[i];
    p.require_object({"name", "hours", "level", "periods"});
    SunlightPointResult q;
    q.name = p.at("name").string();
    q.hours = p.at("hours").number();
    q.level = p.at("level").string();
    const JsonNode periods = p.at("periods");
    for (std::size_t k = 0; k < periods.array_size(); ++k) {
      const JsonNode period = periods[k];
      if (period.array_size() != 2) period.fail("expected [\"HH:MM\", \"HH:MM\"]");
      q.periods.push_back({read_clock(period[0]), read_clock(period[1])});
    }
    r.points.push_back(std::move(q));
  }
  return r;
}

}  // namespace detail

nlohmann::json sunlight_exposure_json(const SunlightExposureResult& r) {
  nlohmann::json points = nlohmann::json::array();
  for (const SunlightPointResult& p : r.points) {
    nlohmann::json periods = nlohmann::json::array();
    for (const SunlightPeriod& q : p.periods)
      periods.push_back({clock_text(q.start_minute), clock_text(q.end_minute)});
    points.push_back(
        {{"name", p.name}, {"hours", p.hours}, {"level", p.level}, {"periods", periods}});
  }
  return {{"date", r.date},
          {"step_minutes", r.step_minutes},
          {"min_elevation_deg", r.min_elevation_deg},
          {"points", points}};
}

Scene load_sunlight_scene(const std::string& path) {
  const std::string base = std::filesystem::path(path).parent_path().string();
  Scene scene = detail::read_unvalidated_scene(detail::read_scene_text(path), path, base);
  // Only the light needs luminaires and targets: their absence is no error here, every other
  // validation error is.
  for (const InputError& e : validation_errors(scene)) {
    const bool no_light = (e.where() == "luminaires" && scene.luminaires.empty()) ||
                          (e.where() == "targets" && scene.targets.empty());
    if (!no_light) throw e;
  }
  if (!scene.sunlight_exposure) {
    throw InputError(path, "sunlight_exposure",
                     "the scene has no sunlight_exposure object (docs/scene-format.md)");
  }
  return scene;
}

SunlightExposureResult sunlight_exposure_from_json(const nlohmann::json& j,
                                                   const std::string& file) {
  return detail::read_sunlight_exposure_result(detail::JsonNode(j, "sunlight_exposure", file));
}

}  // namespace lightsolver
