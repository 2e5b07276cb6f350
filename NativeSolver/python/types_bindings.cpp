#include "types_bindings.hpp"

#include <pybind11/stl.h>

#include "lightsolver/type_tables.hpp"

namespace py = pybind11;

namespace {

py::list luminaire_types() {
  py::list out;
  for (const lightsolver::LuminaireTypeInfo& t : lightsolver::luminaire_type_infos()) {
    py::dict d;
    d["name"] = t.name;
    d["keys"] = t.keys;
    d["effect"] = t.effect;
    d["glare_source"] = t.glare_source.empty() ? py::object(py::none()) : py::str(t.glare_source);
    d["not_glare_because"] = t.not_glare_because;
    d["aimable"] = t.aimable;
    d["placed"] = t.placed;
    out.append(std::move(d));
  }
  return out;
}

py::list target_types() {
  py::list out;
  for (const lightsolver::TargetTypeInfo& t : lightsolver::target_type_infos()) {
    py::dict d;
    d["name"] = t.name;
    d["keys"] = t.keys;
    d["requirements"] = t.requirements;
    d["cells"] = t.cells;
    d["eyes"] = t.eyes;
    d["tally"] = t.tally;
    d["result_fields"] = t.result_fields;
    out.append(std::move(d));
  }
  return out;
}

}  // namespace

void bind_types(py::module_& m) {
  m.def("luminaire_types", &luminaire_types,
        "The solver's luminaire types, one dict per row of its table: name, keys (scene-file "
        "keys; every type also takes power_w and group), effect (its entry in results' "
        "effects), glare_source ('lambertian_area', 'photometric_body' or None), "
        "not_glare_because, aimable, placed");
  m.def("target_types", &target_types,
        "The solver's target types, one dict per row of its table: name, keys (scene-file "
        "keys), requirements (the requirement keys it takes), cells (results have cells), eyes "
        "(tallies eyes: reflected light, glare), tally ('mesh_bin' or 'grid_rows'), "
        "result_fields (the results keys it adds to every target's)");
}
