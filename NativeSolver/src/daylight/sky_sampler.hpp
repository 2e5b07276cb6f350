#pragma once
// Exact sampling of sky directions (docs/daylight.md, "Sky"): directions drawn with density
// proportional to a weight w(ω) over the sphere (the sky's luminance, times the cosine toward a
// portal), by rejection from a tabulated majorant. Accepted directions have density w / ∫w
// exactly, so every photon carries the same power Φ/N and the emitted light is the model's, not a
// tabulation of it; the tabulation only sets the acceptance rate. Pure mathematics.
#include <algorithm>
#include <cmath>
#include <functional>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <memory>
#include <vector>

#include "daylight/sky_glazing.hpp"
#include "daylight/sky_models.hpp"

namespace lightsolver::daylight {

/// Where directions may fall: altitudes [altitude0, altitude0 + altitude_span] and azimuths
/// [azimuth0, azimuth0 + azimuth_span] (radians; azimuth atan2(y, x), counter-clockwise from
/// +x). The default is the whole sphere; a sky patch (docs/daylight.md, "Daylight
/// coefficients") is one such box, and its bands and sectors then cut the box evenly.
struct SkyRegion {
  double altitude0 = -0.5 * 3.141592653589793, altitude_span = 3.141592653589793;
  double azimuth0 = 0.0, azimuth_span = 2.0 * 3.141592653589793;
  bool whole() const {
    return altitude0 == -0.5 * 3.141592653589793 && altitude_span == 3.141592653589793 &&
           azimuth0 == 0.0 && azimuth_span == 2.0 * 3.141592653589793;
  }
};

/// Directions ω (unit, toward the sky) drawn ∝ w(ω) over the sphere.
///
/// The sphere is cut into n_alt altitude bands (the horizon is a band edge, where the sky meets
/// the ground) by n_az azimuth sectors. Each cell's majorant is the largest of w at a 5 x 5 grid
/// of its (sin altitude, azimuth) points and at the `peaks` inside it (the sun, a portal's
/// normal: where w has its kinks and maxima), plus the spread (max − min) over those points: a
/// bound that SkyDirections tests hold on random points (sky_sampler_test). A cell is picked ∝
/// majorant × solid angle, a point uniform in solid angle inside it, and accepted with
/// probability w / majorant.
class SkyDirections {
 public:
  using Weight = std::function<double(const glm::dvec3&)>;
  using Region = SkyRegion;
  SkyDirections(Weight w, const std::vector<glm::dvec3>& peaks, int n_alt = 90, int n_az = 180,
                Region region = {});

  /// ∫ w dω over the sphere: Gauss-Legendre 4 x 4 in each cell.
  double integral() const { return integral_; }
  /// |Gauss 4 x 4 − Gauss 2 x 2| / integral: the integral's relative error estimate.
  double integral_error() const { return integral_error_; }
  /// The cell majorants' solid-angle sum over the integral (>= 1): mean tries per photon.
  double tries_per_sample() const { return integral_ > 0.0 ? cdf_.back() / integral_ : 0.0; }
  /// w itself.
  double weight(const glm::dvec3& toward) const { return w_(toward); }
  /// Largest w / majorant seen at `n` pseudo-random points per cell (a test of the bound).
  double worst_bound_ratio(int n) const;
  /// The table, for the GPU: bands, sectors, each cell's majorant and the cumulative
  /// majorant x solid angle (cell i = band i / n_az, sector i % n_az; band edges at
  /// sin(-pi/2 + pi k / n_alt), the middle one exactly 0, over the whole sphere; at
  /// sin(altitude0 + altitude_span k / n_alt) in a region).
  const Region& region() const { return region_; }
  int bands() const { return n_alt_; }
  int sectors() const { return n_az_; }
  const std::vector<double>& bounds() const { return bound_; }
  const std::vector<double>& cumulative() const { return cdf_; }

  /// One direction; `uniform()` returns doubles in [0, 1).
  template <class Uniform>
  glm::dvec3 sample(Uniform&& uniform) const;

 private:
  struct Cell {
    double u0, u1, phi0, phi1;
  };
  Cell cell(std::size_t i) const;
  bool inside_azimuth(const glm::dvec3& p, const Cell& c) const;
  void set_band_edges();
  static glm::dvec3 direction(double u, double phi);

