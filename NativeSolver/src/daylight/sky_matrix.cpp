// A year of sky vectors from a weather file (include/lightsolver/sky_patches.hpp, sky_matrix):
// the sun at the middle of each hour, the Perez sky of the hour, its sky vector.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

#include "daylight/sky_models.hpp"
#include "daylight/sky_vector.hpp"
#include "lightsolver/error.hpp"
#include "lightsolver/sky_patches.hpp"
#include "lightsolver/weather.hpp"

namespace lightsolver {

namespace {

int day_of_year(int month, int day, bool leap) {
  static constexpr std::array<int, 12> kBefore = {0,   31,  59,  90,  120, 151,
                                                  181, 212, 243, 273, 304, 334};
  return kBefore[static_cast<std::size_t>(month - 1)] + day + (leap && month > 2 ? 1 : 0);
}

// The value of an hour's column, or InputError naming the file, line and column.
double needed(const std::optional<double>& v, const WeatherFile& w, const WeatherHour& h,
              const char* column) {
  if (!v)
    throw InputError(w.file, "line " + std::to_string(h.line),
                     std::string(column) + " is missing (the sun is up: the sky needs it)");
  return *v;
}

void check_options(const SkyMatrixOptions& o) {
  if (!(o.ground_reflectance >= 0.0 && o.ground_reflectance <= 1.0))
    throw InputError("", "ground_reflectance", "must be between 0 and 1");
  if (o.points < 1 || o.points > 32)
    throw InputError("", "points", "must be from 1 to 32, got " + std::to_string(o.points));
}

// Every this many hours the patches' quadrature of the horizontal illuminance is checked
// against the model's fine one (horizontal_integral: 10⁵–10⁶ evaluations, ~0.1 s).
constexpr std::size_t kCheckEvery = 50;

// Row i of the matrix: the Perez sky of `spec`, normalised by its own patches (the Sky class'
// fine horizontal integral would cost ~0.1 s an hour), as the Sky class builds it otherwise.
// Writes row i only; returns the patches' relative quadrature error of the horizontal
// illuminance where `check` asks for it, else 0.
double hour_sky(const daylight::SkySpec& spec, const SkyPatches& patches, const SkyMatrixOptions& o,
                bool check, SkyMatrix& m, std::size_t i) {
  const daylight::Direction& sun = *spec.sun;
  const double zenith = std::acos(sun.z);
  daylight::PerezState st = daylight::perez_state(spec.perez, zenith);
  daylight::SkyShape shape = daylight::perez_shape(st, zenith);
  double raw_h = 0.0;
  std::vector<double> v = daylight::raw_patch_integrals(shape, sun, patches, o.points, raw_h);
  // Where the coefficients give no light above the horizon, raise the brightness (PerezState).
  while (!(raw_h > 0.0) && st.shape_delta < 0.6 - 1e-9) {
    st.shape_delta = std::min(0.6, st.shape_delta + 0.01);
    shape = daylight::perez_shape(st, zenith);
    v = daylight::raw_patch_integrals(shape, sun, patches, o.points, raw_h);
  }
  if (!(raw_h > 0.0) || !std::isfinite(raw_h))
    throw std::invalid_argument("the sky model gives no light above the horizon");
  double error = 0.0;
  if (check) {
    const double fine = daylight::horizontal_integral(shape, sun);
    error = std::abs(raw_h - fine) / fine;
  }
  const double scale = st.diffuse_horizontal_lx / raw_h;
  for (double& x : v) x *= scale;
  const double global = st.diffuse_horizontal_lx + st.direct_normal_lx * sun.z;
  v[0] = o.ground_reflectance * global / std::numbers::pi * patches.patch(0).solid_angle_sr;
  const glm::dvec3 s{sun.x, sun.y, sun.z};
  float sun_lx = static_cast<float>(st.direct_normal_lx);
  if (o.radiance_sun && st.direct_normal_lx > 0.0) {
    daylight::add_sun_as_radiance(v, patches, s, st.direct_normal_lx);
    sun_lx = 0.0f;
  }
  const auto n = v.size();
  for (std::size_t p = 0; p < n; ++p) m.sky[i * n + p] = static_cast<float>(v[p]);
  for (int k = 0; k < 3; ++k)
    m.sun_direction[i * 3 + static_cast<std::size_t>(k)] = static_cast<float>(s[k]);
  m.sun_direct_normal_lx[i] = sun_lx;
  m.diffuse_horizontal_lx[i] = static_cast<float>(st.diffuse_horizontal_lx);
  m.status[i] = 2;
  return error;
}

// An hour with diffuse light: its row and its Perez sky.
struct DaylightHour {
  std::size_t row = 0;
  int line = 0;
  daylight::SkySpec spec;
};

// Every daylight hour's sky, in parallel: each writes its own row, and a failure is reported
// for the first such hour in file order, whatever order the threads finished in.
void daylight_hours(const std::vector<DaylightHour>& hours, const SkyPatches& patches,
                    const SkyMatrixOptions& o, const std::string& file, SkyMatrix& m) {
  std::vector<double> errors(hours.size(), 0.0);
  std::vector<std::string> failed(hours.size());
  tbb::parallel_for(std::size_t(0), hours.size(), [&](std::size_t k) {
    const DaylightHour& h = hours[k];
    try {
      errors[k] = hour_sky(h.spec, patches, o, h.row % kCheckEvery == 0, m, h.row);
    } catch (const std::invalid_argument& e) {
      failed[k] = e.what();
    }
  });
  for (std::size_t k = 0; k < hours.size(); ++k) {
    if (!failed[k].empty())
      throw InputError(file, "line " + std::to_string(hours[k].line), failed[k]);
  }
  for (double e : errors) m.max_quadrature_error = std::max(m.max_quadrature_error, e);
}

// Hour i's sun (row i's altitude and status) and, where it has diffuse light, its sky to
// compute; InputError naming the file and line where its inputs fail.
std::optional<DaylightHour> hour_inputs(const WeatherFile& weather, std::size_t i,
                                        const SkyMatrixOptions& options, SkyMatrix& m) {
  const WeatherLocation& loc = weather.location;
  const Site site{loc.latitude_deg, loc.longitude_deg, loc.elevation_m};
  const WeatherHour& h = weather.hours[i];
  // The row describes the hour ending at its stamp (standard time): its middle is h − 0.5.
  const CivilTime t{h.year, h.month, h.day, h.hour - 1, 30, 0.0, loc.utc_offset_h};
  SunPosition pos;
  try {
    pos = sun_position(site, t, options.sun);
  } catch (const InputError& e) {  // a date the calendar lacks (29 February of a plain year)
    throw InputError(weather.file, "line " + std::to_string(h.line), e.what());
  }
  const glm::dvec3 sun = sun_direction(pos, options.north_deg);
  m.sun_altitude_deg[i] = static_cast<float>(pos.elevation_deg);
  if (!(sun.z > 0.0)) return std::nullopt;  // status 0: night
  daylight::SkySpec spec;
  spec.model = daylight::SkyModel::Perez;
  spec.sun = daylight::Direction{sun.x, sun.y, sun.z};
  spec.ground_reflectance = options.ground_reflectance;
  spec.perez.illuminance = options.use_illuminance;
  spec.perez.day_of_year = day_of_year(h.month, h.day, weather.hours.size() == 8784);
  if (options.use_illuminance) {
    spec.perez.diffuse_horizontal =
        needed(h.diffuse_horizontal_lx, weather, h, "Diffuse Horizontal Illuminance");
    spec.perez.direct_normal = needed(h.direct_normal_lx, weather, h, "Direct Normal Illuminance");
  } else {
    spec.perez.diffuse_horizontal =
        needed(h.diffuse_horizontal_w_m2, weather, h, "Diffuse Horizontal Radiation");
    spec.perez.direct_normal = needed(h.direct_normal_w_m2, weather, h, "Direct Normal Radiation");
  }
  m.status[i] = 1;
  if (!(spec.perez.diffuse_horizontal > 0.0)) return std::nullopt;  // gendaymtx's zero
  return DaylightHour{i, h.line, spec};
}

}  // namespace

SkyMatrix sky_matrix(const WeatherFile& weather, const SkyMatrixOptions& options) {
  check_options(options);
  const SkyPatches patches(options.mf, options.north_deg);
  SkyMatrix m;
  m.mf = options.mf;
  m.patch_count = patches.count();
  m.hours = static_cast<int>(weather.hours.size());
  const auto hours = weather.hours.size(), n = static_cast<std::size_t>(m.patch_count);
  m.sky.assign(hours * n, 0.0f);
  m.sun_direction.assign(hours * 3, 0.0f);
  m.sun_direct_normal_lx.assign(hours, 0.0f);
  m.sun_altitude_deg.assign(hours, 0.0f);
  m.diffuse_horizontal_lx.assign(hours, 0.0f);
  m.status.assign(hours, 0);
  // The suns in order (sun_position serialises libnova anyway), the skies then in parallel. An
  // hour whose inputs fail ends the list; a sky before it that fails is reported first.
  std::vector<DaylightHour> daylight;
  std::exception_ptr failed_inputs;
  for (std::size_t i = 0; i < hours && !failed_inputs; ++i) {
    try {
      if (std::optional<DaylightHour> d = hour_inputs(weather, i, options, m)) {
        daylight.push_back(std::move(*d));
      }
    } catch (const InputError&) {
      failed_inputs = std::current_exception();
    }
  }
  daylight_hours(daylight, patches, options, weather.file, m);
  if (failed_inputs) std::rethrow_exception(failed_inputs);
  return m;
}

}  // namespace lightsolver
