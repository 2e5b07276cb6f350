// lightsolver.direct_sun (docs/daylight.md, "Direct sun at points (for ASE)"): points and
// normals as n × 3 float64 arrays, the year's sun as sky_vectors() gives it (hours × 3 and
// hours float32), the result hours × points float32. Bad input raises lightsolver.InputError.
#include "direct_sun_bindings.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "lightsolver/direct_sun.hpp"

namespace py = pybind11;
using namespace lightsolver;

namespace {

using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Floats = py::array_t<float, py::array::c_style | py::array::forcecast>;

// An n × 3 array as vectors; InputError naming `field` for another shape.
std::vector<glm::dvec3> vectors(const Doubles& a, const char* field) {
  if (a.ndim() != 2 || a.shape(1) != 3) {
    throw InputError("direct_sun_lx", field, "must be an array of shape (n, 3)");
  }
  std::vector<glm::dvec3> out(static_cast<std::size_t>(a.shape(0)));
  const double* d = a.data();
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = {d[3 * i], d[3 * i + 1], d[3 * i + 2]};
  return out;
}

std::vector<float> floats(const Floats& a) { return {a.data(), a.data() + a.size()}; }

glm::dvec3 vec3_of(const py::dict& d, const char* key, const std::string& at) {
  if (!d.contains(key)) throw InputError("direct_sun_lx", at + "." + key, "is missing");
  const auto v = d[key].cast<std::vector<double>>();
  if (v.size() != 3) throw InputError("direct_sun_lx", at + "." + key, "needs 3 numbers");
  return {v[0], v[1], v[2]};
}

// Openings given as dicts: corner, edge1, edge2, optional glazing (transmittance, panes,
// frame_factor, maintenance_factor) and two_sided.
std::vector<SunOpening> openings_of(const py::list& list) {
  std::vector<SunOpening> out;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string at = "openings[" + std::to_string(k) + "]";
    const auto d = list[k].cast<py::dict>();
    SunOpening o{vec3_of(d, "corner", at), vec3_of(d, "edge1", at), vec3_of(d, "edge2", at),
                 std::nullopt, d.contains("two_sided") && d["two_sided"].cast<bool>()};
    if (d.contains("glazing") && !d["glazing"].is_none()) {
      const auto g = d["glazing"].cast<py::dict>();
      GlazingDefinition gd;
      if (!g.contains("transmittance")) {
        throw InputError("direct_sun_lx", at + ".glazing.transmittance", "is missing");
      }
      gd.transmittance = g["transmittance"].cast<double>();
      if (g.contains("panes")) gd.panes = g["panes"].cast<int>();
      if (g.contains("frame_factor")) gd.frame_factor = g["frame_factor"].cast<double>();
      if (g.contains("maintenance_factor")) {
        gd.maintenance_factor = g["maintenance_factor"].cast<double>();
      }
      o.glazing = gd;
    }
    out.push_back(o);
  }
  return out;
}

py::array_t<float> direct_sun(const Scene& scene, const Doubles& points, const Doubles& normals,
                              const Floats& sun_direction, const Floats& sun_direct_normal_lx,
                              const py::object& openings) {
  const std::vector<SunOpening> o =
      openings.is_none() ? sun_openings(scene) : openings_of(openings.cast<py::list>());
  const std::vector<glm::dvec3> p = vectors(points, "points"), n = vectors(normals, "normals");
  const std::vector<float> d = floats(sun_direction), e = floats(sun_direct_normal_lx);
  std::vector<float> r;
  {
    py::gil_scoped_release release;
    r = direct_sun_lx(scene, o, p, n, d, e);
  }
  py::array_t<float> a({static_cast<py::ssize_t>(e.size()), static_cast<py::ssize_t>(p.size())});
  std::copy(r.begin(), r.end(), a.mutable_data());
  return a;
}

}  // namespace

void bind_direct_sun(py::module_& m) {
  m.def("direct_sun", &direct_sun, py::arg("scene"), py::arg("points"), py::arg("normals"),
        py::arg("sun_direction"), py::arg("sun_direct_normal_lx"), py::kw_only(),
        py::arg("openings") = py::none(),
        "Direct sunlight (lx) at points for each hour, the sun's beam alone (docs/daylight.md, "
        "'Direct sun at points (for ASE)'): hours x points float32. points and normals are "
        "(n, 3) arrays (unit normals); sun_direction (hours x 3) and sun_direct_normal_lx "
        "(hours) as sky_vectors() returns them. openings: None takes the scene's (its sun's "
        "opening or portals, else its sky's portals, else an open site); [] an open site; or a "
        "list of dicts with corner, edge1, edge2 (edge1 x edge2 into the room), optional "
        "glazing {transmittance, panes, frame_factor, maintenance_factor} and two_sided. "
        "InputError names the field of a bad value.");
}
