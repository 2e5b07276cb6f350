#include "vulkan/gpu_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>

#include "lightsolver/photometry.hpp"
#include "types/luminaire_rows.hpp"

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

using M = Material::Type;

// The GPU's row of each luminaire type: its code in the packed record and the switch that keeps
// its branch of emit.glsl, generated from LS_LUMINAIRE_TYPES (Shaders/shared/luminaires.h). Each
// code must be its Luminaire::Type value; gpu_luminaire_type() and vulkan_tests'
// GpuLuminaireTypes check that every row of core's table (luminaire_types.cpp) has one.
#define LS_GPU_ROW(name, code, has, emission) \
  {Luminaire::Type::name, code, gpu::luminaire_switch(code)},
const GpuLuminaireType kGpuLuminaireTypes[] = {LS_LUMINAIRE_TYPES(LS_GPU_ROW)};
#undef LS_GPU_ROW
#define LS_SAME_CODE(name, code, has, emission)                  \
  static_assert(static_cast<int>(Luminaire::Type::name) == code, \
                "LS_LUMINAIRE_TYPES: " #name "'s code is not its Luminaire::Type value");
LS_LUMINAIRE_TYPES(LS_SAME_CODE)
#undef LS_SAME_CODE

// Materials are packed by their enum value; the shader's codes come from trace_bindings.h.
static_assert(static_cast<int>(M::Diffuse) == LS_MATERIAL_DIFFUSE &&
              static_cast<int>(M::Mirror) == LS_MATERIAL_MIRROR &&
              static_cast<int>(M::Glass) == LS_MATERIAL_GLASS &&
              static_cast<int>(M::Glossy) == LS_MATERIAL_GLOSSY);

// The record holds what the type's prepare hook left in the prepared luminaire, field for field
// whatever the type (the record's fields carry PreparedLuminaire's names): a type whose
// emission reads only these fields needs no packing of its own.
gpu::Luminaire pack_luminaire(const PreparedLuminaire& l) {
  gpu::Luminaire g{};
  g.position = l.position;
  g.type = gpu_luminaire_type(l.type).code;
  g.axis = l.axis;
  g.half_beam_rad = l.half_beam_rad;
  g.corner = l.corner;
  g.half_field_rad = l.half_field_rad;
  g.edge1 = l.edge1;
  g.cos_half_field = l.cos_half_field;
  g.edge2 = l.edge2;
  return g;  // photometric: pack_luminaires sets it for a photometric luminaire
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
  g.flags = (p.indirect_only ? gpu::kGridIndirectOnly : 0u) |
            (p.direct_by_photons ? gpu::kGridDirectByPhotons : 0u);
  g.connect_r0 = p.connect_r0;
  return g;
}

// The switches are core's scene analysis (prepare/scene_effects.hpp), the one the Embree kernels
// and the results' effect list use. A material kind whose every surface absorbs is switched off:
// scatter.glsl then absorbs the photon, as its own branch would.
std::vector<vkw::SpecConstant> features(const PreparedScene& s) {
  const SceneEffects e = analyse_effects(s);
  using E = Effect;
  // By id, not by position: the ids come from Shaders/trace_bindings.h.
  const std::pair<gpu::SpecId, bool> on[] = {
      {gpu::kHasDiffuse, e.has(E::DiffuseReflection)},
      {gpu::kHasMirror, e.has(E::MirrorReflection)},
      {gpu::kHasGlass, e.has(E::Refraction)},
      {gpu::kHasGlossy, e.has(E::GlossyReflection)},
      {gpu::kHasGrids, e.has(E::GridCrossing) || e.has(E::ObserverCrossing)},
      {gpu::kHasSurfaceBins, e.has(E::SurfaceTargets)},
      {gpu::kManyLuminaires, e.has(E::LuminaireChoice)},
      {gpu::kHasInstances, e.has(E::Instancing)}};
  std::vector<vkw::SpecConstant> out;
  for (const auto& [id, value] : on) out.push_back({id, value ? 1u : 0u});
  for (const auto& row : kGpuLuminaireTypes) {
    out.push_back({row.feature, e.has(emission_effect(row.type))});
  }
  return out;
}

// Photometric sampler tables, stored once per sampler however many luminaires share it.
class PhotometricPacker {
 public:
  explicit PhotometricPacker(GpuSceneData& d) : d_(d) {}

  gpu::Photometric pack(const PreparedLuminaire& l) {
    if (!l.source || !l.source->sampler) {
      throw std::runtime_error("Vulkan backend: photometric luminaire without a loaded file");
    }
    const PhotometricSampler& sampler = *l.source->sampler;
    auto [it, added] = tables_.try_emplace(&sampler);
    if (added) it->second = add_tables(sampler.tables());
    gpu::Photometric p = it->second;
    put(p.c0, l.c0);
    if (const PhotometricData* data = l.source->photometry.get()) {
      p.round_opening = round_opening(data->opening_shape) ? 1u : 0u;
      p.length = static_cast<float>(data->opening_length_m);
      p.width = static_cast<float>(data->opening_width_m);
    }
    return p;
  }

 private:
  // PhotometricSampler::sample_origin draws over an ellipse for these shapes (sampler.cpp).
  static bool round_opening(OpeningShape s) {
    return s == OpeningShape::Disk || s == OpeningShape::VerticalCylinder ||
           s == OpeningShape::Sphere || s == OpeningShape::VerticalDisk;
  }

  std::uint32_t add_floats(const std::vector<double>& v) {
    const auto offset = static_cast<std::uint32_t>(d_.photo_floats.size());
    for (double x : v) d_.photo_floats.push_back(static_cast<float>(x));
    return offset;
  }

  gpu::Photometric add_tables(const SamplerTables& t) {
    gpu::Photometric p{};
    put(p.pole, glm::vec3(t.pole));
    put(p.zero, glm::vec3(t.zero));
    put(p.ninety, glm::vec3(t.ninety));
    p.np = static_cast<std::uint32_t>(t.plane_deg.size());
    p.nt = static_cast<std::uint32_t>(t.polar_deg.size());
    p.plane_off = add_floats(t.plane_deg);
    p.polar_off = add_floats(t.polar_deg);
    p.candela_off = add_floats(t.candela);
    p.bound_off = add_floats(t.cell_bound);
    p.cell_off = static_cast<std::uint32_t>(d_.photo_cdf53.size());
    p.cell_count = static_cast<std::uint32_t>(t.cell_cdf.size());
    const double total = t.cell_cdf.back();
    for (double c : t.cell_cdf) d_.photo_cdf53.push_back(scaled_cdf_threshold(c, total));
    std::size_t last = t.cell_cdf.size() - 1;  // as sample_direction when x rounds up to total
    while (last > 0 && t.cell_cdf[last] == t.cell_cdf[last - 1]) --last;
    p.last_cell = static_cast<std::uint32_t>(last);
    return p;
  }

  GpuSceneData& d_;
  std::map<const PhotometricSampler*, gpu::Photometric> tables_;
};

}  // namespace

