// The general sky form, the CIE and uniform skies, the horizontal integral and Sky (the Perez
// model's tables are in sky_perez.cpp).
#include "daylight/sky_models.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "daylight/gauss_legendre.hpp"
#include "lightsolver/angles.hpp"

namespace lightsolver::daylight {
namespace {

// ISO 15469:2004 / CIE S 011/E:2003, Table 1: gradation group (a, b) and indicatrix group
// (c, d, e) of each of the 15 standard general skies. Checked against two independent
// transcriptions: Darula & Kittler, "CIE general sky standard defining luminance
// distributions", Proc. eSim 2002 (the six gradation and six indicatrix groups), and the
// per-type table of DigitalRune's CieSkyParameters (Type1..Type15).
struct CieRow {
  double a, b, c, d, e;
};
constexpr std::array<CieRow, 15> kCieGeneral = {{
    {4.0, -0.70, 0.0, -1.0, 0.00},    // 1  I.1   CIE standard overcast, steep gradation
    {4.0, -0.70, 2.0, -1.5, 0.15},    // 2  I.2   overcast, slight brightening toward the sun
    {1.1, -0.80, 0.0, -1.0, 0.00},    // 3  II.1  overcast, moderately graded
    {1.1, -0.80, 2.0, -1.5, 0.15},    // 4  II.2
    {0.0, -1.00, 0.0, -1.0, 0.00},    // 5  III.1 sky of uniform luminance
    {0.0, -1.00, 2.0, -1.5, 0.15},    // 6  III.2 partly cloudy
    {0.0, -1.00, 5.0, -2.5, 0.30},    // 7  III.3
    {0.0, -1.00, 10.0, -3.0, 0.45},   // 8  III.4
    {-1.0, -0.55, 2.0, -1.5, 0.15},   // 9  IV.2  partly cloudy, obscured sun
    {-1.0, -0.55, 5.0, -2.5, 0.30},   // 10 IV.3
    {-1.0, -0.55, 10.0, -3.0, 0.45},  // 11 IV.4  white-blue sky, distinct solar corona
    {-1.0, -0.32, 10.0, -3.0, 0.45},  // 12 V.4   CIE standard clear sky, low turbidity
    {-1.0, -0.32, 16.0, -3.0, 0.30},  // 13 V.5   CIE standard clear sky, polluted
    {-1.0, -0.15, 16.0, -3.0, 0.30},  // 14 VI.5  cloudless turbid, broad corona
    {-1.0, -0.15, 24.0, -2.8, 0.15},  // 15 VI.6  white-blue turbid, broad corona
}};

double dot(const Direction& p, const Direction& q) { return p.x * q.x + p.y * q.y + p.z * q.z; }

// Gauss-Legendre nodes and weights on [0, 1] (Newton on P_n, Numerical Recipes' gauleg).
using Rule = GaussRule;

// Panel edges on [lo, hi] with `split` among them (if inside): n panels on each side in
// proportion to their lengths, at least one.
std::vector<double> edges(double lo, double hi, double split, int n) {
  std::vector<double> e;
  if (split > lo + 1e-9 && split < hi - 1e-9) {
    const int n1 = std::max(1, static_cast<int>(std::lround(n * (split - lo) / (hi - lo))));
    const int n2 = std::max(1, n - n1);
    for (int i = 0; i < n1; ++i) e.push_back(lo + (split - lo) * i / n1);
    for (int i = 0; i <= n2; ++i) e.push_back(split + (hi - split) * i / n2);
  } else {
    for (int i = 0; i <= n; ++i) e.push_back(lo + (hi - lo) * i / n);
  }
  return e;
}

// ∫ raw cos Z dω over the upper hemisphere on nz x nphi panels, the azimuth measured from the
// sun's (the integrand is even in it: [0, pi] doubled).
double integrate(const SkyShape& s, const Direction& sun, int nz, int nphi, const Rule& g) {
  const double zs = std::acos(std::clamp(sun.z, -1.0, 1.0));
  const double sun_az = std::atan2(sun.y, sun.x);
  std::vector<double> ze = edges(0.0, kPi / 2, zs, nz);
  if (s.a != 0.0 && s.b > 0.0) {  // the floor's kink at cos Z = kMinCosZ on a panel edge
    const double zf = std::acos(kMinCosZ);
    auto it = std::upper_bound(ze.begin(), ze.end(), zf);
    if (std::abs(*(it - 1) - zf) > 1e-9 && (it == ze.end() || std::abs(*it - zf) > 1e-9)) {
      ze.insert(it, zf);
    }
  }
  const std::vector<double> pe = edges(0.0, kPi, -1.0, nphi);
  // Every ring has the same azimuths: their weights, cosines and sines once.
  struct Azimuth {
    double w, c, s;
  };
  std::vector<Azimuth> az;
  az.reserve((pe.size() - 1) * g.x.size());
  for (std::size_t j = 0; j + 1 < pe.size(); ++j) {
    const double p0 = pe[j], dp = pe[j + 1] - pe[j];
    for (std::size_t gj = 0; gj < g.x.size(); ++gj) {
      const double phi = sun_az + p0 + dp * g.x[gj];
      az.push_back({g.w[gj] * dp, std::cos(phi), std::sin(phi)});
    }
  }
  double total = 0.0;
  for (std::size_t i = 0; i + 1 < ze.size(); ++i) {
    const double z0 = ze[i], dz = ze[i + 1] - ze[i];
    for (std::size_t gi = 0; gi < g.x.size(); ++gi) {
      const double zen = z0 + dz * g.x[gi];
      const double sz = std::sin(zen), cz = std::cos(zen);
      double ring = 0.0;
      for (const Azimuth& a : az) ring += a.w * s.raw({sz * a.c, sz * a.s, cz}, sun);
      total += g.w[gi] * dz * ring * cz * sz;
    }
  }
  return 2.0 * total;
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

Direction checked_sun(const SkySpec& spec, bool needed) {
  if (!spec.sun) {
    require(!needed, "sun: this sky model needs the sun's direction");
    return {0.0, 0.0, 1.0};
  }
  Direction s = *spec.sun;
  const double n = std::sqrt(dot(s, s));
  require(std::isfinite(n) && n > 0.0, "sun: not a finite, non-zero direction");
  s = {s.x / n, s.y / n, s.z / n};
  require(s.z >= 0.0, "sun: below the horizon (a daylight sky needs the sun at or above it)");
  return s;
}

}  // namespace

double SkyShape::raw(const Direction& toward, const Direction& sun) const {
  const double cz = toward.z;
  double phi = 1.0 + m * cz;
  // exp(b / cos Z) -> 0 at the horizon for b < 0 (every CIE sky). A Perez sky can have b > 0
  // (its coefficients outside the conditions they were fitted to: low sun with heavy brightness,
  // the sixth clearness bin at high sun), where the term grows without bound toward the horizon:
  // there cos Z is floored at sin 6° (kMinCosZ), so the band below 6° is as bright as at 6°.
  if (a != 0.0 && cz > 0.0) phi += a * std::exp(b / (b > 0.0 ? std::max(cz, kMinCosZ) : cz));
  double f = 1.0;
  if (c != 0.0 || e != 0.0) {
    const double cchi = std::clamp(dot(toward, sun), -1.0, 1.0);
    f += c * (std::exp(d * std::acos(cchi)) - k) + e * cchi * cchi;
  }
  return std::max(0.0, phi * f);
}

SkyShape cie_general_sky(int type) {
  if (type < 1 || type > 15) {
    throw std::invalid_argument("cie_type: " + std::to_string(type) +
                                " is not a CIE standard general sky (1 to 15)");
  }
  const CieRow& r = kCieGeneral[type - 1];
  SkyShape s;
  s.a = r.a;
  s.b = r.b;
  s.c = r.c;
  s.d = r.d;
  s.e = r.e;
  s.k = std::exp(r.d * kPi / 2.0);
  return s;
}

SkyShape cie_overcast_sky() {
  SkyShape s;
  s.m = 2.0;
  return s;
}

SkyShape uniform_sky() { return SkyShape{}; }

double horizontal_integral(const SkyShape& shape, const Direction& sun, double* error) {
  static const Rule g = gauss_legendre(8);
  // Without an indicatrix the integrand does not depend on azimuth: one panel suffices there.
  // Panels double (to 192 x 192) while the estimate moves by more than 1e-6: a Perez form
  // clamped at zero somewhere has a kink off the panel edges.
  const int az = shape.needs_sun() ? 1 : 0;
  int n = 48;
  double coarse = integrate(shape, sun, n / 2, az ? n / 2 : 1, g);
  double fine = integrate(shape, sun, n, az ? n : 1, g);
  while (std::abs(fine - coarse) > 1e-6 * std::abs(fine) && n < 192) {
    n *= 2;
    coarse = fine;
    fine = integrate(shape, sun, n, az ? n : 1, g);
  }
  if (error) *error = std::abs(fine - coarse);
  return fine;
}

Sky::Sky(const SkySpec& spec) {
  require(std::isfinite(spec.ground_reflectance) && spec.ground_reflectance >= 0.0 &&
              spec.ground_reflectance <= 1.0,
          "ground_reflectance: must be between 0 and 1");
  require(std::isfinite(spec.sun_direct_normal_lx) && spec.sun_direct_normal_lx >= 0.0,
          "sun_direct_normal_lx: must be a finite value >= 0");
  double diffuse_lx = 0.0, sun_normal_lx = spec.sun_direct_normal_lx;
  if (spec.model == SkyModel::Perez) {
    sun_ = checked_sun(spec, true);
    const double zenith = std::acos(sun_.z);
    PerezState st = perez_state(spec.perez, zenith);
    shape_ = perez_shape(st, zenith);
    // Raise the coefficients' brightness where they give a sky with no light (PerezState).
    while (!(horizontal_integral(shape_, sun_) > 0.0) && st.shape_delta < 0.6 - 1e-9) {
      st.shape_delta = std::min(0.6, st.shape_delta + 0.01);
      shape_ = perez_shape(st, zenith);
    }
    perez_ = st;
    diffuse_lx = st.diffuse_horizontal_lx;
    sun_normal_lx = st.direct_normal_lx;
  } else {
    shape_ = spec.model == SkyModel::CieGeneral    ? cie_general_sky(spec.cie_type)
             : spec.model == SkyModel::CieOvercast ? cie_overcast_sky()
                                                   : uniform_sky();
    sun_ = checked_sun(spec, shape_.needs_sun());
    require(std::isfinite(spec.level) && spec.level >= 0.0 && spec.level <= 1e7,
            "level: must be between 0 and 10^7 (cd/m² or lx)");
  }
  double err = 0.0;
  raw_horizontal_ = horizontal_integral(shape_, sun_, &err);
  require(raw_horizontal_ > 0.0 && std::isfinite(raw_horizontal_),
          "the sky model gives no light above the horizon");
  quadrature_error_ = err / raw_horizontal_;
  if (spec.model == SkyModel::Perez ||
      spec.normalisation == SkyNormalisation::DiffuseHorizontalIlluminance) {
    if (spec.model != SkyModel::Perez) diffuse_lx = spec.level;
    scale_ = diffuse_lx / raw_horizontal_;
  } else {
    scale_ = spec.level / shape_.raw({0.0, 0.0, 1.0}, sun_);
    diffuse_lx = scale_ * raw_horizontal_;
  }
  const double global_lx = diffuse_lx + sun_normal_lx * sun_.z;
  ground_luminance_ = spec.ground_reflectance * global_lx / kPi;
}

double Sky::luminance(const Direction& toward) const {
  if (!(toward.z > 0.0)) return ground_luminance_;
  return scale_ * shape_.raw(toward, sun_);
}

}  // namespace lightsolver::daylight
