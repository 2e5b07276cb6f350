// Photometric luminaires in the scene: loading the file, the luminaire frame.
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

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

double photometric_tilt_factor(const Luminaire& l) {
  if (l.type != Luminaire::Type::Photometric || !l.photometry) return 1.0;
  const PhotometricData& d = *l.photometry;
  if (d.tilt == "NONE" || d.type != PhotometricType::C) return 1.0;
  // Type C is measured aimed straight down, so the tilt is the aim's angle from -z, whichever
  // way the luminaire leans. (For horizontal lamps, geometries 2 and 3, LM-63 tabulates tilt
  // about one axis; the angle from straight down is the same quantity for that tilt.)
  const double cos_tilt = std::clamp(-glm::normalize(l.aim).z, -1.0, 1.0);
  return d.tilt_data.factor_at(glm::degrees(std::acos(cos_tilt)));
}

Warnings photometric_warnings(const Luminaire& l) {
  if (l.type != Luminaire::Type::Photometric || !l.photometry) return {};
  const PhotometricData& d = *l.photometry;
  Warnings out;
  const std::string who = "luminaire \"" + l.name + "\" (" + l.file + "): ";
  for (const std::string& w : d.warnings) out.push_back(who + w);
  if (d.tilt != "NONE" && d.type != PhotometricType::C) {
    out.push_back(who +
                  "TILT table not applied: type A/B photometry has no 'aimed down' "
                  "attitude to measure the tilt from");
  }
  return out;
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
