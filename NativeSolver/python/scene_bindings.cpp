// lightsolver.Scene: every add_* goes through the scene file's reader for its kind of entry
// (material_from_json, luminaire_from_json, target_from_json), so a script and a scene file are
// checked by the same code and a change of the scene clears its provenance hash.
#include "scene_bindings.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lightsolver/scene_io.hpp"
#include "run_option_keywords.hpp"
#include "simulation_bindings.hpp"

namespace py = pybind11;
using namespace lightsolver;

namespace {

// {"name": name, "type": type, **fields}: one entry of a scene file's list.
nlohmann::json entry_json(const std::string& name, const std::string& type,
                          const py::kwargs& fields, const std::string& where) {
  nlohmann::json entry = {{"name", name}, {"type", type}};
  for (const auto& [key, value] : fields) {
    entry[py::str(key).cast<std::string>()] = to_json(value, where);
  }
  return entry;
}

Mesh mesh_from_numpy(const std::string& name, int material,
                     py::array_t<double, py::array::c_style | py::array::forcecast> vertices,
                     py::array_t<std::int64_t, py::array::c_style | py::array::forcecast> tris) {
  if (vertices.ndim() != 2 || vertices.shape(1) != 3) {
    throw py::value_error("mesh \"" + name + "\": vertices must have shape (n, 3)");
  }
  if (tris.ndim() != 2 || tris.shape(1) != 3) {
    throw py::value_error("mesh \"" + name + "\": triangles must have shape (m, 3)");
  }
  Mesh m;
  m.name = name;
  m.material = material;
  auto v = vertices.unchecked<2>();
  for (py::ssize_t i = 0; i < v.shape(0); ++i) m.vertices.emplace_back(v(i, 0), v(i, 1), v(i, 2));
  auto t = tris.unchecked<2>();
  for (py::ssize_t i = 0; i < t.shape(0); ++i) {
    for (int k = 0; k < 3; ++k) {
      if (t(i, k) < 0 || t(i, k) >= v.shape(0)) {
        throw py::value_error("mesh \"" + name + "\": triangles[" + std::to_string(i) +
                              "] has a vertex index out of range");
      }
    }
    m.triangles.emplace_back(t(i, 0), t(i, 1), t(i, 2));
  }
  return m;
}

}  // namespace

void bind_scene(py::module_& m) {
  py::class_<Scene> scene_class(m, "Scene", "A scene in memory (see docs/scene-format.md)");
  scene_class.def(py::init<>())
      .def(
          "add_material",
          [](Scene& s, const std::string& name, const std::string& type, py::kwargs fields) {
            const std::string where = "add_material(\"" + name + "\")";
            if (s.find_material(name) >= 0) throw py::value_error("duplicate material " + name);
            nlohmann::json entry = {{"type", type}};
            for (const auto& [key, value] : fields) {
              if (!value.is_none()) entry[py::str(key).cast<std::string>()] = to_json(value, where);
            }
            s.materials.push_back(material_from_json(name, entry, where));
            s.source.reset();  // no longer the file's content (provenance)
          },
          py::arg("name"), py::arg("type") = "diffuse",
          "A material of any type: the keyword arguments are the type's keys of a scene file's "
          "material (docs/scene-format.md), e.g. add_material('glass', 'glass', ior=1.5); read "
          "by the same code as scene files, so a key the type does not have is an InputError "
          "naming it. Keys left out (or None) take lightsolver.material_defaults().")
      .def(
          "add_mesh",
          [](Scene& s, const std::string& name, py::array vertices, py::array triangles,
             const std::string& material) {
            const int mat = s.find_material(material);
            if (mat < 0) throw py::value_error("unknown material \"" + material + "\"");
            if (s.find_mesh(name) >= 0) throw py::value_error("duplicate mesh " + name);
            s.meshes.push_back(mesh_from_numpy(name, mat, vertices, triangles));
            s.source.reset();
          },
          py::arg("name"), py::arg("vertices"), py::arg("triangles"), py::arg("material"))
      .def(
          "add_light",
          [](Scene& s, const std::string& name, const std::string& type, py::kwargs fields) {
            const std::string where = "add_light(\"" + name + "\")";
            s.luminaires.push_back(
                luminaire_from_json(entry_json(name, type, fields, where), where, ""));
            s.source.reset();
          },
          py::arg("name"), py::arg("type"),
          "A luminaire of any type: the keyword arguments are the type's keys of a scene file's "
          "luminaire entry (docs/scene-format.md), e.g. add_light('lamp', 'point', "
          "position=[0, 0, 3], flux_lm=1000); read by the same code as scene files, so a "
          "missing or unknown key is an InputError naming it. A photometric file is relative "
          "to the working folder.")
      .def(
          "add_target",
          [](Scene& s, const std::string& name, const std::string& type, py::kwargs fields) {
            const std::string where = "add_target(\"" + name + "\")";
            s.targets.push_back(target_from_json(entry_json(name, type, fields, where), where, s));
            s.source.reset();
          },
          py::arg("name"), py::arg("type"),
          "A target of any type: the keyword arguments are the type's keys of a scene file's "
          "target entry, e.g. add_target('walls', 'surface', mesh='walls') or "
          "add_target('floor', 'grid', corner=[0, 0, 0], edge1=[4, 0, 0], edge2=[0, 3, 0], "
          "cells=[8, 6])")
      .def(
          "validate", [](Scene& s) { validate(s); }, "Check values; drop degenerate triangles")
      .def_property_readonly("warnings", [](const Scene& s) { return s.warnings; })
      .def_property_readonly("mesh_names",
                             [](const Scene& s) {
                               std::vector<std::string> n;
                               for (const auto& m : s.meshes) n.push_back(m.name);
                               return n;
                             })
      .def_property_readonly("triangle_count",
                             [](const Scene& s) {
                               std::size_t n = 0;
                               for (const auto& m : s.meshes) n += m.triangles.size();
                               return n;
                             })
      .def_property_readonly("total_flux_lm", &Scene::total_flux_lm);
  bind_scene_settings(scene_class);  // photons, seed, confidence, ... (the run options table)
}
