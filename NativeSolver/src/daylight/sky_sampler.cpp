// Exact sky direction sampling and the sky seen through portals (sky_sampler.hpp).
#include "daylight/sky_sampler.hpp"

#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>

#include "lightsolver/angles.hpp"

namespace lightsolver::daylight {
namespace {

// Gauss-Legendre on [0, 1].
constexpr double kG2x[2] = {0.21132486540518713, 0.7886751345948129};
constexpr double kG4x[4] = {0.0694318442029737, 0.33000947820757187, 0.6699905217924281,
                            0.9305681557970263};
constexpr double kG4w[4] = {0.17392742256872692, 0.3260725774312731, 0.3260725774312731,
                            0.17392742256872692};

double wrap_azimuth(double phi) {
  phi = std::fmod(phi, 2.0 * kPi);
  return phi < 0.0 ? phi + 2.0 * kPi : phi;
}

}  // namespace

glm::dvec3 SkyDirections::direction(double u, double phi) {
  const double s = std::sqrt(std::max(0.0, 1.0 - u * u));
  return {s * std::cos(phi), s * std::sin(phi), u};
}

SkyDirections::Cell SkyDirections::cell(std::size_t i) const {
  const std::size_t band = i / n_az_, sector = i % n_az_;
  if (region_.whole()) {  // the whole sphere's cells as they always were (results unchanged)
    const double dphi = 2.0 * kPi / n_az_;
    return {alt_edges_u_[band], alt_edges_u_[band + 1], sector * dphi, (sector + 1) * dphi};
  }
  const double dphi = region_.azimuth_span / n_az_;
  return {alt_edges_u_[band], alt_edges_u_[band + 1], region_.azimuth0 + sector * dphi,
          region_.azimuth0 + (sector + 1) * dphi};
}

bool SkyDirections::inside_azimuth(const glm::dvec3& p, const Cell& c) const {
  if (region_.whole()) {
    const double phi = wrap_azimuth(std::atan2(p.y, p.x));
    return phi >= c.phi0 && phi <= c.phi1;
  }
  return wrap_azimuth(std::atan2(p.y, p.x) - c.phi0) <= c.phi1 - c.phi0;  // from the cell's start
}

void SkyDirections::set_band_edges() {
  alt_edges_u_.resize(n_alt_ + 1);
  if (region_.whole()) {
    for (int i = 0; i <= n_alt_; ++i) {
      alt_edges_u_[i] = i == n_alt_ / 2 ? 0.0 : std::sin(-kPi / 2 + kPi * i / n_alt_);
    }
    alt_edges_u_.front() = -1.0;
    alt_edges_u_.back() = 1.0;
    return;
  }
  for (int i = 0; i <= n_alt_; ++i) {
    const double a = region_.altitude0 + region_.altitude_span * i / n_alt_;
    // The horizon and the poles exactly: a patch's band must not leak across them.
    alt_edges_u_[i] = std::abs(a) < 1e-15 ? 0.0 : std::clamp(std::sin(a), -1.0, 1.0);
  }
}

SkyDirections::SkyDirections(Weight w, const std::vector<glm::dvec3>& peaks, int n_alt, int n_az,
                             Region region)
    : w_(std::move(w)), n_alt_(n_alt), n_az_(n_az), region_(region) {
  const bool sizes_ok = region.whole() ? n_alt >= 2 && n_alt % 2 == 0 : n_alt >= 1;
  if (!sizes_ok || n_az < 1) throw std::invalid_argument("sky table size");
  if (!(region.altitude_span > 0.0) || !(region.azimuth_span > 0.0) ||
      region.altitude0 < -0.5 * kPi - 1e-12 ||
      region.altitude0 + region.altitude_span > 0.5 * kPi + 1e-12 ||
      region.azimuth_span > 2.0 * kPi + 1e-12) {
    throw std::invalid_argument("sky region out of the sphere");
  }
  set_band_edges();
  const std::size_t cells = static_cast<std::size_t>(n_alt) * n_az;
  bound_.resize(cells);
  cdf_.resize(cells);
  double total = 0.0, sum4 = 0.0, sum2 = 0.0;
  for (std::size_t i = 0; i < cells; ++i) {
    const Cell c = cell(i);
    const double du = c.u1 - c.u0, dphi = c.phi1 - c.phi0;
    double hi = 0.0, lo = INFINITY;
    for (int a = 0; a <= 4; ++a) {
      for (int b = 0; b <= 4; ++b) {
        // Nudged off the cell's edges, where the sky meets the ground.
        const double fa = std::clamp(a / 4.0, 1e-9, 1.0 - 1e-9);
        const double v = w_(direction(c.u0 + fa * du, c.phi0 + b / 4.0 * dphi));
        hi = std::max(hi, v);
        lo = std::min(lo, v);
      }
    }
    for (const glm::dvec3& p : peaks) {
      if (p.z >= c.u0 && p.z <= c.u1 && inside_azimuth(p, c)) {
        hi = std::max(hi, w_(p));
      }
    }
    bound_[i] = hi > 0.0 ? hi + (hi - lo) : 0.0;
    total += bound_[i] * du * dphi;
    cdf_[i] = total;
    double q4 = 0.0, q2 = 0.0;
    for (int a = 0; a < 4; ++a) {
      for (int b = 0; b < 4; ++b) {
        q4 += kG4w[a] * kG4w[b] * w_(direction(c.u0 + kG4x[a] * du, c.phi0 + kG4x[b] * dphi));
      }
    }
    for (int a = 0; a < 2; ++a) {
      for (int b = 0; b < 2; ++b) {
        q2 += 0.25 * w_(direction(c.u0 + kG2x[a] * du, c.phi0 + kG2x[b] * dphi));
      }
    }
    sum4 += q4 * du * dphi;
    sum2 += q2 * du * dphi;
  }
  integral_ = sum4;
  integral_error_ = sum4 > 0.0 ? std::abs(sum4 - sum2) / sum4 : 0.0;
  if (!std::isfinite(total)) throw std::invalid_argument("the sky's luminance is not finite");
}

double SkyDirections::worst_bound_ratio(int n) const {
  double worst = 0.0;
  std::uint64_t state = 0x9E3779B97F4A7C15ull;
  auto next = [&]() {  // splitmix64: reproducible points, no dependence on the solver's RNG
    state += 0x9E3779B97F4A7C15ull;
    std::uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  };
  for (std::size_t i = 0; i < bound_.size(); ++i) {
    const Cell c = cell(i);
    for (int k = 0; k < n; ++k) {
      const double v =
          w_(direction(c.u0 + next() * (c.u1 - c.u0), c.phi0 + next() * (c.phi1 - c.phi0)));
      if (v > 0.0) worst = std::max(worst, bound_[i] > 0.0 ? v / bound_[i] : INFINITY);
    }
  }
  return worst;
}

namespace {
// A region's table: cells of about 2° (the whole sky's 90 x 180), at least 2 x 2.
std::unique_ptr<SkyDirections> directions_in(SkyDirections::Weight w,
                                             const std::vector<glm::dvec3>& peaks,
                                             const SkyDirections::Region& r) {
  if (r.whole()) return std::make_unique<SkyDirections>(std::move(w), peaks);
  const double cell = kPi / 90.0;
  const int bands = std::max(2, static_cast<int>(std::ceil(r.altitude_span / cell - 1e-9)));
  const int sectors = std::max(2, static_cast<int>(std::ceil(r.azimuth_span / cell - 1e-9)));
  return std::make_unique<SkyDirections>(std::move(w), peaks, bands, sectors, r);
}
}  // namespace

SkyEmitter::SkyEmitter(std::shared_ptr<const Sky> sky, std::vector<Portal> portals,
                       glm::dvec3 site_centre, double site_radius_m,
                       const SkyDirections::Region& region)
    : sky_(std::move(sky)),
      portals_(std::move(portals)),
      centre_(site_centre),
      radius_(site_radius_m) {
  const Sky* s = sky_.get();
  const Direction sd = s->sun();
  const glm::dvec3 sun(sd.x, sd.y, sd.z);
  auto luminance = [s](const glm::dvec3& d) { return s->luminance({d.x, d.y, d.z}); };
  double total = 0.0, err = 0.0;
  auto add = [&](std::unique_ptr<SkyDirections> dirs, double area) {
    const double f = area * dirs->integral();
    err += f * dirs->integral_error();
    total += f;
    portal_flux_.push_back(f);
    portal_cdf_.push_back(total);
    directions_.push_back(std::move(dirs));
  };
  if (portals_.empty()) {
    if (!(radius_ > 0.0)) throw std::invalid_argument("site radius must be > 0 without portals");
    add(directions_in(luminance, {sun, {0, 0, 1}}, region), kPi * radius_ * radius_);
  }
  for (const Portal& p : portals_) {
    const glm::dvec3 n = glm::cross(p.edge1, p.edge2);
    const double area = glm::length(n);
    if (!(area > 0.0)) throw std::invalid_argument("portal of zero area");
    const glm::dvec3 out = -n / area;  // toward the sky: against the light's way in
    // Glazing: the transmitted part is drawn exactly (τ(θ) in the weight, frame and dirt in the
    // flux), so every photon still carries the same power and none is spent on absorbed light.
    const double scale = p.glazing.scale();
    const unsigned panes = p.glazing.panes;
    auto w = [luminance, out, scale, panes](const glm::dvec3& d) {
      const double c = glm::dot(d, out);
      return c > 0.0 ? luminance(d) * c * shared::glazing_transmittance<double>(c, scale, panes)
                     : 0.0;
    };
    add(directions_in(w, {sun, out, {0, 0, 1}}, region), area * p.glazing.factor());
  }
  flux_lm_ = total;
  flux_error_ = total > 0.0 ? err / total : 0.0;
}

}  // namespace lightsolver::daylight
