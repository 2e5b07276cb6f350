// The `optimization` block of a scene file (docs/optimization.md §10): intention, variables and
// search settings, read from the raw JSON so the scene loader stays unaware of the optimizer.
// Every error names the file and the field, like the scene loader's.
#include "lightsolver/optimizer/scene_problem.hpp"

#include <algorithm>
#include <glm/geometric.hpp>
#include <set>
#include <stdexcept>

#include "io/json_reader.hpp"
#include "lightsolver/scene_io.hpp"
#include "optimizer/placement_region.hpp"
#include "scene/provenance.hpp"
#include "scene/scene_document.hpp"
#include "types/luminaire_types.hpp"
#include "types/target_types.hpp"

namespace lightsolver::optimizer {
namespace {

using detail::JsonNode;

// Index of a named luminaire, or a failure at `n` (the field that names it).
std::size_t luminaire_index(const Scene& s, const JsonNode& n) {
  const std::string name = n.string();
  for (std::size_t i = 0; i < s.luminaires.size(); ++i) {
    if (s.luminaires[i].name == name) return i;
  }
  n.fail("unknown luminaire \"" + name + "\"");
}

const Target* find_target(const Scene& s, const std::string& name) {
  for (const Target& t : s.targets) {
    if (t.name == name) return &t;
  }
  return nullptr;
}

std::uint32_t positive_count(const JsonNode& n) {
  const std::uint64_t c = n.unsigned_integer();
  if (c == 0 || c > (1u << 20)) n.fail("must be between 1 and 1048576 cells");
  return static_cast<std::uint32_t>(c);
}

// Reads corner / edge1 / edge2 / cells: [k, m] and adds the two variables `<name>.u`, `.v`.
// The rectangle, its cells and its optional `within` polygon.
void read_rectangle(const JsonNode& n, const std::string& name, SceneVariable& v, Domain& d) {
  v.corner = n.at("corner").vec3();
  v.edge1 = n.at("edge1").vec3();
  v.edge2 = n.at("edge2").vec3();
  if (glm::length(glm::cross(v.edge1, v.edge2)) <= 1e-12 * glm::dot(v.edge1, v.edge1) ||
      glm::length(v.edge1) == 0.0) {
    n.at("edge2").fail("edge1 and edge2 must be non-zero and not parallel");
  }
  const JsonNode cells = n.at("cells");
  if (cells.array_size() != 2) cells.fail("expected [k, m]: cells along edge1 and edge2");
  const std::uint32_t k = positive_count(cells[0]), m = positive_count(cells[1]);
  v.first = d.dimensions();
  try {
    d.add_range(name + ".u", 0.0, 1.0, k);
    d.add_range(name + ".v", 0.0, 1.0, m);
  } catch (const std::exception& e) {
    cells.fail(e.what());
  }
  if (n.has("within")) v.region = regions::read_region(n.at("within"), v, d);
}

// `luminaire` (one name) or `luminaires` (a non-empty list).
std::vector<std::size_t> read_luminaires(const JsonNode& n, const Scene& s) {
  std::vector<std::size_t> out;
  if (n.has("luminaire") == n.has("luminaires")) {
    n.fail("give exactly one of \"luminaire\" (a name) or \"luminaires\" (a list of names)");
  }
  if (n.has("luminaire")) return {luminaire_index(s, n.at("luminaire"))};
  const JsonNode list = n.at("luminaires");
  if (list.array_size() == 0) list.fail("must name at least one luminaire");
  for (std::size_t i = 0; i < list.array_size(); ++i) out.push_back(luminaire_index(s, list[i]));
  return out;
}

std::string joined_names(const Scene& s, const std::vector<std::size_t>& lums) {
  std::string name;
  for (std::size_t i : lums) name += (name.empty() ? "" : "+") + s.luminaires[i].name;
  return name;
}

// Keeps one variable of a kind per luminaire / mesh: two would fight over the same field.
class Claims {
 public:
  void claim(const JsonNode& n, const std::string& what) {
    if (!taken_.insert(what).second) n.fail(what + " is already set by another variable");
  }

