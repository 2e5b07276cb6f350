// Sky vectors (sky_vector.hpp): each patch's integral of the luminance by a product
// Gauss–Legendre rule in altitude and azimuth (dω = cos(alt) d alt dφ), the patch cut where the
// model is not smooth so that every kink lies on an edge.
#include "daylight/sky_vector.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "daylight/gauss_legendre.hpp"
#include "lightsolver/angles.hpp"

namespace lightsolver::daylight {

namespace {

using Rule = GaussRule;

const Rule& rule(int n) {
  static const std::array<Rule, 33> rules = [] {
    std::array<Rule, 33> a;
    for (int i = 1; i <= 32; ++i) a[static_cast<std::size_t>(i)] = gauss_legendre(i);
    return a;
  }();
  return rules[static_cast<std::size_t>(n)];
}

// Edges of [lo, hi] with each of `cuts` strictly inside added (sorted).
std::vector<double> edges(double lo, double hi, std::initializer_list<double> cuts) {
  std::vector<double> e{lo, hi};
  for (double c : cuts)
    if (c > lo + 1e-12 && c < hi - 1e-12) e.push_back(c);
  std::sort(e.begin(), e.end());
  return e;
}

struct PatchIntegral {
  double l = 0.0;     // ∫ L dω
  double lcos = 0.0;  // ∫ L cos Z dω
};

// ∫ over altitude [a0, a1] × azimuth [z0, z1] (radians, azimuth from north toward east).
// The directions are SkyPatches::direction(alt / kDeg, azimuth / kDeg)'s to the bit, with the
// trigonometry of each altitude and azimuth computed once, not per point.
template <class Luminance>
PatchIntegral integrate(const Luminance& lum, const SkyPatches& patches, double a0, double a1,
                        double z0, double z1, const Rule& g) {
  PatchIntegral s;
  const double da = a1 - a0, dz = z1 - z0;
  std::array<double, 32> cz, sz;
  for (std::size_t j = 0; j < g.x.size(); ++j) {
    const double z = (z0 + dz * g.x[j]) / kDeg * kDeg;
    cz[j] = std::cos(z), sz[j] = std::sin(z);
  }
  for (std::size_t i = 0; i < g.x.size(); ++i) {
    const double alt = a0 + da * g.x[i];
    const double wa = g.w[i] * da * std::cos(alt);
    const double a = alt / kDeg * kDeg, ca = std::cos(a), sa = std::sin(a);
    for (std::size_t j = 0; j < g.x.size(); ++j) {
      const glm::dvec3 d = patches.direction(ca, sa, cz[j], sz[j]);
      const double l = lum(Direction{d.x, d.y, d.z}) * wa * g.w[j] * dz;
      s.l += l;
      s.lcos += l * d.z;
    }
  }
  return s;
}

}  // namespace

// gendaymtx's AddDirect (weights 1/(1.002 − cos), the ground excluded).
void add_sun_as_radiance(std::vector<double>& v, const SkyPatches& patches, const glm::dvec3& sun,
                         double sun_normal_lx) {
  constexpr int kNear = 4;
  std::array<double, kNear> dots;
  std::array<int, kNear> idx{};
  dots.fill(-1.0);
  for (int p = 1; p < patches.count(); ++p) {
    const glm::dvec3& c = patches.patch(p).centre;
    const double dp = c.x * sun.x + c.y * sun.y + c.z * sun.z;
    for (int i = 0; i < kNear; ++i) {
      if (dp > dots[static_cast<std::size_t>(i)]) {
        for (int j = kNear - 1; j > i; --j) {
          dots[static_cast<std::size_t>(j)] = dots[static_cast<std::size_t>(j - 1)];
          idx[static_cast<std::size_t>(j)] = idx[static_cast<std::size_t>(j - 1)];
        }
        dots[static_cast<std::size_t>(i)] = dp;
        idx[static_cast<std::size_t>(i)] = p;
        break;
      }
    }
  }
  std::array<double, kNear> w;
  double total = 0.0;
  for (std::size_t i = 0; i < kNear; ++i) total += w[i] = 1.0 / (1.002 - dots[i]);
  for (std::size_t i = 0; i < kNear; ++i)
    v[static_cast<std::size_t>(idx[i])] += sun_normal_lx * w[i] / total;
}

namespace {

// ∫ L dω and ∫ L cos Z dω of every sky patch (index 0, the ground, left 0).
template <class Luminance>
std::vector<PatchIntegral> patch_integrals(const Luminance& lum, const Direction& s, double shape_b,
                                           const SkyPatches& patches, int points) {
  if (points < 1 || points > 32)
    throw std::invalid_argument("points: must be from 1 to 32, got " + std::to_string(points));
  const Rule& g = rule(points);
  const glm::dvec3 sun{s.x, s.y, s.z};
  double sun_alt = -90.0, sun_azi = 0.0;
  if (sun.z > 0.0) patches.altitude_azimuth(sun, sun_alt, sun_azi);
  // Where b > 0 the model's gradation is floored at sin 6° (kMinCosZ): a kink at 6° altitude.
  const double floor_alt = shape_b > 0.0 ? std::asin(kMinCosZ) : -1.0;
  std::vector<PatchIntegral> out(static_cast<std::size_t>(patches.count()));
  for (int p = 1; p < patches.count(); ++p) {
    const SkyPatch& q = patches.patch(p);
    const double a0 = q.altitude_min_deg * kDeg, a1 = q.altitude_max_deg * kDeg;
    // Azimuth range about the centre; the sun's azimuth brought into it.
    const double half = 0.5 * q.azimuth_width_deg;
    double z0 = q.azimuth_deg - half, z1 = q.azimuth_deg + half, sz = sun_azi;
    if (q.azimuth_width_deg >= 360.0) z0 = sz, z1 = sz + 360.0;  // the cap: cut at the sun
    while (sz < z0) sz += 360.0;
    while (sz >= z1) sz -= 360.0;
    const std::vector<double> ae = edges(a0, a1, {sun_alt * kDeg, floor_alt});
    const bool near_sun =
        sun.z > 0.0 && sun_alt >= q.altitude_min_deg - 1e-9 && sun_alt <= q.altitude_max_deg + 1e-9;
    std::vector<double> ze =
        near_sun ? edges(z0 * kDeg, z1 * kDeg, {sz * kDeg}) : edges(z0 * kDeg, z1 * kDeg, {});
    if (q.azimuth_width_deg >= 360.0) {
      // The cap spans every azimuth: as many parts as the row below it has patches (the sun's
      // azimuth an edge), so that its rule is as fine in azimuth as its neighbours'.
      const int parts = 6 * patches.mf();
      ze.clear();
      for (int k = 0; k <= parts; ++k) ze.push_back((z0 + 360.0 * k / parts) * kDeg);
    }
    PatchIntegral& sum = out[static_cast<std::size_t>(p)];
    for (std::size_t i = 0; i + 1 < ae.size(); ++i)
      for (std::size_t j = 0; j + 1 < ze.size(); ++j) {
        const PatchIntegral part = integrate(lum, patches, ae[i], ae[i + 1], ze[j], ze[j + 1], g);
        sum.l += part.l;
        sum.lcos += part.lcos;
      }
  }
  return out;
}

}  // namespace

std::vector<double> raw_patch_integrals(const SkyShape& shape, const Direction& sun,
                                        const SkyPatches& patches, int points,
                                        double& raw_horizontal) {
  const auto lum = [&](const Direction& d) { return shape.raw(d, sun); };
  const std::vector<PatchIntegral> in = patch_integrals(lum, sun, shape.b, patches, points);
  std::vector<double> out(in.size(), 0.0);
  raw_horizontal = 0.0;
  for (std::size_t p = 1; p < in.size(); ++p) out[p] = in[p].l, raw_horizontal += in[p].lcos;
  return out;
}

SkyVector sky_vector(const Sky& sky, double sun_direct_normal_lx, const SkyPatches& patches,
                     const SkyVectorOptions& options) {
  if (!std::isfinite(sun_direct_normal_lx) || sun_direct_normal_lx < 0.0)
    throw std::invalid_argument("sun_direct_normal_lx: must be a finite value >= 0");
  const Direction& s = sky.sun();
  const glm::dvec3 sun{s.x, s.y, s.z};
  const bool sun_up = sun.z > 0.0 && sun_direct_normal_lx > 0.0;
  const auto lum = [&](const Direction& d) { return sky.luminance(d); };
  const std::vector<PatchIntegral> in =
      patch_integrals(lum, s, sky.shape().b, patches, options.points);
  SkyVector r;
  r.patches.assign(in.size(), 0.0);
  r.patches[0] = sky.ground_luminance() * patches.patch(0).solid_angle_sr;
  double horizontal = 0.0;
  for (std::size_t p = 1; p < in.size(); ++p) r.patches[p] = in[p].l, horizontal += in[p].lcos;
  r.diffuse_horizontal_lx = sky.diffuse_horizontal_lx();
  r.horizontal_quadrature_lx = horizontal;
  r.quadrature_error =
      r.diffuse_horizontal_lx > 0.0
          ? std::abs(horizontal - r.diffuse_horizontal_lx) / r.diffuse_horizontal_lx
          : 0.0;
  if (sun_up) {
    r.sun_direction = sun;
    if (options.radiance_sun)
      add_sun_as_radiance(r.patches, patches, sun, sun_direct_normal_lx);
    else
      r.sun_direct_normal_lx = sun_direct_normal_lx;
  }
  return r;
}

SkyVector sky_vector(const SkySpec& spec, const SkyPatches& patches,
                     const SkyVectorOptions& options) {
  const Sky sky(spec);
  double sun_lx =
      spec.model == SkyModel::Perez ? sky.perez()->direct_normal_lx : spec.sun_direct_normal_lx;
  if (!spec.sun || !(spec.sun->z > 0.0)) sun_lx = 0.0;
  return sky_vector(sky, sun_lx, patches, options);
}

}  // namespace lightsolver::daylight
