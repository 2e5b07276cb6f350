#pragma once
/// \file sky_patches.hpp
/// Reinhart sky patches and a year of sky vectors (docs/daylight.md, "Sky patches and sky
/// vectors"): the groundwork of daylight coefficients (issue 27).
///
/// Patches are numbered as Radiance's `reinhart.cal` / `reinsrc.cal` / `gendaymtx` number
/// them, so that our matrices compare with Radiance's row for row: index 0 is the ground (the
/// whole lower hemisphere), then the rows of the sky from the horizon up, each row's patches by
/// azimuth from north toward east (clockwise seen from above), patch 0 of a row centred on north;
/// the last index is the zenith cap. With subdivision MF the rows are alpha = 90° / (7 MF + 0.5)
/// high, row r (0 … 7 MF − 1) has MF × (30, 30, 24, 24, 18, 12, 6)[r / MF] patches and the cap
/// spans the last alpha / 2: 145 sky patches for MF 1 (Tregenza's), 577 for MF 2, 2305 for
/// MF 4, plus the ground.

#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <vector>

#include "lightsolver/daylight.hpp"

namespace lightsolver {

struct WeatherFile;

/// One sky patch (or the ground, index 0).
struct SkyPatch {
  int row = -1;                    ///< 0 … 7 MF from the horizon up; −1 for the ground
  double altitude_min_deg = 0.0;   ///< the band's lower edge (−90 for the ground)
  double altitude_max_deg = 0.0;   ///< its upper edge (0 for the ground, 90 for the cap)
  double azimuth_deg = 0.0;        ///< centre, from north toward east, [0, 360)
  double azimuth_width_deg = 0.0;  ///< 360 / patches in the row (360 for the cap and ground)
  double solid_angle_sr = 0.0;     ///< exact: width × (sin alt_max − sin alt_min)
  /// (1/Ω) ∫ max(0, cos Z) dω over the patch: the daylight coefficient of an unobstructed
  /// upward-facing horizontal sensor for a patch of uniform luminance, (sin a0 + sin a1) / 2
  /// (0 for the ground).
  double mean_cos_zenith = 0.0;
  /// The centre direction in the scene's frame (unit): Radiance's patch centre, at the middle
  /// altitude and azimuth of the patch; the zenith for the cap, the nadir for the ground.
  glm::dvec3 centre{0.0, 0.0, 1.0};
};

/// The Reinhart subdivision of the sky for a subdivision MF >= 1, in a scene frame whose true
/// north is `north_deg` from +y, counter-clockwise seen from above (docs/daylight.md, "Sun"):
/// north (−sin n, cos n, 0), east (cos n, sin n, 0), z up. With north_deg 0 this is Radiance's
/// frame (+y north, +x east).
class SkyPatches {
 public:
  /// Throws InputError naming `mf` (below 1 or above 64) or `north_deg` (not finite).
  explicit SkyPatches(int mf, double north_deg = 0.0);

  int mf() const { return mf_; }
  double north_deg() const { return north_deg_; }
  /// Patches including the ground: 144 MF² + 2.
  int count() const { return static_cast<int>(patches_.size()); }
  /// Sky rows including the cap: 7 MF + 1.
  int rows() const { return 7 * mf_ + 1; }
  /// Row height in degrees, 90 / (7 MF + 0.5).
  double alpha_deg() const { return alpha_deg_; }
  const SkyPatch& patch(int index) const { return patches_.at(static_cast<std::size_t>(index)); }
  const std::vector<SkyPatch>& patches() const { return patches_; }
  /// The patch a direction (scene frame, any length > 0) falls in, by reinhart.cal's rule:
  /// below the horizon (z < 0) the ground, 0; else row floor(altitude / alpha) and in it the
  /// patch whose azimuth range [centre − w/2, centre + w/2) holds the direction's azimuth.
  /// Throws InputError for a zero or non-finite direction.
  int index(const glm::dvec3& direction) const;
  /// Altitude and azimuth (degrees, azimuth from north toward east) of a scene direction.
  void altitude_azimuth(const glm::dvec3& direction, double& altitude_deg,
                        double& azimuth_deg) const;
  /// The scene direction at an altitude and azimuth (degrees).
  glm::dvec3 direction(double altitude_deg, double azimuth_deg) const;
  /// The same from the altitude's and the azimuth's cosines and sines, for callers that share
  /// them between many directions (a quadrature's rows and columns); the same bits as above.
  glm::dvec3 direction(double cos_altitude, double sin_altitude, double cos_azimuth,
                       double sin_azimuth) const;

