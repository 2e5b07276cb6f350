// `lightsolver sun` and `lightsolver weather` (docs/daylight.md): the same C++ functions as
// Python's lightsolver.sun_position and lightsolver.read_weather.
#include "sun_command.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>

#include "lightsolver/daylight.hpp"
#include "lightsolver/error.hpp"
#include "lightsolver/weather.hpp"

namespace lightsolver::cli {
namespace {

struct SunArgs {
  Site site;
  std::string time;
  std::optional<double> tz;
  bool utc = false;
  double north_deg = 0.0;
  SunOptions options;
  bool no_refraction = false;
  bool json = false;
};

std::string signed_hours(double h) {
  char buf[32];
  const long minutes = std::lround(std::abs(h) * 60.0);
  std::snprintf(buf, sizeof buf, "UTC%s%02ld:%02ld", h < 0 ? "−" : "+", minutes / 60, minutes % 60);
  return buf;
}

void print_sun_text(const SunArgs& a, const CivilTime& t, const SunPosition& p,
                    const glm::dvec3& d) {
  std::printf("site       %.6f° %s, %.6f° %s, %g m\n", std::abs(a.site.latitude_deg),
              a.site.latitude_deg < 0 ? "S" : "N", std::abs(a.site.longitude_deg),
              a.site.longitude_deg < 0 ? "W" : "E", a.site.elevation_m);
  std::printf("time       %04d-%02d-%02d %02d:%02d:%06.3f %s (ΔT %.1f s)\n", t.year, t.month, t.day,
              t.hour, t.minute, t.second, signed_hours(t.utc_offset_h).c_str(), p.delta_t_s);
  std::printf("elevation  %.5f°%s\n", p.elevation_deg,
              p.elevation_deg < 0.0 ? " (below the horizon)" : "");
  std::printf("zenith     %.5f°\n", p.zenith_deg);
  std::printf("azimuth    %.5f° (from north, clockwise)\n", p.azimuth_deg);
  if (a.options.refraction)
    std::printf("refraction %.5f° at %g mbar, %g °C\n", p.elevation_deg - p.geometric_elevation_deg,
                a.options.pressure_mbar, a.options.temperature_c);
  else
    std::printf("refraction none (geometric position)\n");
  std::printf(
      "direction  [%.6f, %.6f, %.6f] toward the sun (scene frame, z up, north %g° "
      "counter-clockwise from +y)\n",
      d.x, d.y, d.z, a.north_deg);
}

// An InputError of the sun's inputs as the command line's: "--lat: must be ...". The library
// names fields as the scene does (latitude_deg, time.month); the user typed flags.
std::string flag_message(const InputError& e) {
  static const std::pair<const char*, const char*> kFlags[] = {{"latitude_deg", "--lat"},
                                                               {"longitude_deg", "--lon"},
                                                               {"elevation_m", "--elevation-m"},
                                                               {"pressure_mbar", "--pressure-mbar"},
                                                               {"temperature_c", "--temperature-c"},
                                                               {"delta_t_s", "--delta-t-s"},
                                                               {"north_deg", "--north-deg"},
                                                               {"time.", "--time"}};
  std::string what = e.what();
  const std::string prefix = e.file() + ": " + e.where() + ": ";
  if (what.rfind(prefix, 0) == 0) what = what.substr(prefix.size());
  std::string flag = e.where();
  for (const auto& [field, name] : kFlags)
    if (flag.rfind(field, 0) == 0) flag = name;
  if (what.find("has no time zone") != std::string::npos) what += ", or give --tz or --utc";
  return flag + ": " + what;
}

int run_sun(SunArgs a) {
  try {
    const std::optional<double> tz = a.utc ? std::optional<double>(0.0) : a.tz;
    const CivilTime t = parse_iso8601(a.time, tz, "--time");
    a.options.refraction = !a.no_refraction;
    const SunPosition p = sun_position(a.site, t, a.options);
    const glm::dvec3 d = sun_direction(p, a.north_deg);
    if (!a.json) {
      print_sun_text(a, t, p, d);
      return 0;
    }
    nlohmann::json j = {{"latitude_deg", a.site.latitude_deg},
                        {"longitude_deg", a.site.longitude_deg},
                        {"elevation_m", a.site.elevation_m},
                        {"time", a.time},
                        {"utc_offset_h", t.utc_offset_h},
                        {"julian_day", p.julian_day},
                        {"delta_t_s", p.delta_t_s},
                        {"zenith_deg", p.zenith_deg},
                        {"elevation_deg", p.elevation_deg},
                        {"azimuth_deg", p.azimuth_deg},
                        {"geometric_elevation_deg", p.geometric_elevation_deg},
                        {"right_ascension_deg", p.right_ascension_deg},
                        {"declination_deg", p.declination_deg},
                        {"distance_au", p.distance_au},
                        {"refraction", a.options.refraction},
                        {"north_deg", a.north_deg},
                        {"direction", {d.x, d.y, d.z}}};
    if (a.options.refraction) {
      j["pressure_mbar"] = a.options.pressure_mbar;
      j["temperature_c"] = a.options.temperature_c;
    }
    std::cout << j.dump(2) << "\n";
    return 0;
  } catch (const InputError& e) {
    std::cerr << "error: " << flag_message(e) << "\n";
    return 1;
  }
}

int run_weather(const std::string& file, bool json) {
  try {
    const WeatherFile w = read_epw(file);
    const double median = median_external_diffuse_illuminance(w);
    const WeatherLocation& l = w.location;
    if (json) {
      nlohmann::json j = {{"file", file},
                          {"city", l.city},
                          {"region", l.region},
                          {"country", l.country},
                          {"source", l.source},
                          {"wmo", l.wmo},
                          {"latitude_deg", l.latitude_deg},
                          {"longitude_deg", l.longitude_deg},
                          {"utc_offset_h", l.utc_offset_h},
                          {"elevation_m", l.elevation_m},
                          {"hours", w.hours.size()},
                          {"median_diffuse_illuminance_lx", median}};
      std::cout << j.dump(2) << "\n";
      return 0;
    }
    std::printf("location   %s%s%s, %s (%s, WMO %s)\n", l.city.c_str(),
                l.region.empty() ? "" : ", ", l.region.c_str(), l.country.c_str(), l.source.c_str(),
                l.wmo.c_str());
    std::printf("site       %.4f° %s, %.4f° %s, %g m, %s\n", std::abs(l.latitude_deg),
                l.latitude_deg < 0 ? "S" : "N", std::abs(l.longitude_deg),
                l.longitude_deg < 0 ? "W" : "E", l.elevation_m,
                signed_hours(l.utc_offset_h).c_str());
    std::printf("hours      %zu\n", w.hours.size());
    std::printf(
        "median external diffuse illuminance (EN 17037, the brighter half of the "
        "year's hours) %.0f lx\n",
        median);
    return 0;
  } catch (const InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace

void add_sun_command(CLI::App& app) {
  auto a = std::make_shared<SunArgs>();
  CLI::App* cmd = app.add_subcommand(
      "sun",
      "The sun's position for a site and a time: elevation, zenith, azimuth (from north, "
      "clockwise) and the direction toward it in a scene's frame");
  cmd->add_option("--lat", a->site.latitude_deg, "Latitude, degrees (north positive)")->required();
  cmd->add_option("--lon", a->site.longitude_deg, "Longitude, degrees (east positive)")->required();
  cmd->add_option("--time", a->time,
                  "Date and time, ISO 8601: 2026-03-21T12:00, with Z or ±hh:mm or --tz/--utc")
      ->required();
  CLI::Option* tz = cmd->add_option("--tz", a->tz, "Time zone of --time: hours from UTC (−7)");
  cmd->add_flag("--utc", a->utc, "--time is UTC")->excludes(tz);
  cmd->add_option("--elevation-m", a->site.elevation_m, "Site height above sea level, m")
      ->capture_default_str();
  cmd->add_option("--north-deg", a->north_deg,
                  "True north from +y, counter-clockwise seen from above (the scene's "
                  "metadata.north_deg)")
      ->capture_default_str();
  cmd->add_option("--pressure-mbar", a->options.pressure_mbar, "Air pressure for refraction")
      ->capture_default_str();
  cmd->add_option("--temperature-c", a->options.temperature_c, "Air temperature for refraction")
      ->capture_default_str();
  cmd->add_flag("--no-refraction", a->no_refraction, "The geometric position, without refraction");
  cmd->add_option("--delta-t-s", a->options.delta_t_s,
                  "ΔT = TT − UT1 in seconds (default: libnova's estimate for the date)");
  cmd->add_flag("--json", a->json, "Print one JSON object");
  cmd->callback([a] {
    if (const int rc = run_sun(*a); rc != 0) throw CLI::RuntimeError(rc);
  });
}

void add_weather_command(CLI::App& app) {
  auto file = std::make_shared<std::string>();
  auto json = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand(
      "weather",
      "Read an EPW weather file: its location and EN 17037's median external diffuse "
      "illuminance");
  cmd->add_option("file", *file, "EnergyPlus weather file (.epw)")->required();
  cmd->add_flag("--json", *json, "Print one JSON object");
  cmd->callback([file, json] {
    if (const int rc = run_weather(*file, *json); rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace lightsolver::cli
