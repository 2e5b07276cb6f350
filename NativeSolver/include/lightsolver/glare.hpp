#pragma once
/// \file glare.hpp
/// Discomfort glare: the Unified Glare Rating (CIE 117-1995) at an observer, and the standard
/// UGR table of a luminaire (CIE 190:2010 tabular method). Conventions and limits:
/// docs/glare.md.
///
///   UGR = 8 log10( (0.25 / L_b) * sum_i L_i^2 omega_i / p_i^2 )
///
/// L_i: luminance of luminaire i's luminous opening toward the eye (cd/m2) = I / A_p, omega_i:
/// its solid angle A_p / r^2 (sr), p_i: Guth position index (CIE 117 Table 4.1), L_b: background
/// luminance (cd/m2), supplied by the caller (the indirect illuminance at the eye / pi).

#include <functional>
#include <glm/vec3.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lightsolver/error.hpp"
#include "lightsolver/photometry.hpp"

namespace lightsolver {

/// Largest H/R and T/R that CIE 117's Table 4.1 covers; beyond them a source is outside the
/// field that counts (about 62 degrees up, 72 degrees to either side).
inline constexpr double kGuthMaxHOverR = 1.9;
inline constexpr double kGuthMaxTOverR = 3.0;

/// Guth position index p from CIE 117-1995 Table 4.1, bilinear between the table's nodes
/// (steps of 0.1 in H/R and T/R). `h_over_r`: height of the source above the line of sight over
/// its distance R along it; `t_over_r`: lateral offset over R (its sign is ignored). Returns
/// nullopt outside the table (H/R < 0 or > 1.9, |T/R| > 3) and where any of the four nodes
/// around the point is one of the table's void entries (hidden by brow and forehead).
std::optional<double> guth_position_index(double h_over_r, double t_over_r);

/// The position index by Levin's closed form (Radiance's glarendx), for comparison only: it is
/// defined everywhere in the upper half field and differs from the table (docs/glare.md).
double levin_position_index(double h_over_r, double t_over_r);

/// An observer: eye position (m), line of sight, and the up direction (made orthogonal to the
/// line of sight). Eye height by convention 1.2 m seated, 1.7 m standing.
struct GlareObserver {
  glm::dvec3 eye_m{0.0, 0.0, 1.2};
  glm::dvec3 view_direction{0.0, 1.0, 0.0};
  glm::dvec3 up{0.0, 0.0, 1.0};
};

/// What a luminaire shows an eye along one direction.
struct ApparentSource {
  double intensity_cd = 0.0;       ///< toward the eye
  double projected_area_m2 = 0.0;  ///< luminous area projected onto the plane normal to it
};

/// A glare source: the centre of its luminous opening and how it looks from a direction.
struct GlareSource {
  std::string name;
  glm::dvec3 centre_m{0.0};
  /// Intensity and projected area toward a unit world direction (from the source to the eye).
  std::function<ApparentSource(const glm::dvec3& toward_eye)> appearance;
};

/// A photometric luminaire as a glare source: intensity from the candela table (interpolated
/// as the sampler does) times `flux_scale`, projected area of the file's luminous opening.
/// `aim` is where gamma = 0 points, `c0` the C0 plane (unit, orthogonal; photometry.hpp).
/// The sampler must outlive the source. Throws InputError if the file gives no luminous area
/// (a point opening: UGR needs the luminance of an area; CIE 117 does not define it).
GlareSource photometric_glare_source(const std::string& name,
                                     std::shared_ptr<const PhotometricData> data,
                                     std::shared_ptr<const PhotometricSampler> sampler,
                                     const glm::dvec3& centre_m, const glm::dvec3& aim,
                                     const glm::dvec3& c0, double flux_scale = 1.0);

/// A one-sided Lambertian emitter of area `area_m2` (an area luminaire's rectangle) facing
/// `normal`: L = flux / (pi A) toward every direction on its emitting side.
GlareSource lambertian_glare_source(const std::string& name, const glm::dvec3& centre_m,
                                    const glm::dvec3& normal, double area_m2, double flux_lm);

/// Projected area (m2) of a photometric file's luminous opening seen along a unit direction
/// in the luminaire frame (shapes as OpeningShape; 0 for a point).
double projected_luminous_area_m2(const PhotometricData& data, const glm::dvec3& direction_local);

/// One luminaire's part in an observer's UGR.
struct GlareContribution {
  std::string name;
  bool counted = false;   ///< inside the field with a position index and a luminance
  std::string why_not;    ///< when not counted: "behind", "below the line of sight", ...
  double h_over_r = 0.0;  ///< geometry (when in front of the eye)
  double t_over_r = 0.0;
  double distance_m = 0.0;
  double luminance_cd_m2 = 0.0;
  double solid_angle_sr = 0.0;
  double position_index = 0.0;
  double term = 0.0;  ///< L^2 omega / p^2
  /// UGR this luminaire alone would give (absent when it is not counted).
  std::optional<double> ugr_alone;
};

/// UGR at one observer.
struct UgrResult {
  /// 8 log10((0.25/L_b) sum): absent when no luminaire counts (no glare from luminaires).
  std::optional<double> ugr;
  double background_luminance_cd_m2 = 0.0;
  double sum = 0.0;  ///< sum of L^2 omega / p^2 over the counted luminaires
  std::vector<GlareContribution> contributions;  ///< one per source, in input order
  /// Sources outside CIE 117's range of validity (solid angle below 0.0003 sr or above
  /// 0.1 sr: CIE 147 applies) and other remarks.
  Warnings warnings;
};

/// UGR at `observer` for `sources` and background luminance `background_luminance_cd_m2`
/// (> 0, finite; otherwise InputError). Sources behind the eye, below its line of sight, out
/// of Table 4.1 or in its void entries, or dark toward the eye do not count.
UgrResult compute_ugr(const GlareObserver& observer, const std::vector<GlareSource>& sources,
                      double background_luminance_cd_m2);

/// Reflectances of a standard room (ceiling, walls, floor cavity = reference plane).
struct RoomReflectances {
  double ceiling = 0.7, walls = 0.5, floor = 0.2;
};

/// Interreflection transfer factors of a box room (CIE 190 Table 5's F_T): flux incident on
/// the walls after interreflection, per lumen that first falls on the floor (`floor_to_walls`),
/// on the walls (`walls_to_walls`, the direct lumen itself excluded) or on the ceiling
/// (`ceiling_to_walls`). Three uniform Lambertian surfaces, exact form factors.
struct WallTransferFactors {
  double floor_to_walls = 0.0, walls_to_walls = 0.0, ceiling_to_walls = 0.0;
};
WallTransferFactors wall_transfer_factors(double x_m, double y_m, double height_m,
                                          const RoomReflectances& rho);

/// Options of the tabular method.
struct UgrTableOptions {
  double spacing_to_height = 0.25;  ///< luminaire spacing / H (data sheets: 0.25)
  double height_m = 2.0;            ///< H, luminaire plane above the eye (scale-free)
  double flux_scale = 1.0;          ///< intensity factor (e.g. PhotometricSampler::flux_scale)
};

/// One room of the table: X (across the line of sight) and Y (along it) in multiples of H,
/// and the UGR for each reflectance combination viewing crosswise (line of sight in the
/// luminaire's C0-C180 plane, CIE 117 eq. 4.5) and endwise (in the C90-C270 plane).
struct UgrTableRow {
  double x_h = 0.0, y_h = 0.0;
  std::vector<std::optional<double>> crosswise, endwise;  ///< one per reflectance combination
  std::vector<double> background_luminance_cd_m2;         ///< per combination (crosswise)
  /// Direct flux of the array on the reference plane over its total flux (crosswise; CIE 190's
  /// F_DF, here integrated exactly rather than from zonal factors).
  double direct_floor_fraction = 0.0;
};

/// The standard UGR table of a luminaire (CIE 190:2010).
struct UgrTable {
  std::vector<RoomReflectances> reflectances;  ///< columns
  std::vector<UgrTableRow> rows;               ///< the 19 standard rooms
  double luminaire_flux_lm = 0.0;              ///< integrated, times flux_scale
  /// Lamp flux CIE 190's correction refers to: the file's lamp lumens (relative photometry) or
  /// the luminaire flux (absolute photometry), times flux_scale. The table's values are for this
  /// flux ("corrected"); CIE 190's 1000 lm values are 8 log10(lamp_flux_lm / 1000) lower.
  double lamp_flux_lm = 0.0;
  double spacing_to_height = 0.25;
  Warnings warnings;
};

/// The five reflectance combinations of CIE 190 data sheets (0.7/0.5/0.2 ... 0.3/0.3/0.2).
std::vector<RoomReflectances> standard_reflectances();

/// Computes the table for `data` at its actual flux (corrected values). Throws InputError if
/// the file gives no luminous area or emits nothing.
UgrTable ugr_table(const PhotometricData& data, const UgrTableOptions& options = {});

/// The table as data sheets print it (rows X, Y; crosswise and endwise columns).
std::string format_ugr_table(const UgrTable& table);

}  // namespace lightsolver
