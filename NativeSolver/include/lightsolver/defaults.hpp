#pragma once
/// \file defaults.hpp
/// File-format tags and material defaults (docs/scene-format.md), defined once. The scene
/// reader, the in-memory Material, the results writers and the Python module take them from
/// here; Python sees them as `lightsolver.SCENE_FORMAT`, `RESULTS_FORMAT`,
/// `OPTIMIZATION_FORMAT` and `material_defaults()`, which the workbench's exporter uses.

namespace lightsolver {

/// `format` of a scene file.
inline constexpr const char* kSceneFormat = "lightsolver.scene/1";
/// `format` of a results file (CLI `--out`, `lightsolver.solve()`).
inline constexpr const char* kResultsFormat = "lightsolver.results/1";
/// `format` of an optimization result (`lightsolver optimize --out`, `lightsolver.optimize()`).
inline constexpr const char* kOptimizationFormat = "lightsolver.optimization/1";

/// Values a material gets for the keys a scene file leaves out, per material type.
namespace material_defaults {
inline constexpr double kDiffuseReflectance = 0.5;  ///< diffuse: Lambertian albedo
inline constexpr double kMirrorReflectance = 0.9;   ///< mirror: specular albedo
inline constexpr double kGlossyReflectance = 0.0;   ///< glossy: Lambertian base under the lobe
inline constexpr double kGlossySpecular = 0.5;      ///< glossy: lobe albedo
inline constexpr double kGlossyRoughness = 0.2;     ///< glossy: roughness, GGX alpha = r^2
inline constexpr double kGlassIor = 1.52;           ///< glass: refractive index (soda-lime)
inline constexpr double kGlassTransmittance = 1.0;  ///< glass: internal transmittance of a pass
inline constexpr bool kGlassThin = false;           ///< glass: a solid body, not one sheet
}  // namespace material_defaults

}  // namespace lightsolver
