#pragma once
// The scene as the tracers consume it: re-centred (in double, then float), tallies laid out as
// bins, luminaires reduced to what emission needs. Shared by every backend (Embree, Vulkan).
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <memory>
#include <string>
#include <vector>

#include "lightsolver/rng.hpp"
#include "lightsolver/scene.hpp"
#include "model/coincident.hpp"

namespace lightsolver::detail {

using glm::vec3;

struct EmittedRay {
  vec3 origin, direction;
  // A daylight photon leaving an opening (a sky's portal, a sun's opening): the vector its
  // origin was pushed off the opening along (into the room). Nonzero: the photon is kept only if
  // its way out, from the opening against `direction`, escapes the scene (opening_escape_origin,
  // Shaders/shared/luminaires.h). Zero: any other photon.
  vec3 opening_push{0.0f};
};

struct PreparedMesh {
  std::vector<float> vertices;         // x,y,z per vertex, plus one float of padding for Embree
  std::vector<std::uint32_t> indices;  // 3 per triangle
  std::vector<vec3> normals;           // unit front (counter-clockwise) normal per triangle
  int material = 0;
  std::int32_t bin = -1;      // surface-target bin, or -1
  bool movable = false;       // instanced so its transform can change cheaply
  glm::mat4 transform{1.0f};  // movable: prepared (local) coordinates -> local world
  // Its surface target's direct light stays with the photons although its groups have
  // next_event (next_event "auto" judged the shadow rays wider there: estimate/direct_choice.hpp):
  // their bounce-0 hits deposit. Every mesh of the target's bin has the same value.
  bool direct_by_photons = false;
};

struct PreparedGrid {
  vec3 corner, normal;  // normal = unit(edge1 x edge2): photons crossing against it count
  vec3 du, dv;          // dual vectors: local (a, b) = (dot(p - corner, du), dot(p - corner, dv))
  std::uint32_t nu = 1, nv = 1;
  std::uint32_t bin = 0;  // whole-grid bin; cell (iu, iv) is bin + 1 + iv * nu + iu
  // Observers' tallies: count only segments after at least one reflection (path depth >= 1).
  std::uint32_t indirect_only = 0;
  // Connected reflected light (estimate/reflection_connection.hpp): for a group with
  // PreparedGroup::connect, a reflected segment (bounce >= 1) counts its crossing only closer
  // than this to its origin; farther crossings come from connections. 0: none.
  float connect_r0 = 0.0f;
  // Its direct light stays with the photons although their group has next_event (next_event
  // "auto" judged the shadow rays wider there): next-event groups' bounce-0 crossings count.
  bool direct_by_photons = false;
};

// Side of an observer's virtual square at the eye (m): small against a room (its mean over
// 10 cm of a smooth indirect field is the value at the eye), large enough to catch photons.
inline constexpr double kObserverSquare_m = 0.1;

struct PreparedLuminaire {
  Luminaire::Type type = Luminaire::Type::Point;
  // The type's emission (its row in luminaire_types.cpp), set by prepare(): one indirect call
  // per photon instead of a switch over the type.
  EmittedRay (*emit)(const PreparedLuminaire& l, PathRng& rng) = nullptr;
  vec3 position{0.0f}, axis{0, 0, -1};  // axis: spot axis, beam or area normal
  vec3 corner{0.0f}, edge1{0.0f}, edge2{0.0f};
  // Spot profile: relative intensity through (0,1), (beam/2, 0.5), (field/2, 0.1), 0 beyond.
  float half_beam_rad = 0, half_field_rad = 0, cos_half_field = 1;
  const Luminaire* source = nullptr;  // for photometric data and names
  double flux_lm = 0.0;               // emitted as traced (emitted_flux_lm: TILT applied), lm
  vec3 c0{1, 0, 0};                   // photometric frame: gamma=0 along axis, C0 along c0
  double direct_norm = 0.0;           // spot: its profile's solid angle (sr), for direct light
  // A sun through portals (luminaire_sun.cpp): each portal facing it as its own record of the
  // fields emit_sun reads, chosen by the cumulative flux fractions `portal_cdf` (last = 1).
  std::vector<PreparedLuminaire> portals;
  std::vector<double> portal_cdf;
};

// A luminaire group (Luminaire::group_name()): its own photon stream and its own tallies.
struct PreparedGroup {
  std::string name;
  double flux_lm = 0.0;                   // the group's emitted flux
  std::vector<std::uint32_t> luminaires;  // indices into PreparedScene::luminaires, scene order
  std::vector<double> cdf;                // cumulative flux fractions within the group, last = 1
  double share = 0.0;  // fraction of a run's photons traced from it (groups.hpp, photon_shares)
  // Its direct light at grids and surface targets comes from next-event estimation
  // (direct/next_event.hpp): backends then tally only its photons' segments and hits after at
  // least one scattering (bounce >= 1), as for observers. Observers are unchanged.
  bool next_event = false;
  // Its reflected light at grids (not observers) beyond each grid's connect_r0 comes from
  // connecting the diffuse vertices of an independent photon stream to the grid's cells
  // (estimate/reflection_connection.hpp), added into its direct parts; its photons count only
  // reflected crossings closer than connect_r0 (cross_grids). Only with next_event.
  bool connect = false;
};

/// A group's direct light in one bin by next-event estimation (estimate/next_event.hpp), at the
/// group's flux as prepared: the mean illuminance, its variance, and how many of its samples
/// saw light (reported with the photon hits).
struct DirectPart {
  double lux = 0.0;
  double variance = 0.0;  // lx^2
  std::uint64_t lit = 0;
};

struct BinInfo {
  double area_m2 = 0.0;
};

/// Bins per eye of an observer or observer grid: its square, then the square's one cell (an
/// eye is a 1 x 1 grid row).
inline constexpr std::uint32_t kEyeBins = 2;

/// Where a target's tallies are: one record per Scene target, laid out by its type's prepare
/// hook (target_types.cpp, append_target_bins). Results, contributions, accuracy goals, reach
/// and rescale read it instead of recounting a type's bins or grid rows.
struct PreparedTarget {
  std::uint32_t bin = 0;        ///< first bin: the whole target (an eye target's first square)
  std::uint32_t bin_count = 1;  ///< bins from `bin` that are its own or shared (a mesh's: 1)
  std::uint32_t cells = 0;      ///< cell bins: cell c at cell_bin(c) (a grid's nu * nv)
  std::uint32_t points = 0;     ///< eyes: eye k's square at point_bin(k), kEyeBins each
  std::uint32_t point_stride = 0;
  std::uint32_t first_grid = 0;  ///< its PreparedGrid rows: [first_grid, first_grid + grid_rows)
  std::uint32_t grid_rows = 0;
  std::int32_t mesh = -1;  ///< the mesh whose bin it is (PreparedScene::meshes), or -1

