// Exact emission sampling from a candela table (see photometry.hpp for the method).

#include <algorithm>
#include <cmath>
#include <numbers>

#include "lightsolver/angles.hpp"
#include "photometry_internal.hpp"

namespace lightsolver {

namespace {

// Acceptance per try is at least 1/12: I is bilinear (>= its largest corner times a product of
// linear ramps) and sin t is concave over a cell (>= its maximum times a tent). 1000 rejections
// in a row thus have probability below 1e-37; the cap only stops hostile input from looping.
constexpr int kMaxTries = 1000;

bool round_footprint(OpeningShape s) {
  return s == OpeningShape::Disk || s == OpeningShape::VerticalCylinder ||
         s == OpeningShape::Sphere || s == OpeningShape::VerticalDisk;
}

}  // namespace

PhotometricSampler::PhotometricSampler(const PhotometricData& data)
    : tables_(photometry_detail::make_tables(data)),
      absolute_(data.absolute_photometry),
      rated_lumens_lm_(data.rated_lumens_lm),
      source_file_(data.source_file),
      footprint_round_(round_footprint(data.opening_shape)),
      length_m_(data.opening_length_m),
      width_m_(data.opening_width_m) {
  total_flux_lm_ = tables_.cell_cdf.empty() ? 0.0 : tables_.cell_cdf.back();
  if (!(total_flux_lm_ > 0.0) || !std::isfinite(total_flux_lm_))
    throw InputError(source_file_, "", "the distribution emits no light (all candela are zero)");
}

glm::dvec3 PhotometricSampler::sample_direction(PathRng& rng) const {
  const auto& cdf = tables_.cell_cdf;
  const double x = rng.uniform_double() * total_flux_lm_;
  // First cell whose cumulative flux exceeds x: zero-flux cells are never chosen.
  std::size_t cell =
      static_cast<std::size_t>(std::upper_bound(cdf.begin(), cdf.end(), x) - cdf.begin());
  if (cell >= cdf.size()) {  // x rounded up to the total: take the last cell with flux
    cell = cdf.size() - 1;
    while (cell > 0 && cdf[cell] == cdf[cell - 1]) --cell;
  }
  const std::size_t nt = tables_.polar_deg.size();
  const std::size_t i = cell / (nt - 1), j = cell % (nt - 1);
  const double p0 = tables_.plane_deg[i], p1 = tables_.plane_deg[i + 1];
  const double t0 = tables_.polar_deg[j], t1 = tables_.polar_deg[j + 1];
  const double i00 = tables_.candela[i * nt + j], i10 = tables_.candela[(i + 1) * nt + j];
  const double i01 = tables_.candela[i * nt + j + 1], i11 = tables_.candela[(i + 1) * nt + j + 1];
  const double bound = tables_.cell_bound[cell];
  // Uniform proposals over the (p, t) cell, accepted with probability I(p, t) sin t / bound:
  // accepted points have density proportional to I dOmega = I sin t dt dp, exactly.
  double s = 0.5, u = 0.5;
  for (int attempt = 0; attempt < kMaxTries; ++attempt) {
    s = rng.uniform_double();
    u = rng.uniform_double();
    const double intensity =
        (1 - s) * (1 - u) * i00 + s * (1 - u) * i10 + (1 - s) * u * i01 + s * u * i11;
    const double weight = intensity * std::sin((t0 + u * (t1 - t0)) * kDeg);
    if (rng.uniform_double() * bound < weight) break;
  }
  return photometry_detail::direction_of(tables_, p0 + s * (p1 - p0), t0 + u * (t1 - t0));
}

glm::dvec3 PhotometricSampler::sample_origin(PathRng& rng) const {
  const double a = rng.uniform_double(), b = rng.uniform_double();
  if (footprint_round_) {  // uniform over the ellipse with axes length x width
    const double r = std::sqrt(a), phi = 2.0 * std::numbers::pi * b;
    return {0.5 * length_m_ * r * std::cos(phi), 0.5 * width_m_ * r * std::sin(phi), 0.0};
  }
  return {(a - 0.5) * length_m_, (b - 0.5) * width_m_, 0.0};
}

double PhotometricSampler::intensity_cd(const glm::dvec3& direction_local) const {
  return photometry_detail::eval_direction(tables_, direction_local);
}

double PhotometricSampler::flux_scale(std::optional<double> flux_lm) const {
  if (!flux_lm) return 1.0;
  if (!(*flux_lm >= 0.0) || !std::isfinite(*flux_lm))
    throw InputError(source_file_, "flux_lm", "must be a finite number >= 0");
  if (absolute_ || !(rated_lumens_lm_ > 0.0)) return *flux_lm / total_flux_lm_;
  return *flux_lm / rated_lumens_lm_;
}

double PhotometricSampler::emitted_flux_lm(std::optional<double> flux_lm) const {
  return total_flux_lm_ * flux_scale(flux_lm);
}

}  // namespace lightsolver
