#include "vulkan/gpu_scene.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace lightsolver::detail {
namespace {

void put(float* dst, const glm::vec3& v) {
  dst[0] = v.x;
  dst[1] = v.y;
  dst[2] = v.z;
}

gpu::Material pack_material(const Material& m) {
  gpu::Material g{};
  g.type = static_cast<std::uint32_t>(m.type);
  g.p_first = probability_threshold(m.reflectance);
  g.p_second = probability_threshold(m.reflectance + m.specular);  // same double sum as the CPU
  g.thin = m.thin ? 1u : 0u;
  g.ior = static_cast<float>(m.ior);
  g.tau = static_cast<float>(m.transmittance);
  g.alpha = static_cast<float>(m.roughness * m.roughness);
  return g;
}

gpu::Luminaire pack_luminaire(const PreparedLuminaire& l) {
  if (l.type == Luminaire::Type::Photometric) {
    throw std::runtime_error("Vulkan backend: photometric luminaire \"" +
                             (l.source ? l.source->name : std::string()) +
                             "\" is not supported yet; use --backend embree");
  }
  gpu::Luminaire g{};
  put(g.position, l.position);
  g.type = static_cast<std::uint32_t>(l.type);
  put(g.axis, l.axis);
  g.half_beam = l.half_beam_rad;
  put(g.corner, l.corner);
  g.half_field = l.half_field_rad;
  put(g.edge1, l.edge1);
  g.cos_half_field = l.cos_half_field;
  put(g.edge2, l.edge2);
  return g;
}

gpu::Grid pack_grid(const PreparedGrid& p) {
  gpu::Grid g{};
  put(g.corner, p.corner);
  g.nu = p.nu;
  put(g.normal, p.normal);
  g.nv = p.nv;
  put(g.du, p.du);
  g.bin = p.bin;
  put(g.dv, p.dv);
  return g;
}

std::vector<vkw::SpecConstant> features(const PreparedScene& s) {
  auto uses_material = [&](Material::Type t) {
    return std::any_of(s.meshes.begin(), s.meshes.end(), [&](const PreparedMesh& m) {
      return !m.indices.empty() && s.materials[m.material].type == t;
    });
  };
  auto uses_luminaire = [&](Luminaire::Type t) {
    return std::any_of(s.luminaires.begin(), s.luminaires.end(),
                       [&](const PreparedLuminaire& l) { return l.type == t; });
  };
  const bool surface_bins = std::any_of(s.meshes.begin(), s.meshes.end(),
                                        [](const PreparedMesh& m) { return m.bin >= 0; });
  using M = Material::Type;
  using L = Luminaire::Type;
  const bool on[] = {uses_material(M::Diffuse), uses_material(M::Mirror),
                     uses_material(M::Glass),   uses_material(M::Glossy),
                     uses_luminaire(L::Point),  uses_luminaire(L::Spot),
                     uses_luminaire(L::Area),   uses_luminaire(L::Directional),
                     !s.grids.empty(),          surface_bins,
                     s.luminaires.size() > 1};
  std::vector<vkw::SpecConstant> out;
  for (std::uint32_t id = gpu::kHasDiffuse; id < gpu::kSpecCount; ++id) {
    out.push_back({id, on[id - gpu::kHasDiffuse] ? 1u : 0u});
  }
  return out;
}

}  // namespace

std::uint32_t probability_threshold(double p) {
  // uniform() = k * 2^-24 exactly, so k * 2^-24 < p  <=>  k < ceil(p * 2^24) (scaling is exact).
  return static_cast<std::uint32_t>(std::clamp(std::ceil(p * 0x1p24), 0.0, 0x1p24));
}

std::uint64_t cdf_threshold(double c) {
  return static_cast<std::uint64_t>(std::clamp(std::ceil(c * 0x1p53), 0.0, 0x1p53));
}

void pack_luminaires(const PreparedScene& s, GpuSceneData& d) {
  d.luminaires.clear();
  d.cdf53.clear();
  for (const auto& l : s.luminaires) d.luminaires.push_back(pack_luminaire(l));
  for (double c : s.luminaire_cdf) d.cdf53.push_back(cdf_threshold(c));
  d.features = features(s);
}

GpuSceneData pack_scene(const PreparedScene& s) {
  GpuSceneData d;
  pack_luminaires(s, d);
  for (const auto& m : s.materials) d.materials.push_back(pack_material(m));
  for (const auto& m : s.meshes) {
    d.meshes.push_back({static_cast<std::uint32_t>(m.material), m.bin, {0, 0}});
  }
  for (const auto& g : s.grids) d.grids.push_back(pack_grid(g));
  d.geometry = build_gpu_geometry(s);
  return d;
}

}  // namespace lightsolver::detail
