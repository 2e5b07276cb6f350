// lightsolver.sun_position and lightsolver.read_weather (docs/daylight.md): the same functions
// as `lightsolver sun` and `lightsolver weather`. Bad input raises lightsolver.InputError.
#include "daylight_bindings.hpp"

#include <pybind11/stl.h>

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "lightsolver/daylight.hpp"
#include "lightsolver/scene.hpp"
#include "lightsolver/sunlight.hpp"
#include "lightsolver/weather.hpp"

namespace py = pybind11;
using namespace lightsolver;

namespace {

py::dict sun_position_dict(double latitude_deg, double longitude_deg, const std::string& time,
                           std::optional<double> utc_offset_h, double elevation_m, double north_deg,
                           bool refraction, double pressure_mbar, double temperature_c,
                           std::optional<double> delta_t_s) {
  const CivilTime t = parse_iso8601(time, utc_offset_h, "time");
  SunOptions o;
  o.refraction = refraction;
  o.pressure_mbar = pressure_mbar;
  o.temperature_c = temperature_c;
  o.delta_t_s = delta_t_s;
  const SunPosition p = sun_position({latitude_deg, longitude_deg, elevation_m}, t, o);
  const glm::dvec3 d = sun_direction(p, north_deg);
  py::dict r;
  r["zenith_deg"] = p.zenith_deg;
  r["elevation_deg"] = p.elevation_deg;
  r["azimuth_deg"] = p.azimuth_deg;
  r["geometric_elevation_deg"] = p.geometric_elevation_deg;
  r["right_ascension_deg"] = p.right_ascension_deg;
  r["declination_deg"] = p.declination_deg;
  r["julian_day"] = p.julian_day;
  r["delta_t_s"] = p.delta_t_s;
  r["distance_au"] = p.distance_au;
  r["utc_offset_h"] = t.utc_offset_h;
  r["direction"] = py::make_tuple(d.x, d.y, d.z);
  return r;
}

py::object optional_value(const std::optional<double>& v) {
  return v ? py::object(py::float_(*v)) : py::object(py::none());
}

py::dict weather_dict(const std::string& path) {
  const WeatherFile w = read_epw(path);
  const WeatherLocation& l = w.location;
  py::dict location;
  location["city"] = l.city;
  location["region"] = l.region;
  location["country"] = l.country;
  location["source"] = l.source;
  location["wmo"] = l.wmo;
  location["latitude_deg"] = l.latitude_deg;
  location["longitude_deg"] = l.longitude_deg;
  location["utc_offset_h"] = l.utc_offset_h;
  location["elevation_m"] = l.elevation_m;
  py::list hours;
  for (const WeatherHour& h : w.hours) {
    py::dict row;
    row["month"] = h.month;
    row["day"] = h.day;
    row["hour"] = h.hour;
    row["direct_normal_w_m2"] = optional_value(h.direct_normal_w_m2);
    row["diffuse_horizontal_w_m2"] = optional_value(h.diffuse_horizontal_w_m2);
    row["global_horizontal_lx"] = optional_value(h.global_horizontal_lx);
    row["direct_normal_lx"] = optional_value(h.direct_normal_lx);
    row["diffuse_horizontal_lx"] = optional_value(h.diffuse_horizontal_lx);
    hours.append(row);
  }
  py::dict r;
  r["file"] = w.file;
  r["location"] = location;
  r["hours"] = hours;
  bool complete = true;
  for (const WeatherHour& h : w.hours) complete = complete && h.diffuse_horizontal_lx.has_value();
  r["median_diffuse_illuminance_lx"] =
      complete ? py::object(py::float_(median_external_diffuse_illuminance(w)))
               : py::object(py::none());
  return r;
}

// The results' `sunlight_exposure` object as a dict (one writer: sunlight_exposure_json).
py::dict sunlight_exposure_dict(const Scene& scene) {
  const std::string text = sunlight_exposure_json(sunlight_exposure(scene)).dump();
  return py::module_::import("json").attr("loads")(text);
}

// A scene file, which may have no luminaire and no target (`lightsolver sunlight`'s reading).
py::dict sunlight_exposure_file_dict(const std::string& path) {
  return sunlight_exposure_dict(load_sunlight_scene(path));
}

}  // namespace

void bind_daylight(py::module_& m) {
  m.def("sun_position", &sun_position_dict, py::arg("latitude_deg"), py::arg("longitude_deg"),
        py::arg("time"), py::kw_only(), py::arg("utc_offset_h") = py::none(),
        py::arg("elevation_m") = 0.0, py::arg("north_deg") = 0.0, py::arg("refraction") = true,
        py::arg("pressure_mbar") = 1010.0, py::arg("temperature_c") = 10.0,
        py::arg("delta_t_s") = py::none(),
        "The sun's topocentric position (docs/daylight.md, 'Sun'): `time` is ISO 8601 "
        "(2026-03-21T12:00+01:00; without a zone, give utc_offset_h). Returns a dict: "
        "zenith_deg, elevation_deg, azimuth_deg (from north, clockwise), "
        "geometric_elevation_deg (without refraction), right_ascension_deg, declination_deg, "
        "julian_day, delta_t_s, distance_au, utc_offset_h and direction (toward the sun in the "
        "scene frame, z up, north `north_deg` counter-clockwise from +y). InputError names the "
        "field of a bad value.");
  m.def("read_weather", &weather_dict, py::arg("path"),
        "Read an EPW weather file (docs/daylight.md, 'Weather'): a dict with file, location "
        "(city, region, country, source, wmo, latitude_deg, longitude_deg, utc_offset_h, "
        "elevation_m), hours (one dict per hour: month, day, hour ending, the irradiances in "
        "W/m² and illuminances in lx, None where the file marks them missing) and "
        "median_diffuse_illuminance_lx (EN 17037's E_v,d,med; None when an hour's diffuse "
        "illuminance is missing). InputError names the file and line of malformed input.");
  m.def("sunlight_exposure", &sunlight_exposure_dict, py::arg("scene"),
        "EN 17037 sunlight exposure of the scene's `sunlight_exposure` reference points "
        "(docs/daylight.md, 'Sunlight exposure (EN 17037)'): a dict with date, step_minutes, "
        "min_elevation_deg and points (name, hours, level: high/medium/minimum/none, periods: "
        "[[\"HH:MM\", \"HH:MM\"], ...] in the site's local time), as a run's results carry it. "
        "InputError names the field of a bad value, or says the scene has none.");
  m.def("sunlight_exposure", &sunlight_exposure_file_dict, py::arg("path"),
        "The same for a scene file's path: the file may have no luminaire and no target.");
}
