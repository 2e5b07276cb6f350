#pragma once
/// \file photometry.hpp
/// Photometric files (IES LM-63 1986/1991/1995/2002/2019 and EULUMDAT .ldt), their common
/// in-memory form, and an exact emission sampler. Conventions: docs/photometry.md.
///
/// Luminaire frame (metres, right-handed): gamma = 0 (nadir, the aim) points to -z, the C0
/// plane toward +x, C90 toward +y (C angles counter-clockwise seen from above, i.e. from +z).
/// The luminous opening lies in z = 0 and emits toward -z; its length runs along x (the C0-C180
/// plane), its width along y. Types A and B put their photometric zero (H = 0, V = 0) on -z too:
///   type C: d = ( sin g cos C,  sin g sin C, -cos g)
///   type B: d = ( cos H sin V,  sin H,       -cos H cos V)   (polar axis y)
///   type A: d = ( sin V,        cos V sin H, -cos V cos H)   (polar axis x)
/// To place a luminaire with world vectors `aim` (gamma = 0) and `c0` (orthonormal):
/// world = x * c0 + y * cross(c0, aim) + z * (-aim); see to_world().

#include <cstddef>
#include <glm/vec3.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "lightsolver/error.hpp"
#include "lightsolver/rng.hpp"

namespace lightsolver {

/// Goniometer system of the data (LM-63 photometric type 1 = C, 2 = B, 3 = A).
enum class PhotometricType { C, B, A };

/// File format the data came from.
enum class PhotometricFormat { Ies, Eulumdat };

/// Symmetry the file declared (the stored data are unfolded whatever it is).
enum class PhotometricSymmetry {
  None,              ///< full data (type C 0..360; types A, B -90..90)
  Rotational,        ///< one plane, same in every C plane
  BilateralC0C180,   ///< mirror about the C0-C180 plane (I(C) = I(360 - C))
  BilateralC90C270,  ///< mirror about the C90-C270 plane (I(C) = I(180 - C))
  Quadrant,          ///< both mirrors (data 0..90)
  LateralAB,         ///< types A, B: mirror about H = 0 (data H 0..90)
};

/// Luminous opening shape (LM-63 width/length/height signs, EULUMDAT luminous area).
enum class OpeningShape {
  Point,
  Rectangle,
  Box,
  Disk,                   ///< circle or ellipse (length x width)
  VerticalCylinder,       ///< circular or elliptical footprint, height along z
  Sphere,                 ///< sphere or ellipsoid
  HorizontalCylinderC0,   ///< axis along x (C0)
  HorizontalCylinderC90,  ///< axis along y (C90)
  VerticalDisk,           ///< vertical circle or ellipse facing C0 (in the y-z plane)
};

/// TILT data of an IES file: lamp output multiplier against the luminaire's tilt from its
/// measured attitude (type C: from aimed straight down).
struct TiltData {
  int lamp_geometry = 0;  ///< 1 vertical base-up/down, 2 horizontal in C0, 3 horizontal in C90
  std::vector<double> angles_deg;
  std::vector<double> factors;

  /// Multiplier at `tilt_deg`: linear between the table's angles, the end value beyond either
  /// end (LM-63 defines no extrapolation), 1 without a table.
  double factor_at(double tilt_deg) const;
};

/// A luminous intensity distribution, whichever file it came from.
struct PhotometricData {
  std::string source_file;  ///< for messages
  PhotometricFormat format = PhotometricFormat::Ies;
  std::string format_version;  ///< "LM-63-1986" ... "LM-63-2019", "EULUMDAT"
  /// IES keywords in file order ("TEST", "MANUFAC", ...; [MORE] lines appended to the one
  /// before), or the named EULUMDAT header fields.
  std::vector<std::pair<std::string, std::string>> keywords;

  PhotometricType type = PhotometricType::C;
  PhotometricSymmetry symmetry = PhotometricSymmetry::None;
  /// Unfolded angles, strictly increasing. Type C: C from 0 to 360 inclusive (a copy of C0 at
  /// 360). Types A, B: H with the mirrored half added. Outside the vertical range I = 0.
  std::vector<double> horizontal_angles_deg;
  std::vector<double> vertical_angles_deg;  ///< gamma (type C) or V (types A, B)
  /// Absolute candela (file value x multiplier x ballast factor [x ballast-lamp factor]),
  /// index h * vertical_angles_deg.size() + v.
  std::vector<double> candela;

