#pragma once
/// \file daylight_coefficients.hpp
/// A year of daylight in one trace (docs/daylight.md, "Daylight coefficients"): the scene's sky
/// cut into Reinhart patches (the ground first), each patch a luminaire group of uniform
/// luminance, and the sun of every sun hour of the year its own group; one trace of all of them,
/// then each hour's illuminance per grid cell is the sky vector times the patches' coefficients
/// plus the hour's sun group, with an interval from the groups' own (independent photon streams:
/// their variances add).

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
};

/// One grid's coefficients: rows are the groups (patches, then sun hours), columns its cells
/// (row by row, index = iv * nu + iu); lux at the group's traced level.
struct CoefficientGrid {
  std::string name;
  std::uint32_t nu = 1, nv = 1;
  std::vector<double> cell_area_m2;
  std::vector<glm::dvec3> cell_centre;  ///< the scene's coordinates
  glm::dvec3 normal{0.0, 0.0, 1.0};     ///< the side the grid counts light arriving on
  /// groups × cells, float32: each group's estimate and its distances down and up to its interval
  /// ends at DaylightCoefficients::z (Wilson or per-path, as every estimate of the solver).
  std::vector<float> mean, below, above;
};

/// The traced coefficients of every grid of the scene.
struct DaylightCoefficients {
  int mf = 1;
  double north_deg = 0.0;
  int patches = 0;  ///< 144 MF² + 2: group p < patches is patch p (0 the ground)
  /// Each patch's traced uniform luminance (cd/m²): the root mean square of its luminance over
  /// the year's sky hours (0: a patch never lit, not traced).
  std::vector<double> patch_luminance;
  /// Group patches + k is the sun of hour sun_hours[k], traced at that hour's direct normal
  /// illuminance (so its weight in that hour is 1).
  std::vector<int> sun_hours;
  double z = 1.959963984540054;
  std::vector<CoefficientGrid> grids;
  /// The trace's own results (photons, groups and their photons, backend, seconds, warnings,
  /// provenance); its targets are the grids, its groups the patches and suns.
  Results trace;
  /// Bytes of the coefficient arrays.
  std::size_t bytes() const;
  std::size_t groups() const { return static_cast<std::size_t>(patches) + sun_hours.size(); }
};

/// The scene the coefficients are traced in (docs/daylight.md, "Daylight coefficients"): the
/// scene's meshes and materials, its grid targets (as plain illuminance grids), one sky per
/// patch with the scene's sky's portals (or site) and glazing, and one sun per hour of `year`
/// with its sun up and light in its beam, through the scene's sun's opening, else the sky's
/// portals, else a square across the beam covering the sky's site. Electric luminaires are left
/// out. InputError naming `luminaires` without exactly one sky, with more than one sun, and
/// `targets` without a grid.
Scene coefficient_scene(const Scene& scene, const SkyMatrix& year,
                        const DaylightCoefficientOptions& options);

/// Traces the coefficients: `coefficient_scene`, photons shared by each group's importance over
/// the year (its flux × the root sum of squares of its hourly weights, each hour relative to its
/// global horizontal illuminance), every group's estimate per cell at `options.z`. InputError for
/// a scene as `coefficient_scene`, a sky matrix of another MF or north, or too few photons for
/// every lit group to get some.
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
  DaylightCoefficients trace(std::uint64_t photons, double z);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// A grid's illuminance at every hour of the year: hours × cells, row-major, float32.
/// At hour h, cell c the interval at two-sided critical value z is [mean − z·spread_low,
/// mean + z·spread_high] (its lower end clamped at 0): the groups' distances to their ends,
/// each scaled by the hour's weight of the group, root-sum-squared, divided by the z they were
/// taken at (exact scaling for per-path normal ends; conservative for Wilson ends, which widen
/// faster than z, when z is below the coefficients' own).
struct HourlyIlluminance {
  int hours = 0, cells = 0;
  std::vector<float> mean, spread_low, spread_high;
  std::vector<double> cell_area_m2;
};

/// Grid `grid`'s hourly illuminance: E[h] = Σ_p w_hp C_p + C_sun(h), w_hp the hour's sky vector
/// entry over (Ω_p × the patch's traced luminance). `sun` false: the sky alone (the sun's groups
/// left out, e.g. for blinds that stop the beam).
HourlyIlluminance hourly_illuminance(const DaylightCoefficients& dc, const SkyMatrix& year,
                                     std::size_t grid, bool sun = true);

}  // namespace lightsolver
