// A year of hours from daylight coefficients (lightsolver/daylight_coefficients.hpp): per grid,
// hours × cells = (hourly sky weights) × (the patches' full coefficients) + the hour's sun bin's
// reflected coefficient + the direct beam. The interval ends' spreads come from the groups'
// squared distances through the squared weights (the groups' streams are independent: variances
// add). Two float products by Eigen, then one sun row per hour.
#include <Eigen/Core>
#include <cmath>
#include <stdexcept>

#include "annual/sun_parts.hpp"
#include "lightsolver/daylight_coefficients.hpp"
#include "lightsolver/error.hpp"

namespace lightsolver {
namespace {

using RowMatrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using ConstMap = Eigen::Map<const RowMatrix>;

// sky[h][p] / (Ω_p L_p): the weight of patch p's coefficient at hour h; 0 for an untraced patch.
std::vector<double> patch_scale(const DaylightCoefficients& dc, const SkyPatches& patches) {
  std::vector<double> s(dc.patches, 0.0);
  for (int p = 0; p < dc.patches; ++p) {
    const double l = dc.patch_luminance[p];
    if (l > 0.0) s[p] = 1.0 / (patches.patch(p).solid_angle_sr * l);
  }
  return s;
}

RowMatrix sky_weights(const SkyMatrix& y, const std::vector<double>& scale) {
  RowMatrix w = ConstMap(y.sky.data(), y.hours, y.patch_count);
  for (int p = 0; p < y.patch_count; ++p) w.col(p) *= static_cast<float>(scale[p]);
  return w;
}

struct Hours {
  RowMatrix mean, var_lo, var_hi;
};

// The sun's reflected light at hour h: its bin's reflected coefficient at E_n / kSunBinLx (the
// bin is its own group: its variance adds).
void add_sun(Hours& out, int h, int bin, float u, int patches, const CoefficientGrid& g,
             int cells) {
  const std::size_t row = std::size_t(patches + bin) * cells;
  for (int c = 0; c < cells; ++c) {
    out.mean(h, c) += u * g.reflected_mean[row + c];
    const float lo = u * g.reflected_below[row + c], hi = u * g.reflected_above[row + c];
    out.var_lo(h, c) += lo * lo;
    out.var_hi(h, c) += hi * hi;
  }
}

}  // namespace

HourlyIlluminance hourly_illuminance(const DaylightCoefficients& dc, const SkyMatrix& y,
                                     std::size_t grid, bool sun) {
  if (grid >= dc.grids.size()) throw std::out_of_range("hourly_illuminance: no such grid");
  if (y.patch_count != dc.patches || y.mf != dc.mf ||
      static_cast<int>(dc.sun_bin_of_hour.size()) != y.hours) {
    throw InputError("", "sky matrix",
                     "its patches are not the coefficients' (MF " + std::to_string(y.mf) + " vs " +
                         std::to_string(dc.mf) + ")");
  }
  const CoefficientGrid& g = dc.grids[grid];
  const int cells = static_cast<int>(g.cell_area_m2.size()), p = dc.patches;
  const SkyPatches patches(dc.mf, dc.north_deg);
  const std::vector<double> scale = patch_scale(dc, patches);
  const RowMatrix w = sky_weights(y, scale);
  const RowMatrix w2 = w.cwiseProduct(w);
  // The patches' rows (the first p; the sun bins' follow).
  const ConstMap c(g.mean.data(), p, cells), lo(g.below.data(), p, cells),
      hi(g.above.data(), p, cells);
  Hours hrs{w * c, w2 * lo.cwiseProduct(lo), w2 * hi.cwiseProduct(hi)};
  const bool direct = sun && !g.direct.empty();
  if (sun) {
    for (int h = 0; h < y.hours; ++h) {
      const int bin = dc.sun_bin_of_hour[h];
      if (bin < 0) continue;
      const float u =
          static_cast<float>(y.sun_direct_normal_lx[h] / DaylightCoefficients::kSunBinLx);
      add_sun(hrs, h, bin, u, p, g, cells);
    }
  }
  HourlyIlluminance out;
  out.hours = y.hours;
  out.cells = cells;
  out.cell_area_m2 = g.cell_area_m2;
  const std::size_t n = static_cast<std::size_t>(y.hours) * cells;
  for (auto* v :
       {&out.mean, &out.spread_low, &out.spread_high, &out.direct_below, &out.direct_above}) {
    v->assign(n, 0.0f);
  }
  const float inv_z = static_cast<float>(1.0 / dc.z);
  for (std::size_t i = 0; i < n; ++i) {
    const float d = direct ? g.direct[i] : 0.0f;
    const float m = hrs.mean.data()[i] + d;
    out.mean[i] = m > 0.0f ? m : 0.0f;  // float sums of non-negative parts: never below 0
    // Float sums and roots round either way: widened by 1e-6 so no end is narrowed.
    out.spread_low[i] = std::sqrt(std::max(0.0f, hrs.var_lo.data()[i])) * inv_z * 1.000001f;
    out.spread_high[i] = std::sqrt(std::max(0.0f, hrs.var_hi.data()[i])) * inv_z * 1.000001f;
    if (direct) {
      out.direct_below[i] = (d - g.direct_low[i]) * 1.000001f;
      out.direct_above[i] = (g.direct_high[i] - d) * 1.000001f;
    }
  }
  return out;
}

}  // namespace lightsolver