  bool absolute_photometry = false;  ///< IES lumens = -1, or EULUMDAT negative lamp count
  /// Lumens the file states: total lamp lumens (relative photometry); for absolute photometry
  /// the luminaire lumens where the file gives them (EULUMDAT), else 0.
  double rated_lumens_lm = 0.0;
  int lamp_count = 1;
  double candela_multiplier = 1.0;  ///< IES multiplier, or EULUMDAT conversion factor
  double ballast_factor = 1.0;
  double ballast_lamp_factor = 1.0;   ///< applied for LM-63-1986..1995 only
  double file_generation_type = 0.0;  ///< LM-63-2019 field (0 when absent)
  double input_watts = 0.0;  ///< IES input watts; EULUMDAT the lamp sets' wattage incl. ballast
  double light_output_ratio_percent = 0.0;      ///< EULUMDAT LORL (0 when unknown)
  double downward_flux_fraction_percent = 0.0;  ///< EULUMDAT DFF (0 when unknown)

  OpeningShape opening_shape = OpeningShape::Point;
  double opening_length_m = 0.0;  ///< extent along x (C0)
  double opening_width_m = 0.0;   ///< extent along y (C90)
  double opening_height_m = 0.0;  ///< extent along z

  std::string tilt = "NONE";  ///< "NONE", "INCLUDE" or the tilt file name
  TiltData tilt_data;
  Warnings warnings;  ///< non-fatal remarks (odd opening sizes, ignored fields)

  /// Candela at unfolded grid node (h, v).
  double candela_at(std::size_t h, std::size_t v) const {
    return candela[h * vertical_angles_deg.size() + v];
  }
};

/// Largest candela table accepted (values); bigger files are refused to bound memory.
inline constexpr std::size_t kMaxPhotometricValues = 1'000'000;

/// Reads an IES (.ies) or EULUMDAT (.ldt) file, chosen by extension (case-insensitive) or, for
/// other names, by content. Throws InputError naming the file and line.
PhotometricData load_photometry(const std::string& path);

/// Parses IES LM-63 text. `source_name` is used in messages. A `TILT=<file>` line is resolved
/// against `tilt_directory`; without one it is an error (in-memory text has no directory).
PhotometricData parse_ies(std::string_view text, const std::string& source_name,
                          const std::optional<std::string>& tilt_directory = std::nullopt);

/// Parses EULUMDAT text. `source_name` is used in messages.
PhotometricData parse_ldt(std::string_view text, const std::string& source_name);

/// Table-driven description of the sampler, for backends that re-implement it (GLSL).
/// Directions are d = cos(t) pole + sin(t) (cos(p) zero + sin(p) ninety) for plane angle p
/// and polar angle t; intensity is bilinear in (p, t) on the grid below, zero outside it.
struct SamplerTables {
  std::vector<double> plane_deg;   ///< p nodes (type C: C; A: H; B: V)
  std::vector<double> polar_deg;   ///< t nodes (type C: gamma; A: V + 90; B: H + 90)
  std::vector<double> candela;     ///< [i_plane * polar_deg.size() + j_polar]
  std::vector<double> cell_cdf;    ///< cumulative cell flux (lm), cell = i * (nt - 1) + j
  std::vector<double> cell_bound;  ///< max of I * sin(t) over each cell (rejection bound)
  bool periodic = false;           ///< type C: plane angle wraps at 360
  glm::dvec3 pole{0, 0, -1}, zero{1, 0, 0}, ninety{0, 1, 0};
};

/// Samples emission exactly from a distribution: a cell of the (plane, polar) grid by its flux
/// (the exact integral of the bilinear patch times sin t), then a direction inside the cell by
/// rejection against I * sin t. Every sample carries equal power. Immutable, thread-safe.
class PhotometricSampler {
 public:
  /// Throws InputError when the distribution emits nothing.
  explicit PhotometricSampler(const PhotometricData& data);

