#pragma once
// Everything trace.comp reads, packed on the CPU from a PreparedScene: geometry and BVH, mesh
// table, materials with integer probability thresholds, luminaires, the luminaire CDF as 53-bit
// integer thresholds, grids, and the specialisation constants that switch features on.
#include <cstdint>
#include <vector>

#include "model/prepared_scene.hpp"
#include "prepare/scene_effects.hpp"
#include "vulkan/algorithm.hpp"
#include "vulkan/gpu_bvh.hpp"
#include "vulkan/gpu_layout.hpp"

namespace lightsolver::detail {

struct GpuSceneData {
  GpuGeometry geometry;
  std::vector<gpu::MeshInfo> meshes;
  std::vector<gpu::Material> materials;
  std::vector<gpu::Luminaire> luminaires;
  std::vector<std::uint64_t> cdf53;  // each group's cumulative flux, group by group
  /// Per luminaire group: its first luminaire in `luminaires` and how many it has.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> group_luminaires;
  std::vector<gpu::Grid> grids;
  std::vector<gpu::Photometric> photometrics;   // one per photometric luminaire
  std::vector<float> photo_floats;              // their sampler tables (shared per file)
  std::vector<std::uint64_t> photo_cdf53;       // their cell thresholds
  std::vector<GpuInstanceRoot> instance_roots;  // one per movable mesh
  std::vector<gpu::Instance> instances;         // their current placement
  std::vector<vkw::SpecConstant> features;      // every id of kSpecConstants but the workgroup's
};

/// The GPU side of a luminaire type, generated from its entry in LS_LUMINAIRE_TYPES
/// (Shaders/shared/luminaires.h): its code in gpu::Luminaire::type and the specialisation
/// constant that keeps its branch of emit() (emit.glsl).
struct GpuLuminaireType {
  Luminaire::Type type;
  std::uint32_t code;
  gpu::SpecId feature;  ///< on when the scene analysis has the type's emission_effect()
};

/// The row of `type`; throws std::logic_error when the type has none.
const GpuLuminaireType& gpu_luminaire_type(Luminaire::Type type);

/// `uniform() < p` for the CPU's double p equals `rng_u24() < probability_threshold(p)`.
std::uint32_t probability_threshold(double p);

/// `uniform_double() < c` equals `rng_u53() < cdf_threshold(c)`.
std::uint64_t cdf_threshold(double c);

/// The photometric cell pick: `uniform_double() * total < c` equals
/// `rng_u53() < scaled_cdf_threshold(c, total)`.
std::uint64_t scaled_cdf_threshold(double c, double total);

/// A movable mesh's BVH placed by `transform` (prepared -> local world, rigid).
gpu::Instance pack_instance(const GpuInstanceRoot& root, const glm::mat4& transform);

/// Packs the scene. Throws std::runtime_error when Embree cannot build the BVH or a
/// photometric luminaire has no loaded file.
GpuSceneData pack_scene(const PreparedScene& scene);

/// Packs the mesh and grid records (their flags follow the next-event plan, which changes per
/// run: PreparedMesh/PreparedGrid::direct_by_photons); true when they differ from `out`'s.
bool pack_target_records(const PreparedScene& scene, GpuSceneData& out);

/// Re-packs luminaires, their CDF, photometric tables and the feature switches.
void pack_luminaires(const PreparedScene& scene, GpuSceneData& out);

}  // namespace lightsolver::detail
