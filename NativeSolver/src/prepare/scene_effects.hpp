#pragma once
// Which effects a prepared scene needs: reflection by material kind, refraction, the target
// kinds and the luminaire types (one emission effect per row of luminaire_types.cpp). One analysis
// for both tracers: the Embree backend picks its specialised path kernel from it
// (embree/path_kernel.hpp), the Vulkan backend its specialisation constants (vulkan/gpu_scene.cpp),
// and the results list what was simulated and what was skipped, with the reason.
#include <array>
#include <cstdint>
#include <string>

#include "types/luminaire_types.hpp"
#include "model/prepared_scene.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver::detail {

/// Every effect a photon path may need, in the order results list them.
enum class Effect : std::uint8_t {
  Interreflection,    ///< some surface returns light: paths go on after their first hit
  DiffuseReflection,  ///< a diffuse material with reflectance > 0
  MirrorReflection,   ///< a mirror with reflectance > 0
  GlossyReflection,   ///< a glossy material (GGX lobe) with reflectance + specular > 0
  Refraction,         ///< glass: Fresnel reflection, refraction, internal transmittance
  SurfaceTargets,     ///< deposits on target meshes
  GridCrossing,       ///< the virtual-grid test per segment
  ObserverCrossing,   ///< indirect-only grids (observers' eyes)
  Instancing,         ///< movable meshes behind Embree instances
  LuminaireChoice,    ///< several luminaires: the flux CDF is searched per photon
  NextEventDirect,    ///< direct light at targets by shadow rays (estimate/next_event.hpp)
  /// reflected light at grids by connections (estimate/reflection_connection.hpp)
  ReflectionConnection,
  /// Then one emission effect per luminaire type, in the rows' order (emission_effect()):
  /// each row names its own (LuminaireType::effect).
  kFirstEmission
};

/// How many effects there are: the fixed ones, then one per luminaire type.
std::size_t effect_count();
/// Room for every effect (SceneEffects' tables).
inline constexpr std::size_t kMaxEffects =
    static_cast<std::size_t>(Effect::kFirstEmission) + kMaxLuminaireTypes;

/// The effect of emitting from luminaires of `type` ("spot_emission").
Effect emission_effect(Luminaire::Type type);

/// The name results use for `e` ("refraction", "mirror_reflection"...).
const char* effect_name(Effect e);

/// The effects a scene needs, and for each one it does not need, why.
class SceneEffects {
 public:
  bool has(Effect e) const { return on_[index(e)]; }
  /// Why `e` is not simulated ("no glass"); empty when it is.
  const std::string& reason(Effect e) const { return reasons_[index(e)]; }
  void set(Effect e, bool on, std::string reason_if_off);

 private:
  static std::size_t index(Effect e) { return static_cast<std::size_t>(e); }
  std::array<bool, kMaxEffects> on_{};
  std::array<std::string, kMaxEffects> reasons_;
};

/// Analyses a prepared scene. Only meshes with triangles count (an empty mesh is never hit).
SceneEffects analyse_effects(const PreparedScene& scene);

/// The list for Results::effects.
EffectsReport effects_report(const SceneEffects& effects);

}  // namespace lightsolver::detail