  /// Unit direction in the luminaire frame, distributed as I(d) dOmega.
  glm::dvec3 sample_direction(PathRng& rng) const;

  /// Point on the luminous opening (metres, luminaire frame, z = 0): uniform over its
  /// projection onto z = 0 (rectangle, ellipse, or the centre for a point source).
  glm::dvec3 sample_origin(PathRng& rng) const;

  /// File candela (interpolated as sampled) toward a direction in the luminaire frame; need
  /// not be normalised. Multiply by flux_scale() for a scaled luminaire.
  double intensity_cd(const glm::dvec3& direction_local) const;

  /// Flux of the interpolated distribution, integral of I dOmega (lm).
  double integrated_flux_lm() const { return total_flux_lm_; }

  /// Intensity factor for a requested flux: flux_lm / rated lamp lumens (relative photometry)
  /// or flux_lm / integrated flux (absolute photometry); 1 without flux_lm (file candela).
  /// Throws InputError for a negative or non-finite flux_lm.
  double flux_scale(std::optional<double> flux_lm) const;

  /// Flux actually emitted for a requested flux: integrated_flux_lm() * flux_scale(flux_lm).
  double emitted_flux_lm(std::optional<double> flux_lm) const;

  /// The lookup and sampling tables (for the GPU backends).
  const SamplerTables& tables() const { return tables_; }

 private:
  SamplerTables tables_;
  double total_flux_lm_ = 0.0;
  bool absolute_ = false;
  double rated_lumens_lm_ = 0.0;
  std::string source_file_;
  bool footprint_round_ = false;
  double length_m_ = 0.0, width_m_ = 0.0;
};

/// Luminaire-frame vector to world, given where gamma = 0 points (`aim`) and where the C0
/// plane points (`c0`), both unit and orthogonal.
inline glm::dvec3 to_world(const glm::dvec3& local, const glm::dvec3& aim, const glm::dvec3& c0) {
  const glm::dvec3 c90{c0.y * aim.z - c0.z * aim.y, c0.z * aim.x - c0.x * aim.z,
                       c0.x * aim.y - c0.y * aim.x};  // cross(c0, aim)
  return local.x * c0 + local.y * c90 - local.z * aim;
}

/// The numbers of a distribution the workbench and reports show (NaN where undefined).
struct PhotometryFacts {
  double rated_lumens_lm = 0.0;      ///< as PhotometricData::rated_lumens_lm
  bool absolute_photometry = false;  ///< the file's candela are absolute (no lamp lumens)
  int lamp_count = 1;
  double integrated_lumens_lm = 0.0;  ///< integral of the interpolated candela, I dOmega
  double peak_cd = 0.0;               ///< largest candela value of the table
  double peak_horizontal_deg = 0.0;   ///< its C (type C) or H angle
  double peak_vertical_deg = 0.0;     ///< its gamma (type C) or V angle
  /// Full angles where the intensity falls to 50 % (beam) and 10 % (field) of the peak, along
  /// the great circles through the aim and C0 ([0]; types A, B: H = 0) and C90 ([1]; V = 0).
  double beam_angle_deg[2] = {0.0, 0.0};
  double field_angle_deg[2] = {0.0, 0.0};
};

/// Lumens, peak and spreads of a distribution (the numbers photometry_summary() prints).
PhotometryFacts photometry_facts(const PhotometricData& data);

/// Human-readable summary: format, type, symmetry, lumens from the file and from integration,
/// peak candela and its direction, beam (50 %) and field (10 %) angles in the two main planes.
std::string photometry_summary(const PhotometricData& data);

/// Writes a polar intensity diagram (PNG) of the C0-C180 and C90-C270 planes (types A, B: the
/// V and H planes through the aim). Throws std::runtime_error if the file cannot be written.
void write_polar_plot_png(const PhotometricData& data, const std::string& path);

/// Short names for messages and summaries.
const char* to_string(PhotometricType type);
const char* to_string(PhotometricSymmetry symmetry);
const char* to_string(OpeningShape shape);

}  // namespace lightsolver
