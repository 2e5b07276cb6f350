#pragma once
// The Embree backend's path kernels: the path loop is compiled once per feature set, and the
// scene analysis (prepare/scene_effects.hpp) picks one at run time, as the Vulkan backend picks
// its specialisation constants. A kernel leaves out what its scene cannot need: material kinds
// no surface has (the glass Fresnel code, the GGX lobe, mirrors), every scattering when no
// surface returns light (direct light only: a path ends at its first hit), the grid test when
// there is no grid. Each variant draws the same random numbers as the general kernel wherever a
// path goes on, so tallies are bit-identical (embree_kernel_test).
#include <glm/geometric.hpp>

#include "model/path_deposits.hpp"
#include "model/scatter.hpp"
#include "prepare/scene_effects.hpp"

namespace lightsolver::detail {

/// What a path kernel is compiled with. Diffuse reflection is always in a reflecting kernel
/// (almost every room has it).
struct KernelFeatures {
  bool reflects = true;  ///< false: direct light only, one segment per photon
  bool mirror = true;
  bool glossy = true;
  bool glass = true;
  bool grids = true;  ///< virtual grids or observers

  constexpr bool operator==(const KernelFeatures&) const = default;
};

/// Every effect: the kernel any scene can run (and the one a forced general run uses).
inline constexpr KernelFeatures kGeneralKernel{};

/// The smallest compiled kernel that covers `effects`.
inline KernelFeatures kernel_for(const SceneEffects& effects) {
  KernelFeatures f;
  f.reflects = effects.has(Effect::Interreflection);
  f.mirror = f.reflects && effects.has(Effect::MirrorReflection);
  f.glossy = f.reflects && effects.has(Effect::GlossyReflection);
  f.glass = f.reflects && effects.has(Effect::Refraction);
  f.grids = effects.has(Effect::GridCrossing) || effects.has(Effect::ObserverCrossing);
  return f;
}

/// Scattering with only the material kinds of F. A kind left out has no surface that returns
/// light (kernel_for), so its photon is absorbed: the general code would draw a number and end
/// the path too, and a path's numbers after its end are never used.
template <KernelFeatures F>
inline bool scatter_with(const Material& m, const vec3& n, vec3& dir, PathRng& rng) {
  if constexpr (F.mirror && F.glossy && F.glass) {
    return scatter(m, n, dir, rng);
  } else {
    const float cos_in = glm::dot(dir, n);
    const vec3 facing = cos_in < 0.0f ? n : -n;
    switch (m.type) {
      case Material::Type::Diffuse:
        return scatter_diffuse(m, facing, dir, rng);
      case Material::Type::Mirror:
        if constexpr (F.mirror) return scatter_mirror(m, facing, dir, rng);
        return false;
      case Material::Type::Glossy:
        if constexpr (F.glossy) return scatter_glossy(m, facing, dir, rng);
        return false;
      case Material::Type::Glass:
        if constexpr (F.glass) return scatter_glass(m, cos_in, facing, dir, rng);
        return false;
    }
    return false;
  }
}

/// The grid test of F (none without grids).
template <KernelFeatures F>
inline void cross_grids_with(const std::vector<PreparedGrid>& grids, const vec3& o, const vec3& d,
                             float t_max, std::uint32_t bounce, PathDeposits& deposits,
                             std::uint32_t first_bounce, bool connected) {
  if constexpr (F.grids) {
    if (!grids.empty()) cross_grids(grids, o, d, t_max, bounce, deposits, first_bounce, connected);
  }
}

namespace kernel_detail {

// Material bits as template arguments, one runtime test each: 16 reflecting variants.
template <bool... Bits, class Fn>
void dispatch_reflecting(const KernelFeatures& f, Fn& fn) {
  constexpr std::size_t kDone = sizeof...(Bits);
  if constexpr (kDone == 4) {
    constexpr bool b[] = {Bits...};
    fn.template operator()<KernelFeatures{true, b[0], b[1], b[2], b[3]}>();
  } else {
    const bool next[] = {f.mirror, f.glossy, f.glass, f.grids};
    if (next[kDone]) {
      dispatch_reflecting<Bits..., true>(f, fn);
    } else {
      dispatch_reflecting<Bits..., false>(f, fn);
    }
  }
}

}  // namespace kernel_detail

/// Calls `fn.template operator()<F>()` with the compiled kernel F equal to `f` (18 variants:
/// 16 reflecting, 2 direct-only). A direct-only `f` must have no material bits set.
template <class Fn>
void with_kernel(const KernelFeatures& f, Fn&& fn) {
  if (!f.reflects) {
    if (f.grids) {
      fn.template operator()<KernelFeatures{false, false, false, false, true}>();
    } else {
      fn.template operator()<KernelFeatures{false, false, false, false, false}>();
    }
    return;
  }
  kernel_detail::dispatch_reflecting(f, fn);
}

}  // namespace lightsolver::detail
