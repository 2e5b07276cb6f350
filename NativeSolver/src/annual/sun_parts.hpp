#pragma once
// The sun in a year of daylight coefficients (docs/daylight.md, "Daylight coefficients"): its
// reflected light from a sun group per bin of sun positions, its direct beam over each grid cell
// by shadow rays.
#include <vector>

#include "lightsolver/daylight_coefficients.hpp"

namespace lightsolver {

/// The year's sun positions binned by the Reinhart patch (subdivision `mf`) they fall in: each
/// bin's direction is the mean of its hours' (normalised); `of_hour` is each hour's bin or −1.
struct SunBins {
  std::vector<glm::dvec3> direction;
  std::vector<int> of_hour;
};
SunBins sun_bins(const SkyMatrix& year, int mf, double north_deg);

/// The sun's direct beam over each cell of `grid` at every hour of `year` into `out.direct*`.
/// Shadow rays (direct_sun_lx, through the scene's sun openings) at the corners of k × k
/// sub-squares of every cell. Where every corner reads what the openings alone give (each
/// opening's beam carried onto the grid's plane: a quadrilateral), the cell's value is exact:
/// each beam's area over the cell, clipped (no interval). Elsewhere (something else shades the
/// cell, an opening reaches below the plane, or the site has no openings) it is the mean over
/// the sub-squares of their corners' mean, with bounds from their minimum and maximum (exact
/// while no shadow edge crosses a sub-square twice). `direct_centre`: the value at the cell's
/// centre (k even: a corner; else its own ray). `scene` validated. Nothing without sun hours.
void direct_sun_cells(const Scene& scene, const Target& grid, const SkyMatrix& year, int k,
                      CoefficientGrid& out);

}  // namespace lightsolver
