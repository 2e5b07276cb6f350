// lightsolver.annual (docs/daylight.md, "Daylight coefficients: a year in one trace"): the annual
// run of lightsolver/annual_run.hpp; the summary as annual.json holds it (a dict), every grid's
// hours as float32 numpy arrays (hours × cells). Bad input raises lightsolver.InputError.
#include "annual_bindings.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <exception>
#include <optional>
#include <string>

#include "lightsolver/annual_run.hpp"
#include "lightsolver/scene_io.hpp"
#include "simulation_bindings.hpp"

namespace py = pybind11;
using namespace lightsolver;

namespace {

py::array_t<float> hours_by_cells(const std::vector<float>& v, std::size_t hours) {
  const auto h = static_cast<py::ssize_t>(hours);
  py::array_t<float> a({h, static_cast<py::ssize_t>(hours > 0 ? v.size() / hours : 0)});
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

py::dict annual_dict(const Scene& scene, const std::filesystem::path& weather, int mf,
                     double north_deg, std::optional<double> ground_reflectance, bool illuminance,
                     std::uint64_t photons, std::optional<std::uint64_t> seed,
                     const std::string& backend, int threads, double confidence,
                     std::optional<double> blinds_transmittance, bool decide,
                     std::optional<std::uint64_t> max_photons, const py::object& progress,
                     const py::object& cancel, const std::vector<std::uint8_t>& occupancy,
                     std::pair<int, int> occupied_hours) {
  AnnualRunOptions o;
  o.weather = weather;
  o.sky.mf = mf;
  o.sky.north_deg = north_deg;
  o.ground_reflectance = ground_reflectance;
  o.sky.use_illuminance = illuminance;
  o.photons = photons;
  o.seed = seed;
  o.backend = backend;
  o.threads = threads;
  o.confidence = confidence;
  o.blinds_transmittance = blinds_transmittance;
  o.decide = decide;
  o.max_photons = max_photons;
  o.occupancy = occupancy;
  o.occupied_first = occupied_hours.first;
  o.occupied_last = occupied_hours.second;
  // progress(done, total) may return False; a CancelToken (or anything with `cancelled`) stops
  // the trace too. Both under the GIL; an exception in progress is raised after the run.
  std::exception_ptr callback_error;
  const ProgressFn user = python_progress(progress, callback_error);
  if (user || !cancel.is_none()) {
    o.progress = [&user, &cancel](std::uint64_t done, std::uint64_t total) {
      if (!cancel.is_none()) {
        py::gil_scoped_acquire gil;
        if (cancel.attr("cancelled").cast<bool>()) return false;
      }
      return user ? user(done, total) : true;
    };
  }
  AnnualResult r;
  {
    py::gil_scoped_release release;
    r = run_annual(scene, o);
  }
  if (callback_error) std::rethrow_exception(callback_error);
  const std::size_t hours = r.month_day_hour.size() / 3;
  py::list grids;
  for (const AnnualGrid& g : r.grids) {
    py::dict d;
    d["name"] = g.name;
    d["mean"] = hours_by_cells(g.hourly.mean, hours);
    d["low"] = hours_by_cells(g.low, hours);
    d["high"] = hours_by_cells(g.high, hours);
    d["direct_sun"] = g.direct_sun.empty() ? py::object(py::none())
                                           : py::object(hours_by_cells(g.direct_sun, hours));
    grids.append(d);
  }
  py::array_t<std::int32_t> stamps({static_cast<py::ssize_t>(hours), py::ssize_t(3)});
  std::copy(r.month_day_hour.begin(), r.month_day_hour.end(), stamps.mutable_data());
  py::dict out;
  out["summary"] = py::module_::import("json").attr("loads")(r.summary.dump());
  out["grids"] = grids;
  out["month_day_hour"] = stamps;
  return out;
}

}  // namespace

void bind_annual(py::module_& m) {
  const char* doc =
      "annual(scene, weather, *, mf=1, north_deg=0, ground_reflectance=None (the scene's sky's), "
      "illuminance=False, photons=20_000_000, seed=None, backend='auto', threads=0, "
      "confidence=0.95, blinds_transmittance=None, decide=False, max_photons=None, "
      "progress=None, cancel=None, occupancy=[] (one 0/1 per hour), occupied_hours=(9, 18) "
      "(EPW hour stamps, LM-83's 8:00-18:00)): a year of "
      "daylight by daylight coefficients (docs/daylight.md, 'Daylight coefficients: a year in "
      "one trace'). `scene` a Scene or a scene file's path (its one sky's openings, its "
      "grids), `weather` an EPW file. Returns a dict: summary (annual.json: weather with its "
      "sha256, sky, trace, seconds, occupancy, grids with their metrics), grids (name, mean, low, "
      "high, direct_sun: float32 hours x cells, lx) and month_day_hour. InputError names the "
      "field, option or weather line.";
  auto bind = [&](auto scene_arg) {
    m.def(
        "annual",
        [](decltype(scene_arg) scene, const std::filesystem::path& weather, int mf,
           double north_deg, std::optional<double> ground_reflectance, bool illuminance,
           std::uint64_t photons, std::optional<std::uint64_t> seed, const std::string& backend,
           int threads, double confidence, std::optional<double> blinds, bool decide,
           std::optional<std::uint64_t> max_photons, const py::object& progress,
           const py::object& cancel, const std::vector<std::uint8_t>& occupancy,
           std::pair<int, int> occupied_hours) {
          if constexpr (std::is_same_v<decltype(scene_arg), std::string>) {
            return annual_dict(load_scene(scene), weather, mf, north_deg, ground_reflectance,
                               illuminance, photons, seed, backend, threads, confidence, blinds,
                               decide, max_photons, progress, cancel, occupancy, occupied_hours);
          } else {
            return annual_dict(scene, weather, mf, north_deg, ground_reflectance, illuminance,
                               photons, seed, backend, threads, confidence, blinds, decide,
                               max_photons, progress, cancel, occupancy, occupied_hours);
          }
        },
        py::arg("scene"), py::arg("weather"), py::kw_only(), py::arg("mf") = 1,
        py::arg("north_deg") = 0.0, py::arg("ground_reflectance") = py::none(),
        py::arg("illuminance") = false, py::arg("photons") = 20'000'000,
        py::arg("seed") = py::none(), py::arg("backend") = "auto", py::arg("threads") = 0,
        py::arg("confidence") = 0.95, py::arg("blinds_transmittance") = py::none(),
        py::arg("decide") = false, py::arg("max_photons") = py::none(),
        py::arg("progress") = py::none(), py::arg("cancel") = py::none(),
        py::arg("occupancy") = std::vector<std::uint8_t>{},
        py::arg("occupied_hours") = std::pair<int, int>{9, 18}, doc);
  };
  bind(Scene{});
  bind(std::string{});
}