 private:
  int mf_ = 1;
  double north_deg_ = 0.0;
  double cos_north_ = 1.0, sin_north_ = 0.0;  ///< of north_deg_, for the rotations
  double alpha_deg_ = 0.0;
  std::vector<int> row_start_;  ///< first index of each row (rows() + 1 entries)
  std::vector<SkyPatch> patches_;
};

/// Options of a year of sky vectors.
struct SkyMatrixOptions {
  int mf = 1;                       ///< Reinhart subdivision
  double north_deg = 0.0;           ///< the scene frame's north (see SkyPatches)
  double ground_reflectance = 0.2;  ///< the ground patch's ρ_g
  /// false: the Perez sky from the file's irradiance columns (W/m², direct normal and diffuse
  /// horizontal) with Perez' luminous efficacies, as Radiance's epw2wea + gendaymtx; true: from
  /// its illuminance columns (lx).
  bool use_illuminance = false;
  /// false: the sun kept apart (sun_direct_normal_lx and sun_direction per hour); true:
  /// gendaymtx's behaviour, the sun's direct normal illuminance shared among the 4 patches
  /// whose centres are nearest to it, weighted 1/(1.002 − cos), and no separate sun.
  bool radiance_sun = false;
  int points = 4;  ///< Gauss–Legendre points per side of each patch (or part of a patch)
  SunOptions sun;  ///< refraction etc. of the sun's position
};

/// A year of skies: one row per hour of the weather file.
struct SkyMatrix {
  int mf = 1;
  int patch_count = 0;  ///< columns: 144 MF² + 2 (ground first)
  int hours = 0;        ///< rows: the file's hours (8760 or 8784)
  /// hours × patch_count, row-major, float32: each patch's mean luminance × its solid angle
  /// (cd·sr/m² = lm/m²), the vector that multiplies daylight coefficients (lx per cd·sr/m²).
  std::vector<float> sky;
  /// hours × 3: the unit direction toward the sun (scene frame) at the middle of the hour;
  /// (0, 0, 0) where the hour has no sun vector (night, or no diffuse light).
  std::vector<float> sun_direction;
  /// The sun's direct normal illuminance (lx, Perez' direct efficacy × DNI, or the file's
  /// illuminance column); 0 where the sun is below the horizon, when radiance_sun puts it into
  /// the patches, or where the hour has no diffuse light.
  std::vector<float> sun_direct_normal_lx;
  std::vector<float> sun_altitude_deg;  ///< at the middle of the hour, refraction as asked
  /// The model's diffuse horizontal illuminance (lx), 0 for a dark hour.
  std::vector<float> diffuse_horizontal_lx;
  /// 0: the sun below the horizon at the middle of the hour (zero row); 1: the sun up but no
  /// diffuse light in the file (zero row, as gendaymtx); 2: a Perez sky.
  std::vector<std::uint8_t> status;
  /// Largest relative difference, over the hours, between the patches' quadrature of the
  /// horizontal illuminance and the model's own (docs/daylight.md): the quadrature's error.
  double max_quadrature_error = 0.0;
  /// Bytes held by the arrays above.
  std::size_t bytes() const;
};

/// The sky vectors of every hour of a weather file (docs/daylight.md, "A year of skies"): the
/// sun at the middle of each hour (EPW rows describe the hour ending at their time stamp,
/// local standard time: row hour h → h − 0.5), the Perez all-weather sky from the hour's
/// direct normal and diffuse horizontal values. InputError naming the file, line and column
/// where an hour with the sun up has a missing value the sky needs, and naming the option
/// (`mf`, `points`, `ground_reflectance`) when one is out of range. The hours' skies are
/// computed in parallel (in the caller's TBB arena); the result does not depend on the threads.
SkyMatrix sky_matrix(const WeatherFile& weather, const SkyMatrixOptions& options = {});

}  // namespace lightsolver
