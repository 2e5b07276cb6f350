// Scene queries and validation shared by every way of building a scene (file, Python, tests).
#include "lightsolver/scene.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <set>
#include <sstream>
#include <string>
#include <tuple>
#include <unordered_map>

#include "scene/daylight_factor_check.hpp"
#include "scene/validate_again.hpp"
#include "types/luminaire_types.hpp"
#include "types/target_types.hpp"
#include "lightsolver/photometry.hpp"
#include "lightsolver/run_options.hpp"
#include "lightsolver/statistics.hpp"

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

// Numbers in messages: 6 significant digits, so 1e-30 does not print as 0.000000.
std::string show(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

void check_photon_count(std::uint64_t photons, std::uint32_t max_bounces, const std::string& file,
                        const std::string& where) {
  if (photons == 0) throw InputError(file, where, "must be at least 1");
  const std::uint64_t most = max_photons(max_bounces);
  if (photons > most) {
    throw InputError(file, where,
                     "at most " + std::to_string(most) + " photons in one run with max_bounces = " +
                         std::to_string(max_bounces) + " (got " + std::to_string(photons) +
                         "): 10^13 at most, and few enough that the 64-bit sums of squared "
                         "per-path counts cannot overflow (docs/statistics.md)");
  }
}

namespace {

class Validator {
 public:
  // With `errors`, every entry is checked and each one's first error collected; without, the
  // first error is thrown (the order of the checks is the order of the messages).
  explicit Validator(Scene& s, std::vector<InputError>* errors = nullptr)
      : s_(s), errors_(errors) {}

  // The meshes' vertices and triangles are known good (the scene was validated and its meshes
  // have not changed since): only their names and materials are checked again.
  void skip_mesh_geometry() { mesh_geometry_ = false; }

  void luminaires() {
    for (std::size_t i = 0; i < s_.luminaires.size(); ++i) luminaire(i);
  }

  void run() {
    for (std::size_t i = 0; i < s_.materials.size(); ++i) entry([&] { material(i); });
    std::unordered_map<std::string, std::size_t> mesh_names;
    for (std::size_t i = 0; i < s_.meshes.size(); ++i) {
      // A target on a mesh with an error would only repeat it: it is skipped.
      if (!entry([&] { named_mesh(i, mesh_names); })) bad_meshes_.insert(static_cast<int>(i));
    }
    entry([&] {
      if (s_.luminaires.empty()) fail("luminaires", "the scene has no luminaire");
    });
    for (std::size_t i = 0; i < s_.luminaires.size(); ++i) entry([&] { luminaire(i); });
    entry([&] {
      if (s_.targets.empty()) fail("targets", "the scene has no target to report");
    });
    for (std::size_t i = 0; i < s_.targets.size(); ++i) entry([&] { target(i); });
    entry([&] {
      if (grid_cells_ > limits::kMaxGridCells) {
        fail("targets",
             "the grids have " + std::to_string(grid_cells_) + " cells together, more than 10^7");
      }
    });
    entry([&] { settings(); });
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
    if (!(v >= 0.0 && v <= 1.0)) fail(where, "must lie in 0..1 (got " + show(v) + ")");
  }
  // Points and edges: finite, and within 10^9 m of the origin (beyond any geographic use; the
  // solver re-centres in double, but the float tracer needs a bounded extent).
  static bool in_range(const glm::dvec3& v) {  // what coordinates() accepts
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) &&
           std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}) <= limits::kMaxCoordinate_m;
  }
  void coordinates(const std::string& where, const glm::dvec3& v) const {
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
      fail(where, "coordinates must be finite numbers");
    }
    const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    if (largest > limits::kMaxCoordinate_m) {
      fail(where, "coordinate " + show(largest) + " m is beyond 10^9 m, beyond any physical use");
    }
  }
  // Directions: any finite non-zero length (they are normalised).
  void direction(const std::string& where, const glm::dvec3& v) const {
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
      fail(where, "coordinates must be finite numbers");
    }
    const double length = glm::length(v);
    if (!(length > 0.0)) fail(where, "must not be the zero vector");
    if (!std::isfinite(length)) fail(where, "too long to normalise (give a unit vector)");
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
    if (!mesh_geometry_) return;
    for (std::size_t v = 0; v < m.vertices.size(); ++v) {
      // The field path only for an error: building it for each of 10^5 vertices was most of
      // the check's time.
      if (!in_range(m.vertices[v])) {
        coordinates(at("meshes", i, "vertices") + "[" + std::to_string(v) + "]", m.vertices[v]);
      }
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

  // The shared checks a luminaire type's own check (luminaire_types.cpp) calls, with field
  // paths under luminaires[i].
  class LuminaireFields final : public detail::LuminaireChecks {
   public:
    LuminaireFields(const Validator& v, std::size_t i) : v_(v), i_(i) {}
    [[noreturn]] void fail(const char* key, const std::string& what) const override {
      v_.fail(at("luminaires", i_, key), what);
    }
    void coordinates(const char* key, const glm::dvec3& p) const override {
      v_.coordinates(at("luminaires", i_, key), p);
    }
    void direction(const char* key, const glm::dvec3& d) const override {
      v_.direction(at("luminaires", i_, key), d);
    }
    void parallelogram(const Luminaire& l, const char* what) const override {
      v_.parallelogram("luminaires", i_, l.corner, l.edge1, l.edge2, what);
    }
    void flux(const Luminaire& l, const char* note) const override {
      if (!(l.flux_lm >= 0.0 && std::isfinite(l.flux_lm))) {
        fail("flux_lm", "must be a finite value >= 0 (got " + show(l.flux_lm) + note + ")");
      }
      // The photometric flux is the file's integrated candela times flux_lm / the file's lamp
      // lumens, times its TILT factor: the product is what is bounded.
      const double emitted = l.flux_lm * photometric_tilt_factor(l);
      if (!(emitted <= limits::kMaxFlux_lm)) {
        fail("flux_lm", "emits " + show(emitted) +
                            " lm, more than 10^12 lm: beyond any physical light source");
      }
    }

   private:
    const Validator& v_;
    std::size_t i_;
  };

  void luminaire(std::size_t i) {
    Luminaire& l = s_.luminaires[i];
    detail::luminaire_type(l.type).check(LuminaireFields(*this, i), l);
    if (l.power_w && !(*l.power_w >= 0.0 && *l.power_w <= limits::kMaxPower_W)) {
      fail(at("luminaires", i, "power_w"),
           "must be a finite value in 0..10^9 W (got " + show(*l.power_w) + ")");
    }
  }

  // corner + s*edge1 + t*edge2 with a non-zero area (area luminaires, sun openings, grids).
  void parallelogram(const char* list, std::size_t i, const glm::dvec3& corner,
                     const glm::dvec3& e1, const glm::dvec3& e2, const char* what) const {
    coordinates(at(list, i, "corner"), corner);
    coordinates(at(list, i, "edge1"), e1);
    coordinates(at(list, i, "edge2"), e2);
    if (glm::length(e1) == 0.0) fail(at(list, i, "edge1"), "must not be the zero vector");
    if (glm::length(e2) == 0.0) fail(at(list, i, "edge2"), "must not be the zero vector");
    if (glm::length(glm::cross(e1, e2)) <= 1e-9 * glm::length(e1) * glm::length(e2)) {
      fail(at(list, i, "edge2"), std::string("edge1 and edge2 are parallel: ") + what);
    }
  }

  // Runs one entry's checks; false when it failed (only when collecting, else it throws).
  template <class Check>
  bool entry(Check&& check) {
    if (!errors_) {
      check();
      return true;
    }
    try {
      check();
      return true;
    } catch (const InputError& e) {
      errors_->push_back(e);
      return false;
    }
  }

  void named_mesh(std::size_t i, std::unordered_map<std::string, std::size_t>& names) {
    const auto [first, inserted] = names.emplace(s_.meshes[i].name, i);
    if (!inserted) {
      fail(at("meshes", i, "name"), "duplicate mesh name \"" + s_.meshes[i].name +
                                        "\" (also meshes[" + std::to_string(first->second) +
                                        "]): mesh names must be unique");
    }
    mesh(i);
  }

  // Requirements: illuminances > 0 and at most 10^7 lx, ratios in (0, 1]; a surface target
  // has no cells, so only em_lux applies to it.
  void requirements(std::size_t i, const Target& t) const {
    const Requirements& r = t.requirements;
    const std::string where = at("targets", i, "requirements");
    for (const auto& [key, v] :
         {std::pair{"em_lux", r.em_lux}, std::pair{"emin_lux", r.emin_lux}}) {
      if (v && !(*v > 0.0 && *v <= limits::kMaxRequiredIlluminance_lx)) {
        fail(where + "." + key, "must be > 0 and at most 10^7 lx (got " + show(*v) + ")");
      }
    }
    for (const auto& [key, v] : {std::pair{"u0", r.u0}, std::pair{"ud", r.ud}}) {
      if (v && !(*v > 0.0 && *v <= 1.0)) {
        fail(where + "." + key, "must lie in (0, 1] (got " + show(*v) + ")");
      }
    }
    if (r.ugr_max && !(*r.ugr_max > 0.0 && *r.ugr_max <= limits::kMaxUgr)) {
      fail(where + ".ugr_max", "must be > 0 and at most 40 (got " + show(*r.ugr_max) + ")");
    }
    const detail::TargetType& row = detail::target_type(t.type);
    if (r.ugr_max && !(row.requirements & detail::kRequireUgr)) {
      fail(where + ".ugr_max",
           "UGR is judged at an observer: give it on an \"observer\" or \"observer_grid\" "
           "target");
    }
    for (const auto& [key, bit, v] : {std::tuple{"em_lux", detail::kRequireEm, r.em_lux},
                                      std::tuple{"u0", detail::kRequireU0, r.u0},
                                      std::tuple{"emin_lux", detail::kRequireEmin, r.emin_lux},
                                      std::tuple{"ud", detail::kRequireUd, r.ud}}) {
      if (v && !(row.requirements & bit)) fail(where + "." + key, row.other_requirements);
    }
  }

  void target(std::size_t i) {
    Target& t = s_.targets[i];
    requirements(i, t);
    detail::check_daylight_factor(s_, i);
    detail::target_type(t.type).check(TargetFields(*this, i), t);
  }

  // The shared checks a target type's own check (target_types.cpp) calls, with field paths
  // under targets[i].
  class TargetFields final : public detail::TargetChecks {
   public:
    TargetFields(Validator& v, std::size_t i) : v_(v), i_(i) {}
    [[noreturn]] void fail(const std::string& key, const std::string& what) const override {
      v_.fail(where(key), what);
    }
    void coordinates(const std::string& key, const glm::dvec3& p) const override {
      v_.coordinates(where(key), p);
    }
    void direction(const std::string& key, const glm::dvec3& d) const override {
      v_.direction(where(key), d);
    }
    void parallelogram(const Target& t, const char* what) const override {
      v_.parallelogram("targets", i_, t.corner, t.edge1, t.edge2, what);
    }
    const Mesh* mesh(int index) const override {
      if (v_.bad_meshes_.count(index)) return nullptr;
      if (index < 0 || index >= static_cast<int>(v_.s_.meshes.size())) fail("mesh", "unknown mesh");
      return &v_.s_.meshes[index];
    }
    void add_grid_cells(std::uint64_t cells) const override { v_.grid_cells_ += cells; }

   private:
    std::string where(const std::string& key) const {
      return "targets[" + std::to_string(i_) + "]." + key;
    }
    Validator& v_;
    std::size_t i_;
  };

  void settings() {
    // Each setting's own range (the run options table), then what depends on two of them.
    for (const auto& [where, error] : settings_errors(s_.settings)) fail(where, error);
    check_photon_count(s_.settings.photons, s_.settings.max_bounces, s_.source_file,
                       "settings.photons");
    const double c = s_.settings.confidence;
    if (c < 0.5) {
      s_.warnings.push_back("settings.confidence: " + show(c) +
                            " gives intervals narrower than one standard deviation; "
                            "0.95 is usual");
    }
  }

  Scene& s_;
  std::vector<InputError>* errors_;
  std::set<int> bad_meshes_;
  std::uint64_t grid_cells_ = 0;
  bool mesh_geometry_ = true;
};

}  // namespace

void validate(Scene& scene) { Validator(scene).run(); }

void validate_luminaires(Scene& scene) { Validator(scene).luminaires(); }

namespace detail {

void validate_again(Scene& scene) {
  Validator v(scene);
  v.skip_mesh_geometry();
  v.run();
}

}  // namespace detail

std::vector<InputError> validation_errors(Scene& scene) {
  std::vector<InputError> errors;
  Validator(scene, &errors).run();
  return errors;
}

}  // namespace lightsolver
