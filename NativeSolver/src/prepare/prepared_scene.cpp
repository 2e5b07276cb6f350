#include "model/prepared_scene.hpp"

#include <algorithm>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <limits>
#include <unordered_map>

#include "model/groups.hpp"
#include "types/luminaire_types.hpp"
#include "types/target_types.hpp"
#include "lightsolver/timings.hpp"

namespace lightsolver::detail {
namespace {

// Centre of everything that has coordinates. Subtracting it in double before the float
// conversion keeps millimetre precision for georeferenced models millions of metres out.
glm::dvec3 scene_centre(const Scene& s) {
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
  auto grow = [&](const glm::dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  };
  for (const auto& m : s.meshes) {
    for (const auto& v : m.vertices) grow(v);
  }
  for (const auto& l : s.luminaires) grow(luminaire_type(l.type).anchor(l));
  for (const auto& t : s.targets) {
    if (const auto at = target_type(t.type).anchor(t)) grow(*at);
  }
  return 0.5 * (lo + hi);
}

vec3 local(const glm::dvec3& p, const glm::dvec3& origin) { return vec3(p - origin); }

// `displacement`: per vertex, empty when the mesh is not moved (coincident surfaces). The
// target area stays that of the mesh as given; normals follow the moved triangles.
PreparedMesh prepare_mesh(const Mesh& m, const glm::dvec3& origin,
                          const std::vector<glm::dvec3>& displacement, double& area_m2) {
  PreparedMesh out;
  out.material = m.material;
  out.vertices.reserve(m.vertices.size() * 3 + 1);
  std::vector<glm::dvec3> moved;
  if (!displacement.empty()) {
    moved = m.vertices;
    for (std::size_t i = 0; i < moved.size(); ++i) moved[i] += displacement[i];
  }
  const std::vector<glm::dvec3>& at = displacement.empty() ? m.vertices : moved;
  for (const auto& v : at) {
    const vec3 p = local(v, origin);
    out.vertices.insert(out.vertices.end(), {p.x, p.y, p.z});
  }
  out.vertices.push_back(0.0f);  // Embree may read 16 bytes at the last vertex
  out.indices.reserve(m.triangles.size() * 3);
  out.normals.reserve(m.triangles.size());
  area_m2 = 0.0;
  for (const auto& t : m.triangles) {
    out.indices.insert(out.indices.end(), {t[0], t[1], t[2]});
    const glm::dvec3 c =
        glm::cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]]);
    area_m2 += 0.5 * glm::length(c);
    out.normals.push_back(
        vec3(glm::normalize(glm::cross(at[t[1]] - at[t[0]], at[t[2]] - at[t[0]]))));
  }
  return out;
}

PreparedLuminaire prepare_luminaire(const Luminaire& l, const glm::dvec3& origin) {
  PreparedLuminaire p;
  p.type = l.type;
  p.source = &l;
  p.position = local(l.position, origin);
  p.corner = local(l.corner, origin);
  p.edge1 = vec3(l.edge1);
  p.edge2 = vec3(l.edge2);
  const LuminaireType& row = luminaire_type(l.type);
  row.prepare(l, p);
  p.emit = row.emit;
  p.flux_lm = row.emitted_flux(l);
  return p;
}

}  // namespace

PreparedScene prepare(const Scene& scene, const std::vector<std::size_t>& movable) {
  PreparedScene out;
  out.origin = scene_centre(scene);
  out.materials = scene.materials;
  out.max_bounces = scene.settings.max_bounces;
  std::vector<bool> is_target(scene.meshes.size()), is_movable(scene.meshes.size());
  for (const auto& t : scene.targets) {
    if (target_type(t.type).tally == TallyKind::MeshBin) is_target.at(t.mesh) = true;
  }
  for (std::size_t i : movable) is_movable.at(i) = true;
  CoincidentGeometry coincident = [&] {
    const timings::Scope phase("coincident surfaces");
    return find_coincident(scene, out.origin, is_target, is_movable);
  }();
  out.coincidences = std::move(coincident.pairs);
  out.warnings = coincidence_warnings(scene, out.coincidences);
  std::vector<double> mesh_area(scene.meshes.size());
  for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
    out.meshes.push_back(
        prepare_mesh(scene.meshes[i], out.origin, coincident.displacements[i], mesh_area[i]));
    out.triangle_count += scene.meshes[i].triangles.size();
  }
  for (const auto& t : scene.targets) target_type(t.type).prepare(t, mesh_area, out);
  for (std::size_t i : movable) out.meshes.at(i).movable = true;
  prepare_luminaires(scene, out);
  return out;
}

namespace {

const std::string kSharedGroupName = "(luminaires without a group)";

// Each luminaire is its own group by default. Where that many groups' tallies would not fit
// (kMaxGroupTallies: thousands of luminaires over fine grids), the luminaires without an
// explicit `group` share one instead of the run being refused; said once among the warnings.
bool default_groups_shared(const Scene& scene, PreparedScene& out) {
  const double tallies = double(scene.luminaires.size()) * double(out.bins.size());
  if (tallies <= double(kMaxGroupTallies)) return false;
  const std::string note =
      std::to_string(scene.luminaires.size()) + " luminaires x " + std::to_string(out.bins.size()) +
      " target bins exceed the 2^26 tallies of one group per luminaire: the luminaires without "
      "a `group` share the group \"" +
      kSharedGroupName + "\" (give luminaires `group` keys to trace groups apart)";
  if (std::find(out.warnings.begin(), out.warnings.end(), note) == out.warnings.end()) {
    out.warnings.push_back(note);
  }
  return true;
}

}  // namespace

void prepare_luminaires(const Scene& scene, PreparedScene& out) {
  out.luminaires.clear();
  out.groups.clear();
  double total = 0.0;
  std::unordered_map<std::string, std::size_t> group_of;  // name -> index in out.groups
  const bool shared = default_groups_shared(scene, out);
  for (std::size_t i = 0; i < scene.luminaires.size(); ++i) {
    const Luminaire& l = scene.luminaires[i];
    out.luminaires.push_back(prepare_luminaire(l, out.origin));
    const double flux = out.luminaires.back().flux_lm;  // a lamp's output at its tilt
    total += flux;
    const std::string& name = shared && l.group.empty() ? kSharedGroupName : l.group_name();
    const auto [at, added] = group_of.try_emplace(name, out.groups.size());
    if (added) out.groups.emplace_back().name = name;
    PreparedGroup* g = &out.groups[at->second];
    g->flux_lm += flux;
    g->luminaires.push_back(static_cast<std::uint32_t>(i));
    g->cdf.push_back(g->flux_lm);
  }
  out.total_flux_lm = total;
  for (PreparedGroup& g : out.groups) {
    if (g.flux_lm > 0.0) {
      for (auto& c : g.cdf) c /= g.flux_lm;
      g.cdf.back() = 1.0;
    }
  }
  // Fixed weights hold while the groups stay the same ones (the optimizer changes no group).
  if (out.share_weights.size() != out.groups.size()) out.share_weights.clear();
  set_photon_shares(out.groups, out.share_weights);
}

}  // namespace lightsolver::detail
