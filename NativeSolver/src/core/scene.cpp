// Scene queries and validation shared by every way of building a scene (file, Python, tests).
#include <glm/geometric.hpp>

#include <cmath>
#include <string>

#include "lightsolver/scene.hpp"

namespace lightsolver {

int Scene::find_material(const std::string& name) const {
  for (std::size_t i = 0; i < materials.size(); ++i) {
    if (materials[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

int Scene::find_mesh(const std::string& name) const {
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    if (meshes[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

double Scene::total_flux_lm() const {
  double sum = 0.0;
  for (const auto& l : luminaires) sum += l.flux_lm;
  return sum;
}

double directional_flux_lm(const Luminaire& l) {
  const glm::dvec3 area = glm::cross(l.edge1, l.edge2);
  return l.illuminance_lx * std::abs(glm::dot(area, glm::normalize(l.direction)));
}

namespace {

class Validator {
 public:
  explicit Validator(Scene& s) : s_(s) {}

  void luminaires() {
    for (std::size_t i = 0; i < s_.luminaires.size(); ++i) luminaire(i);
  }

  void run() {
    for (std::size_t i = 0; i < s_.materials.size(); ++i) material(i);
    for (std::size_t i = 0; i < s_.meshes.size(); ++i) mesh(i);
    if (s_.luminaires.empty()) fail("luminaires", "the scene has no luminaire");
    for (std::size_t i = 0; i < s_.luminaires.size(); ++i) luminaire(i);
    if (s_.targets.empty()) fail("targets", "the scene has no target to report");
    for (std::size_t i = 0; i < s_.targets.size(); ++i) target(i);
    settings();
  }

 private:
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw InputError(s_.source_file, where, what);
  }
  static std::string at(const char* list, std::size_t i, const char* key = nullptr) {
    std::string s = std::string(list) + "[" + std::to_string(i) + "]";
    return key ? s + "." + key : s;
  }
  void unit_interval(const std::string& where, double v) const {
    if (!(v >= 0.0 && v <= 1.0)) fail(where, "must lie in 0..1 (got " + std::to_string(v) + ")");
  }
  void finite(const std::string& where, const glm::dvec3& v) const {
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
      fail(where, "coordinates must be finite numbers");
    }
  }
  void nonzero(const std::string& where, const glm::dvec3& v) const {
    finite(where, v);
    if (glm::length(v) == 0.0) fail(where, "must not be the zero vector");
  }

  void material(std::size_t i) {
    const Material& m = s_.materials[i];
    const std::string w = "materials." + m.name;
    unit_interval(w + ".reflectance", m.reflectance);
    if (m.type == Material::Type::Glass) {
      unit_interval(w + ".transmittance", m.transmittance);
      if (!(m.ior >= 1.0 && m.ior <= 10.0)) fail(w + ".ior", "must lie in 1..10");
    }
    if (m.type == Material::Type::Glossy) {
      unit_interval(w + ".specular", m.specular);
      unit_interval(w + ".roughness", m.roughness);
      if (m.reflectance + m.specular > 1.0 + 1e-12) {
        fail(w, "reflectance + specular must not exceed 1 (energy conservation)");
      }
    }
  }

  void mesh(std::size_t i) {
    Mesh& m = s_.meshes[i];
    if (m.material < 0 || m.material >= static_cast<int>(s_.materials.size())) {
      fail(at("meshes", i, "material"), "unknown material");
    }
    for (std::size_t v = 0; v < m.vertices.size(); ++v) {
      finite(at("meshes", i, "vertices") + "[" + std::to_string(v) + "]", m.vertices[v]);
    }
    std::size_t kept = 0;
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      const auto& tri = m.triangles[t];
      for (int k = 0; k < 3; ++k) {
        if (tri[k] >= m.vertices.size()) {
          fail(at("meshes", i, "triangles") + "[" + std::to_string(t) + "]",
               "vertex index out of range");
        }
      }
      if (!degenerate(m, tri)) m.triangles[kept++] = tri;
    }
    if (kept < m.triangles.size()) {
      s_.warnings.push_back(at("meshes", i) + " (\"" + m.name + "\"): dropped " +
                            std::to_string(m.triangles.size() - kept) +
                            " degenerate (zero-area) triangle(s)");
      m.triangles.resize(kept);
    }
  }

  // A triangle whose edges are (nearly) parallel has no usable normal in float: sin(angle)
  // below 1e-7 is at float resolution.
  static bool degenerate(const Mesh& m, const glm::u32vec3& t) {
    const glm::dvec3 e1 = m.vertices[t[1]] - m.vertices[t[0]];
    const glm::dvec3 e2 = m.vertices[t[2]] - m.vertices[t[0]];
    const double c = glm::length(glm::cross(e1, e2));
    return !(c > 1e-7 * glm::length(e1) * glm::length(e2));
  }

  void luminaire(std::size_t i) {
    Luminaire& l = s_.luminaires[i];
    using T = Luminaire::Type;
    if (l.type != T::Directional && !(l.flux_lm >= 0.0 && std::isfinite(l.flux_lm))) {
      fail(at("luminaires", i, "flux_lm"),
           "must be a finite value >= 0 (got " + std::to_string(l.flux_lm) + ")");
    }
    if (l.type == T::Point || l.type == T::Spot || l.type == T::Photometric) {
      finite(at("luminaires", i, "position"), l.position);
    }
    if (l.type == T::Spot || l.type == T::Directional) {
      nonzero(at("luminaires", i, "direction"), l.direction);
      l.direction = glm::normalize(l.direction);
    }
    if (l.type == T::Spot) spot_angles(i, l);
    if (l.type == T::Photometric) {
      nonzero(at("luminaires", i, "aim"), l.aim);
      l.aim = glm::normalize(l.aim);
      if (!l.sampler) fail(at("luminaires", i, "file"), "no photometric data loaded");
      if (!std::isfinite(l.rotation_deg)) fail(at("luminaires", i, "rotation_deg"), "not finite");
    }
    if (l.type == T::Area || l.type == T::Directional) {
      parallelogram("luminaires", i, l.corner, l.edge1, l.edge2, "the area is zero");
    }
    if (l.type == T::Directional) {
      if (!(l.illuminance_lx >= 0.0)) fail(at("luminaires", i, "illuminance_lx"), "must be >= 0");
      if (std::abs(glm::dot(glm::normalize(glm::cross(l.edge1, l.edge2)), l.direction)) < 1e-9) {
        fail(at("luminaires", i, "direction"), "the beam runs parallel to its parallelogram");
      }
      l.flux_lm = directional_flux_lm(l);
    }
  }

  void spot_angles(std::size_t i, const Luminaire& l) {
    if (!(l.beam_angle_deg > 0.0 && l.beam_angle_deg < l.field_angle_deg)) {
      fail(at("luminaires", i, "beam_angle_deg"), "need 0 < beam_angle_deg < field_angle_deg");
    }
    if (!(l.field_angle_deg <= 360.0)) {
      fail(at("luminaires", i, "field_angle_deg"), "must be <= 360");
    }
  }

  // corner + s*edge1 + t*edge2 with a non-zero area (area luminaires, sun openings, grids).
  void parallelogram(const char* list, std::size_t i, const glm::dvec3& corner,
                     const glm::dvec3& e1, const glm::dvec3& e2, const char* what) {
    finite(at(list, i, "corner"), corner);
    nonzero(at(list, i, "edge1"), e1);
    nonzero(at(list, i, "edge2"), e2);
    if (glm::length(glm::cross(e1, e2)) <= 1e-9 * glm::length(e1) * glm::length(e2)) {
      fail(at(list, i, "edge2"), std::string("edge1 and edge2 are parallel: ") + what);
    }
  }

  void target(std::size_t i) {
    const Target& t = s_.targets[i];
    if (t.type == Target::Type::Surface) {
      if (t.mesh < 0 || t.mesh >= static_cast<int>(s_.meshes.size())) {
        fail(at("targets", i, "mesh"), "unknown mesh");
      }
      if (s_.meshes[t.mesh].triangles.empty()) {
        fail(at("targets", i, "mesh"),
             "mesh \"" + s_.meshes[t.mesh].name + "\" has zero area (no usable triangle)");
      }
      return;
    }
    parallelogram("targets", i, t.corner, t.edge1, t.edge2, "the grid has zero area");
    if (t.nu == 0 || t.nv == 0) fail(at("targets", i, "cells"), "need at least 1x1 cells");
  }

  void settings() {
    if (s_.settings.photons == 0) fail("settings.photons", "must be at least 1");
    const double c = s_.settings.confidence;
    if (!(c > 0.0 && c < 1.0)) fail("settings.confidence", "must lie strictly between 0 and 1");
  }

  Scene& s_;
};

}  // namespace

void validate(Scene& scene) { Validator(scene).run(); }

void validate_luminaires(Scene& scene) { Validator(scene).luminaires(); }

}  // namespace lightsolver