const GpuLuminaireType& gpu_luminaire_type(Luminaire::Type type) {
  for (const auto& row : kGpuLuminaireTypes) {
    if (row.type == type) return row;
  }
  throw std::logic_error("luminaire type without a GPU row in vulkan/gpu_scene.cpp");
}

std::uint64_t scaled_cdf_threshold(double c, double total) {
  // The CPU picks the first cell with c > uniform_double() * total, where uniform_double() =
  // k 2^-53 exactly; the rounded product is monotone in k, so the cells above the draw are
  // exactly those with k < (smallest k whose product reaches c).
  std::uint64_t lo = 0, hi = std::uint64_t(1) << 53;
  while (lo < hi) {
    const std::uint64_t mid = lo + (hi - lo) / 2;
    if (static_cast<double>(mid) * 0x1p-53 * total >= c)
      hi = mid;
    else
      lo = mid + 1;
  }
  return lo;
}

gpu::Instance pack_instance(const GpuInstanceRoot& r, const glm::mat4& transform) {
  gpu::Instance g{};
  const glm::dmat4 m(transform);
  const glm::mat4 inv(glm::inverse(m));
  std::memcpy(g.to_world, &transform[0][0], sizeof g.to_world);
  std::memcpy(g.to_object, &inv[0][0], sizeof g.to_object);
  g.root = r.root;
  glm::dvec3 lo(0.0), hi(0.0);
  if (r.lo.x <= r.hi.x) {  // not an empty mesh: the world box of the eight moved corners
    lo = glm::dvec3(std::numeric_limits<double>::max());
    hi = -lo;
    for (int k = 0; k < 8; ++k) {
      const glm::dvec3 c(k & 1 ? r.hi.x : r.lo.x, k & 2 ? r.hi.y : r.lo.y, k & 4 ? r.hi.z : r.lo.z);
      const glm::dvec3 w(m * glm::dvec4(c, 1.0));
      lo = glm::min(lo, w);
      hi = glm::max(hi, w);
    }
    // Widened well beyond float rounding of the transform: the box only culls.
    const glm::dvec3 a = glm::max(glm::abs(lo), glm::abs(hi));
    const double pad = 1e-5 * (1.0 + std::max({a.x, a.y, a.z}));
    lo -= pad;
    hi += pad;
  }
  put(g.lo, glm::vec3(lo));
  put(g.hi, glm::vec3(hi));
  return g;
}

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
  d.photometrics.clear();
  d.photo_floats.clear();
  d.photo_cdf53.clear();
  d.group_luminaires.clear();
  PhotometricPacker photometric(d);
  // Group by group, each group's cumulative flux after it: pick_luminaire() searches its own.
  for (const PreparedGroup& g : s.groups) {
    d.group_luminaires.push_back({static_cast<std::uint32_t>(d.luminaires.size()),
                                  static_cast<std::uint32_t>(g.luminaires.size())});
    for (std::size_t k = 0; k < g.luminaires.size(); ++k) {
      const PreparedLuminaire& l = s.luminaires[g.luminaires[k]];
      d.luminaires.push_back(pack_luminaire(l));
      d.cdf53.push_back(cdf_threshold(g.cdf[k]));
      if (l.type == Luminaire::Type::Photometric) {
        d.luminaires.back().photometric = static_cast<std::uint32_t>(d.photometrics.size());
        d.photometrics.push_back(photometric.pack(l));
      } else if (l.type == Luminaire::Type::Sky) {  // its record in the photometric floats
        if (!l.source || !l.source->sky_emitter) {
          throw std::runtime_error("Vulkan backend: sky luminaire not validated");
        }
        d.luminaires.back().photometric =
            pack_sky_record(l, d.photo_floats, d.photo_cdf53, scaled_cdf_threshold);
      } else if (l.type == Luminaire::Type::Sun) {  // its portals, if it has them
        d.luminaires.back().photometric =
            pack_sun_record(l, d.photo_floats, d.photo_cdf53, scaled_cdf_threshold);
      }
    }
  }
  if (d.photo_floats.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw std::runtime_error("Vulkan backend: photometric tables too large");
  }
  d.features = features(s);
}

