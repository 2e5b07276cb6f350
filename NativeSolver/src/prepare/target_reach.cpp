#include "prepare/target_reach.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

#include "lightsolver/angles.hpp"
#include "types/luminaire_types.hpp"

namespace lightsolver::detail {
namespace {

using glm::dvec3;
// Angles closer than this to a cone's edge are not trusted (float directions in the tracer).
constexpr double kAngleMargin_rad = 1e-3;
// Target triangles x luminaires beyond which a target is not judged (the check must stay cheap).
constexpr std::size_t kMaxPairs = 4'000'000;

// True when no photon of `s` can cross the plane through `c` with unit normal `n` from its
// front: every origin is behind the plane, or every direction leaves it. `margin_m` absorbs
// the tracer's origin offsets and float coordinates.
bool cannot_reach(const EmissionSupport& s, const dvec3& c, const dvec3& n, double margin_m) {
  double front = -std::numeric_limits<double>::infinity();
  for (const dvec3& p : s.points) front = std::max(front, glm::dot(p - c, n));
  if (front + s.radius < -margin_m) return true;
  // Smallest d.n over the cone: the axis's angle from n plus the cone's half angle.
  const double from_n = std::acos(std::clamp(glm::dot(s.axis, n), -1.0, 1.0));
  return from_n + s.half_angle_rad + kAngleMargin_rad < 0.5 * kPi;
}

bool dark_for_all(const std::vector<EmissionSupport>& supports, const dvec3& c, const dvec3& n,
                  double margin_m) {
  return std::all_of(supports.begin(), supports.end(),
                     [&](const EmissionSupport& s) { return cannot_reach(s, c, n, margin_m); });
}

// Every triangle of a surface target faces away from every luminaire.
bool mesh_is_dark(const PreparedMesh& m, const std::vector<EmissionSupport>& supports,
                  double margin_m) {
  for (std::size_t t = 0; t < m.normals.size(); ++t) {
    const dvec3 n(m.normals[t]);
    if (!(std::abs(glm::length(n) - 1.0) < 1e-3)) return false;  // degenerate: do not judge
    const std::uint32_t i = m.indices[3 * t];
    const dvec3 v(m.vertices[3 * i], m.vertices[3 * i + 1], m.vertices[3 * i + 2]);
    if (!dark_for_all(supports, v, n, margin_m)) return false;
  }
  return true;
}

// Float error of the tracer's local coordinates and origin offsets (256 ulps at most) grows
// with the distance from the scene's centre.
double margin_for(const PreparedScene& s) {
  double far_m = 0.0;
  for (const PreparedLuminaire& l : s.luminaires) {
    far_m = std::max(
        {far_m, glm::length(dvec3(l.position)),
         glm::length(dvec3(l.corner)) + glm::length(dvec3(l.edge1)) + glm::length(dvec3(l.edge2))});
  }
  for (const PreparedGrid& g : s.grids) far_m = std::max(far_m, glm::length(dvec3(g.corner)));
  return 1e-3 + 1e-4 * far_m;
}

std::string label(const Scene& scene, std::size_t i) {
  return "targets[" + std::to_string(i) + "] (\"" + scene.targets[i].name + "\")";
}

// A target's grid rows (its record's), every one counting reflected light only: its eyes.
bool only_reflected(const PreparedScene& s, const PreparedTarget& at) {
  if (at.grid_rows == 0) return false;
  for (std::uint32_t r = at.first_grid; r < at.first_grid + at.grid_rows; ++r) {
    if (s.grids[r].indirect_only == 0) return false;
  }
  return true;
}

// Every grid row of the target faces away from every luminaire.
bool rows_are_dark(const PreparedScene& s, const PreparedTarget& at,
                   const std::vector<EmissionSupport>& supports, double margin_m) {
  for (std::uint32_t r = at.first_grid; r < at.first_grid + at.grid_rows; ++r) {
    const PreparedGrid& g = s.grids[r];
    if (!dark_for_all(supports, dvec3(g.corner), glm::normalize(dvec3(g.normal)), margin_m)) {
      return false;
    }
  }
  return true;
}

// A surface target: every triangle of its mesh faces away (a movable mesh is never judged).
bool mesh_target_is_dark(const PreparedMesh& m, const std::vector<EmissionSupport>& supports,
                         double margin_m) {
  return !m.movable && !m.normals.empty() && m.normals.size() * supports.size() <= kMaxPairs &&
         mesh_is_dark(m, supports, margin_m);
}

}  // namespace

std::vector<DarkTarget> dark_targets(const Scene& scene, const PreparedScene& prepared,
                                     const SceneEffects& effects) {
  std::vector<DarkTarget> out;
  if (effects.has(Effect::Interreflection) || prepared.total_flux_lm <= 0.0) return out;
  std::vector<EmissionSupport> supports;
  for (std::size_t i = 0; i < prepared.luminaires.size(); ++i) {
    const PreparedLuminaire& l = prepared.luminaires[i];
    if (scene.luminaires[i].flux_lm > 0.0) supports.push_back(luminaire_type(l.type).support(l));
  }
  const double margin_m = margin_for(prepared);
  for (std::size_t i = 0; i < scene.targets.size(); ++i) {
    const PreparedTarget& at = prepared.targets[i];  // where it tallies: a mesh, or grid rows
    if (only_reflected(prepared, at)) {
      out.push_back({i, label(scene, i) +
                            ": an observer counts reflected light only and no surface reflects "
                            "(every reflectance is 0): its background luminance will be 0"});
      continue;
    }
    const bool dark =
        at.mesh >= 0
            ? mesh_target_is_dark(prepared.meshes[std::size_t(at.mesh)], supports, margin_m)
            : at.grid_rows > 0 && rows_are_dark(prepared, at, supports, margin_m);
    if (dark) {
      out.push_back({i, label(scene, i) +
                            ": faces away from every luminaire and no surface reflects (every "
                            "reflectance is 0): it cannot receive light, its result will be 0 lx"});
    }
  }
  return out;
}

void report_effects(const Scene& scene, const PreparedScene& prepared, Results& results) {
  const SceneEffects effects = analyse_effects(prepared);
  results.effects = effects_report(effects);
  // next_event "auto" gave some targets back to the photons: which, and why.
  if (effects.has(Effect::NextEventDirect) && !prepared.next_event_targets.empty()) {
    results.effects.notes.push_back(
        {effect_name(Effect::NextEventDirect), prepared.next_event_targets});
  }
  for (DarkTarget& d : dark_targets(scene, prepared, effects)) {
    results.warnings.push_back(std::move(d.message));
  }
}

}  // namespace lightsolver::detail