  Weight w_;
  int n_alt_, n_az_;
  Region region_;
  std::vector<double> alt_edges_u_;  ///< sin(altitude) at band edges, n_alt + 1
  std::vector<double> bound_;        ///< majorant per cell
  std::vector<double> cdf_;          ///< cumulative majorant x solid angle
  double integral_ = 0.0, integral_error_ = 0.0;
};

/// A sky seen through portals (parallelograms; edge1 x edge2 points into the room, the way the
/// light goes), or, with no portal, from a disc of the site's radius perpendicular to each
/// direction, centred `radius` beyond the site's centre toward the sky: the light every point
/// within `radius` of the centre receives, from every direction.
class SkyEmitter {
 public:
  struct Portal {
    glm::dvec3 corner, edge1, edge2;
    Glazing glazing{};  ///< τ(θ) weights the directions; frame x maintenance the flux
  };
  /// `region`: only the sky within it shines (a sky patch: docs/daylight.md, "Daylight
  /// coefficients"); its table has cells of about 2° as the whole sky's.
  SkyEmitter(std::shared_ptr<const Sky> sky, std::vector<Portal> portals, glm::dvec3 site_centre,
             double site_radius_m, const SkyDirections::Region& region = {});

  /// Flux entering through the portals (or leaving the disc), lm: A f ∫ L cos τ(θ) dω per
  /// portal (f = frame x maintenance, τ the glazing's transmittance; 1 without glazing), or
  /// π R² ∫ L dω for the disc.
  double flux_lm() const { return flux_lm_; }
  /// Relative error estimate of flux_lm() (the quadrature's).
  double flux_error() const { return flux_error_; }
  const Sky& sky() const { return *sky_; }
  const std::vector<Portal>& portals() const { return portals_; }
  /// Flux of each portal (the disc: one entry).
  const std::vector<double>& portal_flux_lm() const { return portal_flux_; }
  const SkyDirections& directions(std::size_t portal) const { return *directions_[portal]; }
  /// Without portals: the site's centre and radius.
  const glm::dvec3& site_centre() const { return centre_; }
  double site_radius_m() const { return radius_; }

  /// A photon: origin and direction of travel (world); returns the portal it comes through
  /// (0 for the disc). `uniform()` returns doubles in [0, 1).
  template <class Uniform>
  std::size_t emit(Uniform&& uniform, glm::dvec3& origin, glm::dvec3& dir) const;
  /// Portal k's unit normal into the room (edge1 x edge2 normalised).
  glm::dvec3 inward(std::size_t k) const {
    return glm::normalize(glm::cross(portals_[k].edge1, portals_[k].edge2));
  }

 private:
  std::shared_ptr<const Sky> sky_;
  std::vector<Portal> portals_;
  glm::dvec3 centre_;
  double radius_;
  std::vector<std::unique_ptr<SkyDirections>> directions_;
  std::vector<double> portal_flux_, portal_cdf_;
  double flux_lm_ = 0.0, flux_error_ = 0.0;
};

// ---- templates ----

template <class Uniform>
glm::dvec3 SkyDirections::sample(Uniform&& uniform) const {
  constexpr int kMaxTries = 100000;  // acceptance is ~1/2 or better; only stops a broken table
  glm::dvec3 d(0.0, 0.0, 1.0);
  if (!(cdf_.back() > 0.0)) return d;  // no light this way: the emitter never picks it
  for (int attempt = 0; attempt < kMaxTries; ++attempt) {
    const double x = uniform() * cdf_.back();
    std::size_t i =
        static_cast<std::size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), x) - cdf_.begin());
    if (i >= cdf_.size()) i = cdf_.size() - 1;
    while (i > 0 && bound_[i] <= 0.0) --i;  // x rounded onto a zero cell's edge
    const Cell c = cell(i);
    d = direction(c.u0 + uniform() * (c.u1 - c.u0), c.phi0 + uniform() * (c.phi1 - c.phi0));
    if (uniform() * bound_[i] < w_(d)) return d;
  }
  return d;
}

template <class Uniform>
std::size_t SkyEmitter::emit(Uniform&& uniform, glm::dvec3& origin, glm::dvec3& dir) const {
  std::size_t k = 0;
  if (portal_cdf_.size() > 1) {
    const double x = uniform() * portal_cdf_.back();
    while (k + 1 < portal_cdf_.size() && !(x < portal_cdf_[k])) ++k;
  }
  const glm::dvec3 toward = directions_[k]->sample(uniform);
  dir = -toward;
  const double s = uniform(), t = uniform();
  if (!portals_.empty()) {
    const Portal& p = portals_[k];
    origin = p.corner + s * p.edge1 + t * p.edge2;
    return k;
  }
  // Uniform on the disc of radius R perpendicular to `toward`, R beyond the centre.
  const glm::dvec3 helper = std::abs(toward.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
  const glm::dvec3 e1 = glm::normalize(glm::cross(helper, toward));
  const glm::dvec3 e2 = glm::cross(toward, e1);
  const double r = radius_ * std::sqrt(s), phi = 2.0 * 3.141592653589793 * t;
  origin = centre_ + radius_ * toward + r * (std::cos(phi) * e1 + std::sin(phi) * e2);
  return 0;
}

}  // namespace lightsolver::daylight
