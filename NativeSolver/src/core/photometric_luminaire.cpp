// Photometric luminaires in the scene: loading the file, the luminaire frame.
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>

#include "lightsolver/photometry.hpp"
#include "lightsolver/scene.hpp"

namespace lightsolver {

glm::dvec3 photometric_c0(const Luminaire& l) {
  const glm::dvec3 aim = glm::normalize(l.aim);
  // C0 defaults to +x (ies2rad's convention for a downlight), or +y when aiming along x.
  const glm::dvec3 ref = std::abs(aim.x) > 0.999 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  const glm::dvec3 c0 = glm::normalize(ref - glm::dot(ref, aim) * aim);
  // Turn counter-clockwise about the luminaire's up axis (-aim): for a downlight, as seen from
  // above, as CAD tools rotate about z. c0 is orthogonal to the axis (Rodrigues, no parallel
  // term).
  const double a = glm::radians(l.rotation_deg);
  return std::cos(a) * c0 + std::sin(a) * glm::cross(c0, aim);
}

void load_photometric(Luminaire& l, const std::string& path,
                      std::optional<double> requested_flux_lm, const std::string& where) {
  auto data = std::make_shared<PhotometricData>(load_photometry(path));
  auto sampler = std::make_shared<PhotometricSampler>(*data);
  if (requested_flux_lm && !(std::isfinite(*requested_flux_lm) && *requested_flux_lm >= 0.0)) {
    throw InputError("", where, "must be a finite value >= 0");
  }
  l.flux_lm = sampler->emitted_flux_lm(requested_flux_lm);
  l.photometry = std::move(data);
  l.sampler = std::move(sampler);
}

}  // namespace lightsolver
