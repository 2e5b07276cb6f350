#pragma once
/// \file daylight_coefficients.hpp
/// A year of daylight in one trace (docs/daylight.md, "Daylight coefficients"): the scene's sky
/// cut into Reinhart patches (the ground first), each patch a luminaire group of uniform
/// luminance, and the year's sun positions binned into fine Reinhart patches, each bin a sun
/// group at its hours' mean direction, all traced once; every grid counted twice (all light,
/// and light reflected at least once). An hour's illuminance per grid cell is the sky vector
/// times the patches' full coefficients, plus the hour's direct normal illuminance times its sun
/// bin's reflected coefficient, plus the sun's direct beam by shadow rays at the hour's own sun
/// position, with an interval: the groups' (independent photon streams: variances add) and the
/// direct beam's bounds over each cell.

#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lightsolver/scene.hpp"
#include "lightsolver/sky_patches.hpp"
#include "lightsolver/solver.hpp"

namespace lightsolver {

/// How to trace the coefficients.
struct DaylightCoefficientOptions {
  int mf = 1;  ///< Reinhart subdivision of the sky (1: 145 patches + ground, 2: 577, 4: 2305)
  /// The scene frame's true north (from +y, counter-clockwise seen from above); must be the one
  /// the sky matrix was made with.
  double north_deg = 0.0;
  std::uint64_t photons = 20'000'000;  ///< all groups together
  std::optional<std::uint64_t> seed;   ///< default: the scene's settings.seed
  std::string backend = "auto";
  int threads = 0;  ///< 0: all cores
  /// Critical value (two-sided standard normal) of the groups' interval ends the coefficients
  /// keep: the strictest level the annual metrics use (their spreads scale down from it).
  double z = 1.959963984540054;
  /// The direct sun over each cell: shadow rays at the corners of k × k sub-squares.
  int direct_subdivision = 8;
  /// The Reinhart subdivision whose patches bin the year's sun positions for the sun's reflected
  /// light (4: ~3° bins, 410 of them for Chicago).
  int sun_mf = 4;
};

/// One grid's coefficients: rows are the groups (patches, 0 the ground, then sun bins), columns
/// its cells (row by row, index = iv * nu + iu); lux at the group's traced level.
struct CoefficientGrid {
  std::string name;
  std::uint32_t nu = 1, nv = 1;
  std::vector<double> cell_area_m2;
  std::vector<glm::dvec3> cell_centre;  ///< the scene's coordinates
  glm::dvec3 normal{0.0, 0.0, 1.0};     ///< the side the grid counts light arriving on
  /// patches × cells, float32: each group's estimate and its distances down and up to its
  /// interval ends at DaylightCoefficients::z (Wilson or per-path, as every estimate of the
  /// solver), for all light and for light reflected at least once.
  std::vector<float> mean, below, above;
  std::vector<float> reflected_mean, reflected_below, reflected_above;
  /// hours × cells, float32, lx: the sun's direct beam over each cell (shadow rays at the corners
  /// of k × k sub-squares: the mean of each sub-square's corners, and bounds from their minimum
  /// and maximum) and at its centre (IES LM-83's sensor point, for ASE). Empty without sun.
  std::vector<float> direct, direct_low, direct_high, direct_centre;
};

/// The traced coefficients of every grid of the scene.
struct DaylightCoefficients {
  int mf = 1;
  double north_deg = 0.0;
  int patches = 0;  ///< 144 MF² + 2: group p is patch p (0 the ground)
  /// Each patch's traced uniform luminance (cd/m²): the root mean square over the year's sky
  /// hours of its luminance (0: a patch never lit).
  std::vector<double> patch_luminance;
  /// Group patches + b is sun bin b: its direction (toward the sun, the mean of its hours'),
  /// traced at kSunBinLx of direct normal illuminance.
  std::vector<glm::dvec3> sun_bins;
  std::vector<int> sun_bin_of_hour;  ///< per hour, its bin or −1 (no sun)
  static constexpr double kSunBinLx = 1000.0;
  double z = 1.959963984540054;
  std::vector<CoefficientGrid> grids;
  /// The trace's own results (photons, groups and their photons, backend, seconds, warnings,
  /// provenance); its targets are the grids and their reflected-only twins.
  Results trace;
  double direct_seconds = 0.0;  ///< the beam's shadow rays and clipping (once per tracer)
  double setup_seconds = 0.0;   ///< the traced scene's validation and preparation
  /// Bytes of the coefficient and direct-sun arrays.
  std::size_t bytes() const;
};

/// The scene the coefficients are traced in (docs/daylight.md, "Daylight coefficients"): the
/// scene's meshes and materials, its grid targets (as plain illuminance grids) each followed by
/// its reflected-only twin, one sky per patch with the scene's sky's portals (or site) and
/// glazing, and one sun per direction of `sun_bins` through the scene's sun's opening, else the
/// sky's portals, else a square across the beam covering the site. Electric luminaires are left
/// out. InputError naming `luminaires` without exactly one sky, with more than one sun, and
/// `targets` without a grid.
Scene coefficient_scene(const Scene& scene, const SkyMatrix& year,
                        const DaylightCoefficientOptions& options,
                        const std::vector<glm::dvec3>& sun_bins = {});

/// Traces the coefficients: `coefficient_scene`, photons shared by each group's importance over
/// the year (its flux × the root sum of squares of its hourly weights, each hour relative to its
/// global horizontal illuminance), every group's estimate per cell at `options.z`; the direct
/// sun by shadow rays through the scene's sun openings (sun_openings). InputError for a scene as
/// `coefficient_scene`, a sky matrix of another MF, or too few photons for every lit group to
/// get some.
DaylightCoefficients trace_daylight_coefficients(const Scene& scene, const SkyMatrix& year,
                                                 const DaylightCoefficientOptions& options);

/// The same, kept open for more photons (`annual --decide`): each trace() continues the previous
/// one (photon i is photon i: the same as one trace of that many photons with the seed).
class CoefficientTracer {
 public:
  /// InputError as trace_daylight_coefficients.
  CoefficientTracer(const Scene& scene, const SkyMatrix& year,
                    const DaylightCoefficientOptions& options);
  ~CoefficientTracer();
  CoefficientTracer(const CoefficientTracer&) = delete;
  CoefficientTracer& operator=(const CoefficientTracer&) = delete;
  /// Traces up to `photons` in all (at least the previous count) and returns the coefficients
  /// with their ends at `z`.
  /// `processes`: MPI ranks sharing the trace (null: alone).
  DaylightCoefficients trace(std::uint64_t photons, double z, const ProgressFn& progress = {},
                             std::shared_ptr<ProcessGroup> processes = nullptr);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// A grid's illuminance at every hour of the year: hours × cells, row-major, float32.
/// At hour h, cell c the interval at two-sided critical value z is
/// [mean − z·spread_low − direct_below, mean + z·spread_high + direct_above] (its lower end
/// clamped at 0): the spreads are the groups' distances to their ends, each scaled by the
/// hour's weight of the group, root-sum-squared, divided by the z they were taken at (exact
/// scaling for per-path normal ends; conservative for Wilson ends, which widen faster than z,
/// when z is below the coefficients' own); direct_below and direct_above the direct beam's
/// bounds, which do not scale with z.
struct HourlyIlluminance {
  int hours = 0, cells = 0;
  std::vector<float> mean, spread_low, spread_high, direct_below, direct_above;
  std::vector<double> cell_area_m2;
};

/// Grid `grid`'s hourly illuminance: E_h = Σ_p w_hp C_p + (E_n,h / kSunBinLx) R_b(h) + D_h, w_hp
/// the hour's sky vector entry over (Ω_p × the patch's traced luminance), C the patches' full
/// coefficients, R_b the reflected coefficient of the hour's sun bin, D the direct beam. `sun`
/// false: the sky alone (R and D left out, e.g. for blinds that stop the beam).
HourlyIlluminance hourly_illuminance(const DaylightCoefficients& dc, const SkyMatrix& year,
                                     std::size_t grid, bool sun = true);

}  // namespace lightsolver
