#pragma once
// Sky vectors (docs/daylight.md, "Sky patches and sky vectors"): a sky model integrated over each
// Reinhart patch, the vector that multiplies daylight coefficients, with the sun kept apart.
// Pure mathematics: includes nothing of src/ but daylight/.
#include <glm/vec3.hpp>
#include <vector>

#include "daylight/sky_models.hpp"
#include "lightsolver/sky_patches.hpp"

namespace lightsolver::daylight {

/// How a sky vector is computed.
struct SkyVectorOptions {
  /// Gauss–Legendre points per side of each patch, or of each part of a patch cut at the sun's
  /// altitude and azimuth (where the indicatrix has its kink) and at 6° (where a Perez sky with
  /// b > 0 has its floor): 1 … 32.
  int points = 4;
  /// Radiance's gendaymtx behaviour: the sun's direct normal illuminance shared among the 4
  /// patches with the nearest centres, weighted 1/(1.002 − cos angle), instead of kept apart.
  bool radiance_sun = false;
};

/// One sky as patch values plus the sun.
struct SkyVector {
  /// Per patch (index 0 the ground): ∫ L dω over the patch = mean luminance × solid angle
  /// (cd·sr/m²); with radiance_sun, the sun's share added.
  std::vector<double> patches;
  glm::dvec3 sun_direction{0.0, 0.0, 0.0};  ///< toward the sun, scene frame; 0 without a sun
  double sun_direct_normal_lx = 0.0;        ///< the sun kept apart (0 with radiance_sun or no sun)
  double diffuse_horizontal_lx = 0.0;       ///< the model's own (its quadrature, error < 1e-6)
  /// Σ over sky patches of ∫ L cos Z dω by this quadrature, and its relative difference to the
  /// model's diffuse horizontal illuminance: the quadrature's error, measured every time.
  double horizontal_quadrature_lx = 0.0;
  double quadrature_error = 0.0;
};

/// The sky vector of a sky whose sun (if any) has direct normal illuminance
/// `sun_direct_normal_lx`. The sky's directions are in the patches' scene frame.
SkyVector sky_vector(const Sky& sky, double sun_direct_normal_lx, const SkyPatches& patches,
                     const SkyVectorOptions& options = {});

/// Each patch's ∫ raw dω of a sky form (scale 1, the ground left 0) and Σ over the sky of
/// ∫ raw cos Z dω, by the rule of sky_vector: a sky normalised by its own patches, without the
/// Sky class' fine horizontal integral (a year of skies; sky_matrix).
std::vector<double> raw_patch_integrals(const SkyShape& shape, const Direction& sun,
                                        const SkyPatches& patches, int points,
                                        double& raw_horizontal);

/// gendaymtx's AddDirect: `sun_normal_lx` shared among the 4 sky patches whose centres are
/// nearest `sun`, weighted 1/(1.002 − cos).
void add_sun_as_radiance(std::vector<double>& v, const SkyPatches& patches, const glm::dvec3& sun,
                         double sun_normal_lx);

/// The same from a sky's specification: the sun's direct normal illuminance is the Perez
/// model's (DNI × its direct efficacy, or the given illuminance) or `sun_direct_normal_lx`
/// for the other models; no sun where `spec.sun` is absent or not above the horizon.
SkyVector sky_vector(const SkySpec& spec, const SkyPatches& patches,
                     const SkyVectorOptions& options = {});

}  // namespace lightsolver::daylight
