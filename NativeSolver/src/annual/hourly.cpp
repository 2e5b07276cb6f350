// A year of hours from daylight coefficients (lightsolver/daylight_coefficients.hpp): per grid,
// hours × cells = (hourly patch weights) × (patch coefficients) plus each sun hour's own group,
// and the interval ends' spreads from the groups' squared distances through the squared weights
// (the groups' streams are independent: variances add). Two float products by Eigen.
#include <Eigen/Core>
#include <cmath>
#include <stdexcept>

#include "lightsolver/daylight_coefficients.hpp"
#include "lightsolver/error.hpp"

namespace lightsolver {
namespace {

using RowMatrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using ConstMap = Eigen::Map<const RowMatrix>;

// The hours' weights of the patches: sky[h][p] / (Ω_p L_p), 0 for an untraced patch.
RowMatrix patch_weights(const DaylightCoefficients& dc, const SkyMatrix& y) {
  const SkyPatches patches(dc.mf, dc.north_deg);
  RowMatrix w = ConstMap(y.sky.data(), y.hours, y.patch_count);
  for (int p = 0; p < y.patch_count; ++p) {
    const double l = dc.patch_luminance[p];
    const double scale = l > 0.0 ? 1.0 / (patches.patch(p).solid_angle_sr * l) : 0.0;
    w.col(p) *= static_cast<float>(scale);
  }
  return w;
}

}  // namespace

HourlyIlluminance hourly_illuminance(const DaylightCoefficients& dc, const SkyMatrix& y,
                                     std::size_t grid, bool sun) {
  if (grid >= dc.grids.size()) throw std::out_of_range("hourly_illuminance: no such grid");
  if (y.patch_count != dc.patches || y.mf != dc.mf) {
    throw InputError("", "sky matrix", "its patches are not the coefficients' (MF " +
                                           std::to_string(y.mf) + " vs " +
                                           std::to_string(dc.mf) + ")");
  }
  const CoefficientGrid& g = dc.grids[grid];
  const int cells = static_cast<int>(g.cell_area_m2.size());
  const int groups = static_cast<int>(g.mean.size() / cells);
  const RowMatrix w = patch_weights(dc, y);
  const RowMatrix w2 = w.cwiseProduct(w);
  const ConstMap c(g.mean.data(), groups, cells), lo(g.below.data(), groups, cells),
      hi(g.above.data(), groups, cells);
  const int p = dc.patches;
  RowMatrix mean = w * c.topRows(p);
  RowMatrix var_lo = w2 * lo.topRows(p).cwiseProduct(lo.topRows(p));
  RowMatrix var_hi = w2 * hi.topRows(p).cwiseProduct(hi.topRows(p));
  if (sun) {  // each sun group lights its own hour, at weight 1
    for (std::size_t k = 0; k < dc.sun_hours.size(); ++k) {
      const int h = dc.sun_hours[k], row = p + static_cast<int>(k);
      mean.row(h) += c.row(row);
      var_lo.row(h) += lo.row(row).cwiseProduct(lo.row(row));
      var_hi.row(h) += hi.row(row).cwiseProduct(hi.row(row));
    }
  }
  HourlyIlluminance out;
  out.hours = y.hours;
  out.cells = cells;
  out.cell_area_m2 = g.cell_area_m2;
  const std::size_t n = static_cast<std::size_t>(y.hours) * cells;
  out.mean.resize(n);
  out.spread_low.resize(n);
  out.spread_high.resize(n);
  const float inv_z = static_cast<float>(1.0 / dc.z);
  for (std::size_t i = 0; i < n; ++i) {
    const float m = mean.data()[i];
    out.mean[i] = m > 0.0f ? m : 0.0f;  // float sums of non-negative parts: never below 0
    // Float sums and roots round either way: widened by 1e-6 so no end is narrowed.
    out.spread_low[i] = std::sqrt(var_lo.data()[i]) * inv_z * 1.000001f;
    out.spread_high[i] = std::sqrt(var_hi.data()[i]) * inv_z * 1.000001f;
  }
  return out;
}

}  // namespace lightsolver