 private:
  std::set<std::string> taken_;
};

SceneVariable read_position(const JsonNode& n, SceneProblem& p, Claims& claims) {
  n.require_object(
      {"type", "name", "luminaire", "luminaires", "corner", "edge1", "edge2", "cells", "within"});
  SceneVariable v;
  v.type = SceneVariable::Type::kPosition;
  v.luminaires = read_luminaires(n, p.scene);
  const glm::dvec3 first = detail::anchor_of(p.scene.luminaires[v.luminaires[0]]);
  for (std::size_t i : v.luminaires) {
    claims.claim(n, "the position of luminaire \"" + p.scene.luminaires[i].name + "\"");
    v.offsets.push_back(detail::anchor_of(p.scene.luminaires[i]) - first);
  }
  const std::string name =
      n.has("name") ? n.at("name").string() : joined_names(p.scene, v.luminaires);
  read_rectangle(n, name, v, p.domain);
  return v;
}

SceneVariable read_translation(const JsonNode& n, SceneProblem& p, Claims& claims) {
  n.require_object(
      {"type", "name", "mesh", "anchor", "corner", "edge1", "edge2", "cells", "within"});
  SceneVariable v;
  v.type = SceneVariable::Type::kTranslation;
  const std::string mesh = n.at("mesh").string();
  const int index = p.scene.find_mesh(mesh);
  if (index < 0) n.at("mesh").fail("unknown mesh \"" + mesh + "\"");
  v.mesh = static_cast<std::size_t>(index);
  claims.claim(n.at("mesh"), "the placement of mesh \"" + mesh + "\"");
  if (n.has("anchor")) v.anchor = n.at("anchor").vec3();
  read_rectangle(n, n.has("name") ? n.at("name").string() : mesh, v, p.domain);
  return v;
}

// Turning an object (a desk, a partition) about a vertical axis through its centre is what a
// designer means by "rotate it"; pivot and axis can say otherwise.
SceneVariable read_rotation(const JsonNode& n, SceneProblem& p, Claims& claims,
                            std::vector<bool>& pivot_given) {
  n.require_object({"type", "name", "mesh", "pivot", "axis", "min_deg", "max_deg", "cells"});
  SceneVariable v;
  v.type = SceneVariable::Type::kRotation;
  const std::string mesh = n.at("mesh").string();
  const int index = p.scene.find_mesh(mesh);
  if (index < 0) n.at("mesh").fail("unknown mesh \"" + mesh + "\"");
  v.mesh = static_cast<std::size_t>(index);
  claims.claim(n.at("mesh"), "the rotation of mesh \"" + mesh + "\"");
  pivot_given.push_back(n.has("pivot"));
  if (n.has("pivot")) v.pivot = n.at("pivot").vec3();
  if (n.has("axis")) {
    const glm::dvec3 axis = n.at("axis").vec3();
    if (!(glm::length(axis) > 1e-12)) n.at("axis").fail("must not be the zero vector");
    v.axis = glm::normalize(axis);
  }
  const double lo = n.at("min_deg").number(), hi = n.at("max_deg").number();
  if (!(lo < hi)) n.at("max_deg").fail("must be greater than min_deg");
  if (hi - lo > 360.0) n.at("max_deg").fail("a rotation may span at most one turn (360 degrees)");
  const std::uint32_t cells = positive_count(n.at("cells"));
  v.first = p.domain.dimensions();
  try {
    p.domain.add_angle(n.has("name") ? n.at("name").string() : mesh + ".rotation_deg", lo, hi,
                       cells);
  } catch (const std::exception& e) {
    n.at("cells").fail(e.what());
  }
  return v;
}

// Default pivots, once every variable is known: the anchor of the same mesh's translation (so
// the anchor still lands on its rectangle after turning), else the bounding-box centre.
void resolve_pivots(SceneProblem& p, const std::vector<bool>& pivot_given) {
  std::size_t k = 0;
  for (SceneVariable& v : p.variables) {
    if (v.type != SceneVariable::Type::kRotation || pivot_given[k++]) continue;
    const Mesh& m = p.scene.meshes[v.mesh];
    glm::dvec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::dvec3& q : m.vertices) {
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
    }
    v.pivot = 0.5 * (lo + hi);
    for (const SceneVariable& t : p.variables) {
      if (t.type == SceneVariable::Type::kTranslation && t.mesh == v.mesh) v.pivot = t.anchor;
    }
  }
}

SceneVariable read_aim(const JsonNode& n, SceneProblem& p, Claims& claims) {
  n.require_object({"type", "name", "luminaire", "angle", "min_deg", "max_deg", "cells"});
  SceneVariable v;
  v.type = SceneVariable::Type::kAim;
  v.luminaires = {luminaire_index(p.scene, n.at("luminaire"))};
  const Luminaire& l = p.scene.luminaires[v.luminaires[0]];
  Luminaire scratch = l;
  if (detail::luminaire_type(l.type).aim(scratch) == nullptr) {
    n.at("luminaire")
        .fail("only " + detail::aimable_luminaire_type_names() + " luminaires can be aimed");
  }
  const std::string angle = n.at("angle").string();
  if (angle != "tilt" && angle != "pan") n.at("angle").fail("expected \"tilt\" or \"pan\"");
  v.angle = angle == "tilt" ? SceneVariable::Angle::kTilt : SceneVariable::Angle::kPan;
  claims.claim(n.at("angle"), "the " + angle + " of luminaire \"" + l.name + "\"");
  const double lo = n.at("min_deg").number(), hi = n.at("max_deg").number();
  if (!(lo < hi)) n.at("max_deg").fail("must be greater than min_deg");
  if (v.angle == SceneVariable::Angle::kTilt && (lo < 0.0 || hi > 180.0)) {
    n.at("max_deg").fail("tilt is measured from straight down: keep it within [0, 180]");
  }
  if (v.angle == SceneVariable::Angle::kPan && hi - lo > 360.0) {
    n.at("max_deg").fail("pan may span at most one turn (360 degrees)");
  }
  const std::uint32_t cells = positive_count(n.at("cells"));
  v.first = p.domain.dimensions();
  try {
    p.domain.add_angle(n.has("name") ? n.at("name").string() : l.name + "." + angle + "_deg", lo,
                       hi, cells);
  } catch (const std::exception& e) {
    n.at("cells").fail(e.what());
  }
  return v;
}

SceneVariable read_flux(const JsonNode& n, SceneProblem& p, Claims& claims) {
  n.require_object(
      {"type", "name", "luminaire", "luminaires", "levels_lm", "min_lm", "max_lm", "cells"});
  SceneVariable v;
  v.type = SceneVariable::Type::kFlux;
  v.luminaires = read_luminaires(n, p.scene);
  for (std::size_t i : v.luminaires) {
    const Luminaire& l = p.scene.luminaires[i];
    if (l.type == Luminaire::Type::Directional) {
      n.fail("luminaire \"" + l.name + "\" is directional: its flux follows illuminance_lx");
    }
    claims.claim(n, "the flux of luminaire \"" + l.name + "\"");
  }
  const std::string name =
      n.has("name") ? n.at("name").string() : joined_names(p.scene, v.luminaires) + ".flux_lm";
  v.first = p.domain.dimensions();
  if (n.has("levels_lm") == (n.has("min_lm") || n.has("max_lm") || n.has("cells"))) {
    n.fail("give either \"levels_lm\" or \"min_lm\", \"max_lm\" and \"cells\"");
  }
  try {
    if (n.has("levels_lm")) {
      const JsonNode levels = n.at("levels_lm");
      std::vector<double> lm;
      for (std::size_t i = 0; i < levels.array_size(); ++i) {
        lm.push_back(levels[i].number());
        if (lm.back() < 0.0) levels[i].fail("must be >= 0");
      }
      if (lm.empty()) levels.fail("needs at least one level");
      p.domain.add_levels(name, lm);
    } else {
      const double lo = n.at("min_lm").number(), hi = n.at("max_lm").number();
      if (lo < 0.0 || !(lo < hi)) n.at("max_lm").fail("need 0 <= min_lm < max_lm");
      p.domain.add_range(name, lo, hi, positive_count(n.at("cells")));
    }
  } catch (const std::invalid_argument& e) {
    n.fail(e.what());
  }
  return v;
}

void read_variables(const JsonNode& list, SceneProblem& p) {
  if (list.array_size() == 0) list.fail("needs at least one variable");
  Claims claims;
  std::vector<bool> pivot_given;  // per rotation variable
  for (std::size_t i = 0; i < list.array_size(); ++i) {
    const JsonNode n = list[i];
    const std::string type = n.at("type").string();
    if (type == "position") {
      p.variables.push_back(read_position(n, p, claims));
    } else if (type == "translation") {
      p.variables.push_back(read_translation(n, p, claims));
    } else if (type == "rotation") {
      p.variables.push_back(read_rotation(n, p, claims, pivot_given));
    } else if (type == "aim") {
      p.variables.push_back(read_aim(n, p, claims));
    } else if (type == "flux") {
      p.variables.push_back(read_flux(n, p, claims));
    } else {
      n.at("type").fail("unknown variable type \"" + type +
                        "\" (expected position, translation, rotation, aim or flux)");
    }
  }
  resolve_pivots(p, pivot_given);
}

Intention read_intention(const JsonNode& n, const Scene& s) {
  const std::string type = n.at("type").string();
  const std::string target = n.at("target").string();
  const Target* t = find_target(s, target);
  if (!t) n.at("target").fail("unknown target \"" + target + "\"");
  const bool needs_grid = type == "maximize_uniformity" || type == "minimize_installed_flux";
  if (needs_grid && !detail::target_type(t->type).cells) {
    n.at("target").fail("uniformity needs a grid target; \"" + target + "\" is of type \"" +
                        detail::target_type(t->type).name + "\"");
  }
  auto positive = [&](const char* key) {
    const double x = n.at(key).number();
    if (x < 0.0) n.at(key).fail("must be >= 0");
    return x;
  };
  if (type == "maximize_mean_illuminance" || type == "minimize_mean_illuminance") {
    n.require_object({"type", "target"});
    return type[1] == 'a' ? maximize_mean_illuminance(target) : minimize_mean_illuminance(target);
  }
  if (type == "maximize_uniformity") {
    n.require_object({"type", "target", "min_mean_lux"});
    return maximize_uniformity(target, positive("min_mean_lux"));
  }
  if (type == "minimize_installed_flux") {
    n.require_object({"type", "target", "min_mean_lux", "min_uniformity"});
    const double u = positive("min_uniformity");
    if (u > 1.0) n.at("min_uniformity").fail("U0 = Emin/Em cannot exceed 1");
    return minimize_installed_flux(target, positive("min_mean_lux"), u);
  }
  n.at("type").fail("unknown intention \"" + type +
                    "\" (expected maximize_mean_illuminance, minimize_mean_illuminance, "
                    "maximize_uniformity or minimize_installed_flux)");
}

template <typename Enum>
Enum choice(const JsonNode& n, std::initializer_list<std::pair<const char*, Enum>> options) {
  const std::string s = n.string();
  std::string list;
  for (const auto& [name, value] : options) {
    if (s == name) return value;
    list += (list.empty() ? "" : ", ") + std::string(name);
  }
  n.fail("unknown value \"" + s + "\" (expected " + list + ")");
}

std::vector<Configuration> read_initial(const JsonNode& n, const Domain& d) {
  std::vector<Configuration> out;
  for (std::size_t i = 0; i < n.array_size(); ++i) {
    const JsonNode c = n[i];
    if (c.array_size() != d.dimensions()) {
      c.fail("expected " + std::to_string(d.dimensions()) + " cell indices (one per variable)");
    }
    Configuration cfg;
    for (std::size_t k = 0; k < d.dimensions(); ++k) {
      const std::uint64_t cell = c[k].unsigned_integer();
      if (cell >= d.variables()[k].size()) {
        c[k].fail("cell index out of range (variable \"" + d.variables()[k].name + "\" has " +
                  std::to_string(d.variables()[k].size()) + " cells)");
      }
      cfg.push_back(static_cast<std::uint32_t>(cell));
    }
    out.push_back(cfg);
  }
  return out;
}

VnsOptions read_search(const JsonNode& n, const SceneProblem& p) {
  n.require_object({"seed", "confidence", "screening_photons", "confirmation_photons", "strategy",
                    "uncertain", "max_iterations", "max_evaluations", "starts", "kmax",
                    "local_search", "neighbourhood", "initial", "min_spacing_m", "reuse_traces",
                    "refine_stage_photons", "match_widths"});
  VnsOptions o;
  o.confidence = p.scene.settings.confidence;
  if (n.has("seed")) o.seed = n.at("seed").unsigned_integer();
  o.confidence = n.number_or("confidence", o.confidence);
  if (!(o.confidence > 0.0 && o.confidence < 1.0)) {
    n.at("confidence").fail("must lie strictly between 0 and 1");
  }
  if (n.has("screening_photons"))
    o.screening_photons = n.at("screening_photons").unsigned_integer();
  if (n.has("confirmation_photons")) {
    o.confirmation_photons = n.at("confirmation_photons").unsigned_integer();
    if (o.confirmation_photons == 0) n.at("confirmation_photons").fail("must be at least 1");
  }
  using PS = PhotonStrategy;
  if (n.has("strategy")) {
    o.strategy = choice<PS>(n.at("strategy"),
                            {{"confirm", PS::kConfirm}, {"refine_at_end", PS::kRefineAtEnd}});
  }
  if (n.has("refine_stage_photons")) {  // SceneProblem::refine_stage_photons (read_block)
    o.refine_stage_photons = n.at("refine_stage_photons").unsigned_integer();
    if (o.refine_stage_photons >= o.confirmation_photons) {
      n.at("refine_stage_photons").fail("must be below confirmation_photons (0: unstaged)");
    }
  }
  if (n.has("uncertain")) {
    o.uncertain = choice<UncertainPolicy>(
        n.at("uncertain"),
        {{"reject", UncertainPolicy::kReject}, {"accept", UncertainPolicy::kAccept}});
  }
  if (n.has("max_iterations")) o.max_iterations = n.at("max_iterations").unsigned_integer();
  if (n.has("max_evaluations")) o.max_evaluations = n.at("max_evaluations").unsigned_integer();
  if (n.has("starts")) {
    const std::uint64_t s = n.at("starts").unsigned_integer();
    if (s == 0 || s > 1000000) n.at("starts").fail("must be between 1 and 1000000");
    o.starts = static_cast<std::uint32_t>(s);
  }
  if (n.has("kmax")) o.kmax = static_cast<std::uint32_t>(n.at("kmax").unsigned_integer());
  if (n.has("local_search")) {
    o.local_search = choice<LocalSearch>(
        n.at("local_search"),
        {{"first", LocalSearch::kFirstImprovement}, {"best", LocalSearch::kBestImprovement}});
  }
  if (n.has("neighbourhood")) {
    o.neighbourhood = choice<Neighbourhood>(
        n.at("neighbourhood"),
        {{"axis", Neighbourhood::kAxis}, {"chebyshev", Neighbourhood::kChebyshev}});
    if (o.neighbourhood == Neighbourhood::kChebyshev && p.domain.dimensions() > 12) {
      n.at("neighbourhood").fail("chebyshev needs at most 12 variables");
    }
  }
  if (n.has("initial")) o.initial = read_initial(n.at("initial"), p.domain);
  return o;
}

SceneProblem read_block(Scene scene, const nlohmann::json& block, const std::string& file) {
  SceneProblem p;
  p.scene = std::move(scene);
  p.file = file;
  p.block_sha256 = lightsolver::detail::sha256_hex(lightsolver::detail::canonical_json(block));
  const JsonNode root(block, "optimization", p.file);
  root.require_object({"intention", "variables", "search"});
  p.intention = read_intention(root.at("intention"), p.scene);
  read_variables(root.at("variables"), p);
  if (root.has("search")) {
    p.search = read_search(root.at("search"), p);
  } else {
    p.search.confidence = p.scene.settings.confidence;
  }
  if (root.has("search")) p.reuse_traces = root.at("search").boolean_or("reuse_traces", true);
  if (root.has("search")) p.match_widths = root.at("search").boolean_or("match_widths", true);
  if (root.has("search") && root.at("search").has("refine_stage_photons")) {
    p.refine_stage_photons = p.search.refine_stage_photons;
  }
  if (root.has("search") && root.at("search").has("min_spacing_m")) {
    const JsonNode spacing = root.at("search").at("min_spacing_m");
    p.min_spacing_m = spacing.number();
    if (!(p.min_spacing_m >= 0.0)) spacing.fail("must be >= 0");
  }
  // Cells off a `within` region and cells with two luminaires in one place (or closer than
  // min_spacing_m) are never traced, so no optimum can hold them.
  p.search.admissible = regions::both(regions::admissible_filter(p), regions::spacing_filter(p));
  for (std::size_t i = 0; i < p.search.initial.size(); ++i) {
    if (p.search.admissible && !p.search.admissible(p.search.initial[i])) {
      root.at("search").at("initial")[i].fail(
          "not admissible: a cell centre lies outside its variable's `within`, or two "
          "luminaires are closer than min_spacing_m (or in one place)");
    }
  }
  return p;
}

// The block of a scene file read once by the shared loader, which checked everything else.
SceneProblem problem_from_document(detail::SceneDocument d, const std::string& file) {
  if (!d.json.contains("optimization")) {
    throw InputError(file, "optimization", "the scene has no optimization block to run");
  }
  return read_block(std::move(d.scene), d.json.at("optimization"), file);
}

}  // namespace

std::vector<std::string> SceneProblem::movable_meshes() const {
  std::vector<std::string> names;
  for (const SceneVariable& v : variables) {
    const bool moves =
        v.type == SceneVariable::Type::kTranslation || v.type == SceneVariable::Type::kRotation;
    const std::string& name = scene.meshes[v.mesh].name;
    if (moves && std::find(names.begin(), names.end(), name) == names.end()) {
      names.push_back(name);
    }
  }
  return names;
}

SceneProblem problem_from_json(const std::string& text, const std::string& file,
                               const std::string& base_dir) {
  return problem_from_document(detail::read_scene_document(text, file, base_dir), file);
}

SceneProblem load_problem(const std::string& path) {
  return problem_from_document(detail::load_scene_document(path), path);
}

SceneProblem problem_from_scene(Scene scene, const std::string& optimization_json,
                                const std::string& file) {
  validate(scene);
  const nlohmann::json block = detail::parse_json_text(optimization_json, file);
  return read_block(std::move(scene), block, file);
}

}  // namespace lightsolver::optimizer
