// lightsolver.sky_patches and lightsolver.sky_vectors (docs/daylight.md, "Sky patches and sky
// vectors"): numpy arrays, float64 for the patches' geometry, float32 for the year's matrix.
// Bad input raises lightsolver.InputError.
#include "sky_patches_bindings.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <string>
#include <vector>

#include "lightsolver/sky_patches.hpp"
#include "lightsolver/weather.hpp"

namespace py = pybind11;
using namespace lightsolver;

namespace {

template <class T>
py::array_t<T> array(const std::vector<T>& v, std::vector<py::ssize_t> shape) {
  py::array_t<T> a(shape);
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

py::dict patches_dict(int mf, double north_deg) {
  const SkyPatches p(mf, north_deg);
  const auto n = static_cast<std::size_t>(p.count());
  std::vector<double> centre(n * 3), omega(n), mean_cos(n), alt0(n), alt1(n), azi(n), width(n);
  std::vector<int> row(n);
  for (std::size_t i = 0; i < n; ++i) {
    const SkyPatch& q = p.patch(static_cast<int>(i));
    for (int k = 0; k < 3; ++k) centre[i * 3 + static_cast<std::size_t>(k)] = q.centre[k];
    omega[i] = q.solid_angle_sr;
    mean_cos[i] = q.mean_cos_zenith;
    alt0[i] = q.altitude_min_deg;
    alt1[i] = q.altitude_max_deg;
    azi[i] = q.azimuth_deg;
    width[i] = q.azimuth_width_deg;
    row[i] = q.row;
  }
  const auto sn = static_cast<py::ssize_t>(n);
  py::dict r;
  r["mf"] = mf;
  r["north_deg"] = north_deg;
  r["count"] = p.count();
  r["centre"] = array(centre, {sn, 3});
  r["solid_angle_sr"] = array(omega, {sn});
  r["mean_cos_zenith"] = array(mean_cos, {sn});
  r["altitude_min_deg"] = array(alt0, {sn});
  r["altitude_max_deg"] = array(alt1, {sn});
  r["azimuth_deg"] = array(azi, {sn});
  r["azimuth_width_deg"] = array(width, {sn});
  r["row"] = array(row, {sn});
  return r;
}

py::dict sky_vectors_dict(const std::string& path, int mf, double north_deg,
                          double ground_reflectance, bool illuminance, bool radiance_sun,
                          int points) {
  const WeatherFile w = read_epw(path);
  SkyMatrixOptions o;
  o.mf = mf;
  o.north_deg = north_deg;
  o.ground_reflectance = ground_reflectance;
  o.use_illuminance = illuminance;
  o.radiance_sun = radiance_sun;
  o.points = points;
  SkyMatrix m;
  {
    py::gil_scoped_release release;
    m = sky_matrix(w, o);
  }
  const auto h = static_cast<py::ssize_t>(m.hours);
  std::vector<int> month, day, hour;
  for (const WeatherHour& x : w.hours) {
    month.push_back(x.month);
    day.push_back(x.day);
    hour.push_back(x.hour);
  }
  py::dict r;
  r["file"] = w.file;
  r["mf"] = m.mf;
  r["north_deg"] = north_deg;
  r["sky"] = array(m.sky, {h, static_cast<py::ssize_t>(m.patch_count)});
  r["sun_direction"] = array(m.sun_direction, {h, 3});
  r["sun_direct_normal_lx"] = array(m.sun_direct_normal_lx, {h});
  r["sun_altitude_deg"] = array(m.sun_altitude_deg, {h});
  r["diffuse_horizontal_lx"] = array(m.diffuse_horizontal_lx, {h});
  r["status"] = array(m.status, {h});
  r["month"] = array(month, {h});
  r["day"] = array(day, {h});
  r["hour"] = array(hour, {h});
  r["max_quadrature_error"] = m.max_quadrature_error;
  r["bytes"] = m.bytes();
  r["radiance_sun"] = radiance_sun;
  r["illuminance_columns"] = illuminance;
  return r;
}

}  // namespace

void bind_sky_patches(py::module_& m) {
  m.def("sky_patches", &patches_dict, py::arg("mf") = 1, py::arg("north_deg") = 0.0,
        "Reinhart sky patches (docs/daylight.md, 'Sky patches and sky vectors'), numbered as "
        "Radiance's reinhart.cal: 0 the ground, then rows from the horizon up, each from north "
        "toward east, the zenith cap last. A dict: mf, north_deg, count, and per patch "
        "'centre' (count x 3, the scene frame), 'solid_angle_sr', 'mean_cos_zenith' (an "
        "upward sensor's daylight coefficient), 'altitude_min_deg', 'altitude_max_deg', "
        "'azimuth_deg' (centre, from north toward east), 'azimuth_width_deg', 'row' (-1 ground).");
  m.def("sky_vectors", &sky_vectors_dict, py::arg("epw_path"), py::arg("mf") = 1,
        py::arg("north_deg") = 0.0, py::arg("ground_reflectance") = 0.2,
        py::arg("illuminance") = false, py::arg("radiance_sun") = false, py::arg("points") = 4,
        "A year of sky vectors from an EPW file (docs/daylight.md): 'sky' (hours x patches, "
        "float32, each patch's mean luminance x solid angle in cd.sr/m2, ground first), "
        "'sun_direction' (hours x 3, toward the sun at the middle of the hour; zeros without a "
        "sun), 'sun_direct_normal_lx' (the sun kept apart; 0 with radiance_sun=True, which puts "
        "it into the 4 nearest patches as gendaymtx does), 'sun_altitude_deg', "
        "'diffuse_horizontal_lx', 'status' (0 night, 1 no diffuse light, 2 sky), 'month', "
        "'day', 'hour' (the file's stamps), 'max_quadrature_error', 'bytes'. The Perez sky from "
        "the irradiance columns with Perez' efficacies, or illuminance=True for the "
        "illuminance columns.");
}
