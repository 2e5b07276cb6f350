// Reinhart sky patches (include/lightsolver/sky_patches.hpp): Radiance's numbering and geometry
// (reinhart.cal for direction → patch, reinsrc.cal and gendaymtx's rh_init for patch →
// direction and solid angle), in the scene frame of docs/daylight.md.
#include "lightsolver/sky_patches.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "lightsolver/angles.hpp"
#include "lightsolver/error.hpp"

namespace lightsolver {

namespace {

// Tregenza's patches per row, horizon up (the zenith cap apart).
constexpr int kTregenzaRow[7] = {30, 30, 24, 24, 18, 12, 6};

}  // namespace

SkyPatches::SkyPatches(int mf, double north_deg)
    : mf_(mf),
      north_deg_(north_deg),
      cos_north_(std::cos(north_deg * kDeg)),
      sin_north_(std::sin(north_deg * kDeg)) {
  if (mf < 1 || mf > 64)
    throw InputError(
        "", "mf",
        "the Reinhart subdivision must be an integer from 1 to 64, got " + std::to_string(mf));
  if (!std::isfinite(north_deg))
    throw InputError("", "north_deg", "must be a finite angle in degrees");
  alpha_deg_ = 90.0 / (7.0 * mf + 0.5);
  const double alpha = alpha_deg_ * kDeg;
  SkyPatch ground;
  ground.row = -1;
  ground.altitude_min_deg = -90.0;
  ground.altitude_max_deg = 0.0;
  ground.azimuth_width_deg = 360.0;
  ground.solid_angle_sr = 2.0 * kPi;
  ground.mean_cos_zenith = 0.0;
  ground.centre = {0.0, 0.0, -1.0};
  patches_.push_back(ground);
  for (int r = 0; r < 7 * mf; ++r) {
    row_start_.push_back(count());
    const int n = mf * kTregenzaRow[r / mf];
    const double s0 = std::sin(alpha * r), s1 = std::sin(alpha * (r + 1));
    for (int j = 0; j < n; ++j) {
      SkyPatch p;
      p.row = r;
      p.altitude_min_deg = alpha_deg_ * r;
      p.altitude_max_deg = alpha_deg_ * (r + 1);
      p.azimuth_width_deg = 360.0 / n;
      p.azimuth_deg = p.azimuth_width_deg * j;
      p.solid_angle_sr = 2.0 * kPi / n * (s1 - s0);
      p.mean_cos_zenith = 0.5 * (s0 + s1);
      p.centre = direction(alpha_deg_ * (r + 0.5), p.azimuth_deg);
      patches_.push_back(p);
    }
  }
  row_start_.push_back(count());
  SkyPatch cap;
  cap.row = 7 * mf;
  cap.altitude_min_deg = alpha_deg_ * 7 * mf;
  cap.altitude_max_deg = 90.0;
  cap.azimuth_width_deg = 360.0;
  // 1 − sin(90° − α/2) = 1 − cos(α/2): the form that keeps its digits.
  cap.solid_angle_sr = 4.0 * kPi * std::pow(std::sin(0.25 * alpha), 2);
  cap.mean_cos_zenith = 0.5 * (1.0 + std::cos(0.5 * alpha));
  cap.centre = {0.0, 0.0, 1.0};
  patches_.push_back(cap);
  row_start_.push_back(count());
}

void SkyPatches::altitude_azimuth(const glm::dvec3& d, double& altitude_deg,
                                  double& azimuth_deg) const {
  const double len = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  if (!(len > 0.0) || !std::isfinite(len))
    throw InputError("", "direction", "must be a finite, non-zero vector");
  const double north = -sin_north_ * d.x + cos_north_ * d.y;
  const double east = cos_north_ * d.x + sin_north_ * d.y;
  altitude_deg = std::asin(std::clamp(d.z / len, -1.0, 1.0)) / kDeg;
  double azi = std::atan2(east, north) / kDeg;
  if (azi < 0.0) azi += 360.0;
  if (azi >= 360.0) azi -= 360.0;
  azimuth_deg = azi;
}

glm::dvec3 SkyPatches::direction(double altitude_deg, double azimuth_deg) const {
  const double a = altitude_deg * kDeg, z = azimuth_deg * kDeg;
  return direction(std::cos(a), std::sin(a), std::cos(z), std::sin(z));
}

glm::dvec3 SkyPatches::direction(double cos_altitude, double sin_altitude, double cos_azimuth,
                                 double sin_azimuth) const {
  const double north = cos_altitude * cos_azimuth, east = cos_altitude * sin_azimuth;
  return {-sin_north_ * north + cos_north_ * east, cos_north_ * north + sin_north_ * east,
          sin_altitude};
}

int SkyPatches::index(const glm::dvec3& direction) const {
  double alt = 0.0, azi = 0.0;
  altitude_azimuth(direction, alt, azi);
  // reinhart.cal: rbin = if(-alt, 0, ...): only a direction strictly below the horizon is ground.
  if (direction.z < 0.0) return 0;
  const int row = std::min(static_cast<int>(std::floor(alt / alpha_deg_)), 7 * mf_);
  const int first = row_start_[static_cast<std::size_t>(row)];
  const int n = row_start_[static_cast<std::size_t>(row) + 1] - first;
  const double inc = 360.0 / n;
  int col = static_cast<int>(std::floor((azi + 0.5 * inc) / inc));
  if (col >= n) col = 0;  // the last half patch before north belongs to patch 0
  return first + col;
}

std::size_t SkyMatrix::bytes() const {
  return sky.size() * sizeof(float) + sun_direction.size() * sizeof(float) +
         sun_direct_normal_lx.size() * sizeof(float) + sun_altitude_deg.size() * sizeof(float) +
         diffuse_horizontal_lx.size() * sizeof(float) + status.size();
}

}  // namespace lightsolver
