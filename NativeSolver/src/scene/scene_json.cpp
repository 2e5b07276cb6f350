// Scene file reader: JSON -> Scene. Types and keys are checked here; value ranges and
// cross-references are checked by validate(), shared with scenes built in memory.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <future>
#include <limits>
#include <sstream>
#include <system_error>
#include <type_traits>
#include <vector>

#include "io/json_reader.hpp"
#include "scene/provenance.hpp"
#include "scene/requirements_table.hpp"
#include "scene/scene_document.hpp"
#include "scene/sunlight_json.hpp"
#include "types/luminaire_types.hpp"
#include "types/target_types.hpp"
#include "lightsolver/run_options.hpp"
#include "lightsolver/scene_io.hpp"
#include "lightsolver/timings.hpp"

namespace lightsolver {
namespace {

using detail::JsonNode;
namespace fs = std::filesystem;

// Keys left out keep default_material()'s values (lightsolver/defaults.hpp).
Material read_material(const std::string& name, const JsonNode& n) {
  Material m;
  const std::string type = n.at("type").string();
  if (type == "diffuse") {
    n.require_object({"type", "reflectance"});
    m = default_material(name, Material::Type::Diffuse);
    m.reflectance = n.number_or("reflectance", m.reflectance);
  } else if (type == "mirror") {
    n.require_object({"type", "reflectance"});
    m = default_material(name, Material::Type::Mirror);
    m.reflectance = n.number_or("reflectance", m.reflectance);
  } else if (type == "glass") {
    n.require_object({"type", "ior", "transmittance", "thin"});
    m = default_material(name, Material::Type::Glass);
    m.ior = n.number_or("ior", m.ior);
    m.transmittance = n.number_or("transmittance", m.transmittance);
    m.thin = n.boolean_or("thin", m.thin);
  } else if (type == "glossy") {
    n.require_object({"type", "reflectance", "specular", "roughness"});
    m = default_material(name, Material::Type::Glossy);
    m.reflectance = n.number_or("reflectance", m.reflectance);
    m.specular = n.number_or("specular", m.specular);
    m.roughness = n.number_or("roughness", m.roughness);
  } else {
    n.at("type").fail("unknown material type \"" + type +
                      "\" (expected diffuse, mirror, glass or glossy)");
  }
  return m;
}

glm::dmat4 read_transform(const JsonNode& n) {
  if (n.array_size() != 4) n.fail("expected a 4x4 matrix (4 rows of 4 numbers)");
  glm::dmat4 m(1.0);
  for (int r = 0; r < 4; ++r) {
    const JsonNode row = n[r];
    if (row.array_size() != 4) row.fail("expected a row of 4 numbers");
    for (int c = 0; c < 4; ++c) m[c][r] = row[c].number();  // glm is column-major
  }
  if (m[0][3] != 0 || m[1][3] != 0 || m[2][3] != 0 || m[3][3] != 1) {
    n[3].fail("the last row of an affine transform must be [0, 0, 0, 1]");
  }
  return m;
}

// The common case read straight from the JSON values: three finite numbers. Anything else goes
// through JsonNode::vec3(), which names the field in its error (a path per element would cost
// more than the reading itself on a large mesh).
glm::dvec3 vertex_at(const JsonNode& v, std::size_t i) {
  const nlohmann::json& p = v.json()[i];
  if (p.is_array() && p.size() == 3 && p[0].is_number() && p[1].is_number() &&
      p[2].is_number()) {
    const glm::dvec3 out(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
    if (std::isfinite(out.x) && std::isfinite(out.y) && std::isfinite(out.z)) return out;
  }
  return v[i].vec3();
}

// A vertex index: an unsigned JSON integer below `vertices`, else JsonNode's error.
std::uint32_t index_at(const JsonNode& t, std::size_t i, int k, std::size_t vertices) {
  const nlohmann::json& e = t.json()[i][k];
  std::uint64_t index = 0;
  if (e.is_number_unsigned()) {
    index = e.get<std::uint64_t>();
  } else {
    index = t[i][k].unsigned_integer();  // a float spelling of an integer, or the error
  }
  if (index >= vertices) {
    t[i][k].fail("vertex index " + std::to_string(index) + " out of range (the mesh has " +
                 std::to_string(vertices) + " vertices)");
  }
  return static_cast<std::uint32_t>(index);
}

Mesh read_inline_geometry(const JsonNode& n) {
  Mesh mesh;
  const JsonNode v = n.at("vertices"), t = n.at("triangles");
  mesh.vertices.resize(v.array_size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) mesh.vertices[i] = vertex_at(v, i);
  mesh.triangles.resize(t.array_size());
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const nlohmann::json& tri = t.json()[i];
    if (!tri.is_array() || tri.size() != 3) {
      if (t[i].array_size() != 3) t[i].fail("expected [i, j, k] (3 vertex indices)");
    }
    for (int k = 0; k < 3; ++k) mesh.triangles[i][k] = index_at(t, i, k, mesh.vertices.size());
  }
  return mesh;
}

// Mesh files are read in single precision (Assimp's Debian build): far from the origin their
// coordinates are already rounded before the solver re-centres in double. Said, not hidden.
void warn_if_coarse(const Mesh& mesh, const JsonNode& n, const std::string& file,
                    Warnings& warnings) {
  double largest = 0.0;
  for (const auto& p : mesh.vertices) {
    largest = std::max({largest, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  }
  constexpr double kFineUpTo_m = 65536.0;  // float steps below 8 mm
  if (largest < kFineUpTo_m) return;
  const double step_mm = 1e3 * (std::nextafter(float(largest), INFINITY) - float(largest));
  std::ostringstream w;
  w << n.path() << " (\"" << file << "\"): coordinates reach " << largest
    << " m; mesh files are read in single precision, so positions there are rounded to " << step_mm
    << " mm steps. Move the model near the origin in the file and place it with "
    << "\"transform\" (applied in double), or give the vertices inline";
  warnings.push_back(w.str());
}

Mesh read_mesh(const JsonNode& n, Scene& scene, const std::string& base_dir) {
  n.require_object({"name", "material", "file", "vertices", "triangles", "transform"});
  Mesh mesh;
  if (n.has("file")) {
    if (n.has("vertices") || n.has("triangles")) n.fail("give either \"file\" or inline geometry");
    const std::string file = n.at("file").string();
    {
      const timings::Scope phase("mesh file");
      mesh = load_mesh_file((fs::path(base_dir) / file).lexically_normal().string());
    }
    warn_if_coarse(mesh, n, file, scene.warnings);
  } else {
    mesh = read_inline_geometry(n);
  }
  mesh.name = n.at("name").string();
  const std::string material = n.at("material").string();
  mesh.material = scene.find_material(material);
  if (mesh.material < 0) n.at("material").fail("unknown material \"" + material + "\"");
  if (n.has("transform")) {
    const glm::dmat4 m = read_transform(n.at("transform"));
    for (auto& p : mesh.vertices) p = glm::dvec3(m * glm::dvec4(p, 1.0));
  }
  return mesh;
}

Luminaire read_luminaire(const JsonNode& n, const std::string& base_dir) {
  Luminaire l;
  l.name = n.at("name").string();
  const std::string type = n.at("type").string();
  const detail::LuminaireType* row = detail::find_luminaire_type(type);
  if (!row) {
    n.at("type").fail("unknown luminaire type \"" + type + "\" (expected " +
                      detail::luminaire_type_names() + ")");
  }
  l.type = row->type;
  detail::read_luminaire_keys(*row, n, l, base_dir);
  return l;
}

Target read_target(const JsonNode& n, const Scene& scene, const std::string& base_dir) {
  Target t;
  t.name = n.at("name").string();
  const std::string type = n.at("type").string();
  const detail::TargetType* row = detail::find_target_type(type);
  if (!row) {
    n.at("type").fail("unknown target type \"" + type + "\" (expected " +
                      detail::target_type_names() + ")");
  }
  t.type = row->type;
  row->read(n, scene, t);
  t.requirements = detail::read_requirements(n, base_dir);
  // A task row's limits apply where the type takes them (UGR at observers, illuminances on
  // surfaces and grids); explicit others are left for validate() to refuse.
  const auto drop = [&](const char* key, unsigned bit, std::optional<double>& value) {
    const bool explicit_value = n.has("requirements") && n.at("requirements").has(key);
    if (!(row->requirements & bit) && !explicit_value) value.reset();
  };
  Requirements& r = t.requirements;
  drop("em_lux", detail::kRequireEm, r.em_lux);
  drop("u0", detail::kRequireU0, r.u0);
  drop("emin_lux", detail::kRequireEmin, r.emin_lux);
  drop("ud", detail::kRequireUd, r.ud);
  drop("ugr_max", detail::kRequireUgr, r.ugr_max);
  return t;
}

// A scene setting's value as its row's type. Ranges are validate()'s (check_scene lists every
// error), except where the value would not fit the member (max_bounces: 32 bits).
template <class T>
T read_setting(const JsonNode& n, const RunOptionInfo& option) {
  if constexpr (std::is_same_v<T, bool>) {
    return n.boolean();
  } else if constexpr (std::is_same_v<T, std::string>) {
    std::string v = n.string();
    if (!is_choice(option, v)) n.fail(choice_error(option, v));
    return v;
  } else if constexpr (std::is_floating_point_v<T>) {
    return n.number();
  } else {
    const std::uint64_t v = n.unsigned_integer();
    if (v > std::numeric_limits<T>::max()) n.fail(range_error(option, double(v)));
    return static_cast<T>(v);
  }
}

// Every key is a row of the run options table (lightsolver/run_options.hpp).
Settings read_settings(const JsonNode& n) {
  std::vector<const char*> keys;
  for_each_run_option([&](const auto& row) {
    if (row.info.scene_key) keys.push_back(row.info.scene_key);
  });
  n.require_object(keys);
  Settings s;
  for_each_run_option([&](const auto& row) {
    using Row = std::decay_t<decltype(row)>;
    if constexpr (Row::kInScene) {
      if (n.has(row.info.scene_key)) {
        s.*row.setting = read_setting<typename Row::value_type>(n.at(row.info.scene_key), row.info);
      }
    }
  });
  return s;
}

// EN 17037 sunlight exposure (sunlight_json.hpp), north from the metadata the workbench writes.
void read_scene_sunlight(const JsonNode& root, Scene& scene) {
  const bool north = root.has("metadata") && root.at("metadata").has("north_deg");
  const double north_deg = north ? root.at("metadata").at("north_deg").number() : 0.0;
  scene.sunlight_exposure =
      detail::read_sunlight_exposure(root.at("sunlight_exposure"), north_deg, scene.warnings);
}

// The scene of a parsed scene file, validated unless the caller collects validation errors.
Scene read_scene(const nlohmann::json& doc, const std::string& file, const std::string& base_dir,
                 bool validated = true) {
  const JsonNode root(doc, "", file);
  root.require_object({"format", "materials", "meshes", "luminaires", "targets", "settings",
                       "optimization", "metadata", "sunlight_exposure"});
  const std::string format = root.at("format").string();
  if (format != kSceneFormat) {
    root.at("format").fail("unsupported format \"" + format + "\" (this solver reads \"" +
                           kSceneFormat + "\")");
  }
  Scene scene;
  scene.source_file = file;
  for (const auto& item : root.at("materials").object().items()) {
    scene.materials.push_back(
        read_material(item.key(), JsonNode(item.value(), "materials." + item.key(), file)));
  }
  const JsonNode meshes = root.at("meshes");
  for (std::size_t i = 0; i < meshes.array_size(); ++i) {
    scene.meshes.push_back(read_mesh(meshes[i], scene, base_dir));
  }
  const JsonNode luminaires = root.at("luminaires");
  for (std::size_t i = 0; i < luminaires.array_size(); ++i) {
    scene.luminaires.push_back(read_luminaire(luminaires[i], base_dir));
  }
  const JsonNode targets = root.at("targets");
  for (std::size_t i = 0; i < targets.array_size(); ++i) {
    scene.targets.push_back(read_target(targets[i], scene, base_dir));
  }
  if (root.has("settings")) scene.settings = read_settings(root.at("settings"));
  if (root.has("optimization")) root.at("optimization").object();  // read by the optimizer
  if (root.has("sunlight_exposure")) read_scene_sunlight(root, scene);
  if (validated) {
    const timings::Scope phase("validate");
    validate(scene);
  }
  return scene;
}

}  // namespace

namespace detail {

SceneDocument read_scene_document(const std::string& text, const std::string& file,
                                  const std::string& base_dir) {
  SceneDocument d;
  {
    const timings::Scope phase("parse JSON");
    d.json = parse_json_text(text, file);
  }
  // The provenance hash on a thread of its own beside the reading (both only read d.json): on
  // two cores the run does not wait for it. A reading error still comes first, as when the hash
  // followed: then the future is waited for (std::async's destructor) and its result dropped.
  const auto hash = [&] { return scene_source(d.json, base_dir, file, true); };
  std::future<SceneSource> source;
  try {
    source = std::async(std::launch::async, [&] {
      const timings::Scope phase("provenance hash (a thread)", 1);
      return hash();
    });
  } catch (const std::system_error&) {  // no thread to be had: hash after reading
  }
  {
    const timings::Scope phase("read scene objects");
    d.scene = read_scene(d.json, file, base_dir);
  }
  d.scene.source = source.valid() ? source.get() : hash();
  return d;
}

std::string read_scene_text(const std::string& path) {
  const timings::Scope phase("read file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open the scene file");
  std::stringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path, "", "cannot read the scene file");
  return text.str();
}

SceneDocument load_scene_document(const std::string& path) {
  return read_scene_document(read_scene_text(path), path, fs::path(path).parent_path().string());
}

Scene read_unvalidated_scene(const std::string& text, const std::string& file,
                             const std::string& base_dir) {
  return read_scene(parse_json_text(text, file), file, base_dir, false);
}

}  // namespace detail

Scene scene_from_json(const std::string& text, const std::string& file,
                      const std::string& base_dir) {
  return detail::read_scene_document(text, file, base_dir).scene;
}

Scene load_scene(const std::string& path) { return detail::load_scene_document(path).scene; }

Material material_from_json(const std::string& name, const nlohmann::json& entry,
                            const std::string& where) {
  return read_material(name, JsonNode(entry, "", where));
}

Luminaire luminaire_from_json(const nlohmann::json& entry, const std::string& where,
                              const std::string& base_dir) {
  return read_luminaire(JsonNode(entry, "", where), base_dir);
}

Target target_from_json(const nlohmann::json& entry, const std::string& where, const Scene& scene) {
  return read_target(JsonNode(entry, "", where), scene, "");
}

}  // namespace lightsolver