  std::uint32_t cell_bin(std::uint32_t c) const { return bin + 1 + c; }
  std::uint32_t point_bin(std::uint32_t k) const { return bin + point_stride * k; }
  /// The bins an accuracy goal judges: each eye's square, else the whole target.
  std::uint32_t goal_count() const { return points > 0 ? points : 1; }
  std::uint32_t goal_bin(std::uint32_t k) const { return points > 0 ? point_bin(k) : bin; }
};

struct PreparedScene {
  glm::dvec3 origin{0.0};  // world = local + origin
  std::vector<Material> materials;
  std::vector<PreparedMesh> meshes;
  std::vector<PreparedGrid> grids;
  std::vector<PreparedLuminaire> luminaires;
  std::vector<PreparedGroup> groups;  // in the order of first appearance in the scene
  // Fixed photon-share weights, one per group (Simulation::fix_photon_shares); empty: by flux.
  std::vector<double> share_weights;
  std::vector<BinInfo> bins;
  std::vector<PreparedTarget> targets;  // one per Scene target, in scene order
  std::vector<std::string> observers;   // the target of each eye's tally (indirect-only grids)
  double total_flux_lm = 0.0;
  std::uint32_t max_bounces = 1000;
  std::size_t triangle_count = 0;
  std::vector<Coincidence> coincidences;  // coplanar overlapping meshes (coincident.hpp)
  Warnings warnings;                      // for Results::warnings: the coincidences, in words
  // Next-event estimation of the run (groups with next_event): their direct parts, groups x
  // bins (group-major like the tallies); empty when no group has it. `next_event_off` says why
  // a scene has none (the effects list's reason).
  std::vector<DirectPart> direct;
  std::string next_event_off = "not planned";
  // next_event "auto": which targets kept shadow rays and which went back to the photons, in
  // words (the effects list's note on next_event_direct); empty when every target kept them.
  std::string next_event_targets;
  // Why no group has `connect` (the effects list's reason).
  std::string connect_off = "not planned";
  // Some surface returns light: a next-event group's photons can deposit (after a bounce). When
  // false, their photon part is exactly zero and the direct part is the whole estimate.
  bool photons_reflect = true;
};

// Builds the tracer-side scene. The Scene must have passed validate(). Meshes whose indices
// are listed in `movable` are marked for instancing. Coincident static surfaces are detected
// and the hidden one moved behind the target (coincident.hpp); movable meshes are not checked.
PreparedScene prepare(const Scene& scene, const std::vector<std::size_t>& movable = {});

// Re-derives the luminaires, their groups and each group's flux CDF after Scene::luminaires
// changed.
void prepare_luminaires(const Scene& scene, PreparedScene& out);

}  // namespace lightsolver::detail