bool pack_target_records(const PreparedScene& s, GpuSceneData& d) {
  std::vector<gpu::MeshInfo> meshes;
  for (const auto& m : s.meshes) {
    const std::uint32_t flags = m.direct_by_photons ? gpu::kMeshDirectByPhotons : 0u;
    meshes.push_back({static_cast<std::uint32_t>(m.material), m.bin, flags, 0});
  }
  std::vector<gpu::Grid> grids;
  for (const auto& g : s.grids) grids.push_back(pack_grid(g));
  // Empty vectors may have null data(), which memcmp must not get (UBSan's nonnull check).
  const auto same_bytes = [](const auto& a, const auto& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(a.front())) == 0);
  };
  if (same_bytes(meshes, d.meshes) && same_bytes(grids, d.grids)) return false;
  d.meshes = std::move(meshes);
  d.grids = std::move(grids);
  return true;
}

GpuSceneData pack_scene(const PreparedScene& s) {
  GpuSceneData d;
  pack_luminaires(s, d);
  for (const auto& m : s.materials) d.materials.push_back(pack_material(m));
  pack_target_records(s, d);
  d.geometry = build_gpu_geometry(s);
  d.instance_roots = d.geometry.instances;
  for (const auto& r : d.instance_roots) {
    d.instances.push_back(pack_instance(r, s.meshes[r.mesh].transform));
  }
  return d;
}

}  // namespace lightsolver::detail
