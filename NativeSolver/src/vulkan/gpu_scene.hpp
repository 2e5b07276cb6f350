#pragma once
// Everything trace.comp reads, packed on the CPU from a PreparedScene: geometry and BVH, mesh
// table, materials with integer probability thresholds, luminaires, the luminaire CDF as 53-bit
// integer thresholds, grids, and the specialisation constants that switch features on.
#include <cstdint>
#include <vector>

#include "core/prepared_scene.hpp"
#include "vulkan/algorithm.hpp"
#include "vulkan/gpu_bvh.hpp"
#include "vulkan/gpu_layout.hpp"

namespace lightsolver::detail {

struct GpuSceneData {
  GpuGeometry geometry;
  std::vector<gpu::MeshInfo> meshes;
  std::vector<gpu::Material> materials;
  std::vector<gpu::Luminaire> luminaires;
  std::vector<std::uint64_t> cdf53;
  std::vector<gpu::Grid> grids;
  std::vector<vkw::SpecConstant> features;  // ids kHasDiffuse .. kManyLuminaires
};

/// `uniform() < p` for the CPU's double p equals `rng_u24() < probability_threshold(p)`.
std::uint32_t probability_threshold(double p);

/// `uniform_double() < c` equals `rng_u53() < cdf_threshold(c)`.
std::uint64_t cdf_threshold(double c);

/// Packs the scene. Throws std::runtime_error for what the GPU tracer does not support yet
/// (photometric luminaires).
GpuSceneData pack_scene(const PreparedScene& scene);

/// Re-packs only luminaires, their CDF and the feature switches (after luminaires changed).
void pack_luminaires(const PreparedScene& scene, GpuSceneData& out);

}  // namespace lightsolver::detail
