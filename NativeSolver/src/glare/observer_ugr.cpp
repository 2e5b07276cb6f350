// UGR at an observer (CIE 117-1995): sources, their apparent luminance and solid angle, and the
// position-weighted sum.
#include <cmath>
#include <glm/geometric.hpp>
#include <sstream>

#include "glare/glare_terms.hpp"
#include "lightsolver/angles.hpp"
#include "lightsolver/glare.hpp"

namespace lightsolver {
namespace {

// CIE 117's formula holds for sources of 0.0003 to 0.1 sr (CIE 147 rates smaller and larger
// ones); outside it the result is still computed but flagged.
constexpr double kSmallSourceSr = 3e-4;
constexpr double kLargeSourceSr = 0.1;

// Width of an ellipse with semi-axes a (along x) and b (along y) across the horizontal
// direction (dx, dy), times that direction's length: the silhouette of a vertical side.
double ellipse_side(double a, double b, double dx, double dy) {
  return 2.0 * std::sqrt(a * a * dy * dy + b * b * dx * dx);
}

std::string format_g(double v) {
  std::ostringstream s;
  s.precision(3);
  s << v;
  return s.str();
}

}  // namespace

namespace detail {

std::optional<std::string> solid_angle_warning(const std::string& name, double solid_angle_sr) {
  if (solid_angle_sr >= kSmallSourceSr && solid_angle_sr <= kLargeSourceSr) return std::nullopt;
  return name + ": solid angle " + format_g(solid_angle_sr) +
         " sr is outside CIE 117's range 0.0003-0.1 sr (" +
         (solid_angle_sr < kSmallSourceSr ? "small source, CIE 147" : "large source, CIE 147") +
         ")";
}

}  // namespace detail

double projected_luminous_area_m2(const PhotometricData& data, const glm::dvec3& dir) {
  const glm::dvec3 d = glm::normalize(dir);
  const double l = data.opening_length_m, w = data.opening_width_m, h = data.opening_height_m;
  const double ax = std::abs(d.x), ay = std::abs(d.y), az = std::abs(d.z);
  switch (data.opening_shape) {
    case OpeningShape::Point:
      return 0.0;
    case OpeningShape::Rectangle:
      return l * w * az;
    case OpeningShape::Box:
      return l * w * az + w * h * ax + l * h * ay;
    case OpeningShape::Disk:
      return 0.25 * kPi * l * w * az;
    case OpeningShape::VerticalCylinder:
      return 0.25 * kPi * l * w * az + h * ellipse_side(0.5 * l, 0.5 * w, d.x, d.y);
    case OpeningShape::Sphere: {  // ellipsoid with semi-axes a, b, c
      const double a = 0.5 * l, b = 0.5 * w, c = 0.5 * h;
      return kPi * std::sqrt(b * b * c * c * d.x * d.x + a * a * c * c * d.y * d.y +
                             a * a * b * b * d.z * d.z);
    }
    case OpeningShape::HorizontalCylinderC0:  // axis along x, cross-section w x h
      return l * ellipse_side(0.5 * w, 0.5 * h, d.y, d.z) + 0.25 * kPi * w * h * ax;
    case OpeningShape::HorizontalCylinderC90:  // axis along y, cross-section l x h
      return w * ellipse_side(0.5 * l, 0.5 * h, d.x, d.z) + 0.25 * kPi * l * h * ay;
    case OpeningShape::VerticalDisk:  // in the y-z plane, w x h
      return 0.25 * kPi * w * h * ax;
  }
  return 0.0;
}

GlareSource photometric_glare_source(const std::string& name,
                                     std::shared_ptr<const PhotometricData> data,
                                     std::shared_ptr<const PhotometricSampler> sampler,
                                     const glm::dvec3& centre_m, const glm::dvec3& aim,
                                     const glm::dvec3& c0, double flux_scale) {
  if (data->opening_shape == OpeningShape::Point)
    throw InputError(data->source_file, "luminous opening",
                     "the file gives no luminous area (a point opening); UGR needs the "
                     "luminance of an area (docs/glare.md)");
  const glm::dvec3 c90 = glm::cross(c0, aim);
  GlareSource s;
  s.name = name;
  s.centre_m = centre_m;
  s.appearance = [data, sampler, aim, c0, c90, flux_scale](const glm::dvec3& toward_eye) {
    // World to luminaire frame: the inverse of to_world (x = c0, y = c90, z = -aim).
    const glm::dvec3 local{glm::dot(toward_eye, c0), glm::dot(toward_eye, c90),
                           -glm::dot(toward_eye, aim)};
    return ApparentSource{flux_scale * sampler->intensity_cd(local),
                          projected_luminous_area_m2(*data, local)};
  };
  return s;
}

GlareSource lambertian_glare_source(const std::string& name, const glm::dvec3& centre_m,
                                    const glm::dvec3& normal, double area_m2, double flux_lm) {
  if (!(area_m2 > 0.0) || !std::isfinite(area_m2) || !(flux_lm >= 0.0) || !std::isfinite(flux_lm))
    throw InputError("", name, "a Lambertian glare source needs area_m2 > 0 and flux_lm >= 0");
  const glm::dvec3 n = glm::normalize(normal);
  GlareSource s;
  s.name = name;
  s.centre_m = centre_m;
  // One-sided Lambertian: I = (flux / pi) cos(theta), projected area A cos(theta).
  s.appearance = [n, area_m2, flux_lm](const glm::dvec3& toward_eye) {
    const double c = glm::dot(n, toward_eye);
    if (c <= 0.0) return ApparentSource{};
    return ApparentSource{flux_lm / kPi * c, area_m2 * c};
  };
  return s;
}

UgrResult compute_ugr(const GlareObserver& observer, const std::vector<GlareSource>& sources,
                      double background_luminance_cd_m2) {
  if (!(background_luminance_cd_m2 > 0.0) || !std::isfinite(background_luminance_cd_m2))
    throw InputError("", "UGR", "the background luminance must be a finite number > 0 cd/m2");
  const glm::dvec3 v = glm::normalize(observer.view_direction);
  glm::dvec3 u = observer.up - glm::dot(observer.up, v) * v;
  if (glm::length(u) < 1e-9)
    throw InputError("", "UGR observer", "the up direction is parallel to the view");
  u = glm::normalize(u);
  const glm::dvec3 side = glm::cross(v, u);

  UgrResult result;
  result.background_luminance_cd_m2 = background_luminance_cd_m2;
  const double k = 0.25 / background_luminance_cd_m2;
  for (const GlareSource& src : sources) {
    GlareContribution c;
    c.name = src.name;
    const glm::dvec3 d = src.centre_m - observer.eye_m;
    const double r_along = glm::dot(d, v), h = glm::dot(d, u), t = glm::dot(d, side);
    c.distance_m = glm::length(d);
    if (r_along <= 0.0) {
      c.why_not = "behind the eye";
    } else {
      c.h_over_r = h / r_along;
      c.t_over_r = t / r_along;
      const std::optional<double> p = guth_position_index(c.h_over_r, c.t_over_r);
      const ApparentSource a = src.appearance(-d / c.distance_m);
      if (h < 0.0) {
        c.why_not = "below the line of sight (outside CIE 117's table)";
      } else if (!p) {
        c.why_not = "outside the field or hidden by brow (CIE 117 Table 4.1)";
      } else if (!(a.projected_area_m2 > 0.0) || !(a.intensity_cd > 0.0)) {
        c.why_not = "dark or edge-on toward the eye";
      } else {
        c.counted = true;
        c.position_index = *p;
        c.luminance_cd_m2 = a.intensity_cd / a.projected_area_m2;
        c.solid_angle_sr = a.projected_area_m2 / (c.distance_m * c.distance_m);
        c.term = c.luminance_cd_m2 * c.luminance_cd_m2 * c.solid_angle_sr / (*p * *p);
        c.ugr_alone = 8.0 * std::log10(k * c.term);
        result.sum += c.term;
        if (auto w = detail::solid_angle_warning(src.name, c.solid_angle_sr))
          result.warnings.push_back(std::move(*w));
      }
    }
    result.contributions.push_back(std::move(c));
  }
  if (result.sum > 0.0) result.ugr = 8.0 * std::log10(k * result.sum);
  return result;
}

}  // namespace lightsolver
