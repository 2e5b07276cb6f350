// The photometric luminaire type: an IES / EULUMDAT distribution in an aimed, rotated frame.
// Its row of the table in luminaire_types.cpp.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <glm/geometric.hpp>
#include <numbers>
#include <optional>

#include "io/json_reader.hpp"
#include "types/luminaire_rows.hpp"
#include "model/sampling.hpp"
#include "lightsolver/photometry.hpp"

namespace lightsolver::detail {
namespace {

namespace fs = std::filesystem;
using namespace luminaire_rows;

constexpr const char* kPhotometricKeys[] = {"name", "type",         "file",   "position",
                                            "aim",  "rotation_deg", "flux_lm"};

void read_photometric(const JsonNode& n, Luminaire& l, const std::string& base_dir) {
  n.require_object(kPhotometricKeys);
  l.position = n.at("position").vec3();
  if (n.has("aim")) l.aim = n.at("aim").vec3();
  l.rotation_deg = n.number_or("rotation_deg", 0.0);
  std::optional<double> flux;
  if (n.has("flux_lm")) {
    flux = n.at("flux_lm").number();
    // Checked here so the message names the scene file (load_photometric knows only the field).
    if (!(*flux >= 0.0)) n.at("flux_lm").fail("must be a finite value >= 0");
  }
  l.file = n.at("file").string();
  load_photometric(l, (fs::path(base_dir) / l.file).lexically_normal().string(), flux,
                   n.path() + ".flux_lm");
}

void check_photometric(const LuminaireChecks& c, Luminaire& l) {
  c.coordinates("position", l.position);
  unit_direction(c, "aim", l.aim);
  if (!l.sampler) c.fail("file", "no photometric data loaded");
  if (!std::isfinite(l.rotation_deg)) c.fail("rotation_deg", "not finite");
  c.flux(l, " (emitted, from the file)");
  // The scaled table's peak: the file's candela times emitted flux / the file's integrated flux.
  if (!l.photometry || l.photometry->candela.empty()) return;
  const double peak_cd =
      *std::max_element(l.photometry->candela.begin(), l.photometry->candela.end()) *
      (l.flux_lm / l.sampler->integrated_flux_lm());
  if (!(peak_cd <= limits::kMaxIntensity_cd)) {
    c.fail("file", "peak intensity " + show(peak_cd) +
                       " cd (as scaled) is more than 10^15 cd: beyond any physical light source");
  }
}

void prepare_photometric(const Luminaire& l, PreparedLuminaire& p) {
  p.axis = vec3(glm::normalize(l.aim));
  p.c0 = vec3(photometric_c0(l));
}

// Direction and opening point drawn exactly from the file's distribution (equal power per
// photon), mapped from the luminaire frame (gamma = 0 along -z, C0 along +x) to the world.
// The origin is pushed off the opening's plane so a recessed or flush luminaire is not
// blocked by the ceiling it sits in.
EmittedRay emit_photometric(const PreparedLuminaire& l, PathRng& rng) {
  const PhotometricSampler& sampler = *l.source->sampler;
  const glm::dvec3 aim(l.axis), c0(l.c0);
  const glm::dvec3 o = lightsolver::to_world(sampler.sample_origin(rng), aim, c0);
  const glm::dvec3 d = lightsolver::to_world(sampler.sample_direction(rng), aim, c0);
  return {offset_ray_origin(l.position + vec3(o), l.axis), glm::normalize(vec3(d))};
}

// A uniform point o of the luminous opening (as emit_photometric draws it, pushed off the same
// way) and the traced intensity toward x from there: I(w) = flux * candela(w) / the table's
// integrated flux, the density emit_photometric draws directions from (independent of o).
LightSample direct_photometric(const PreparedLuminaire& l, const glm::dvec3& x, PathRng& rng) {
  const PhotometricSampler& sampler = *l.source->sampler;
  const glm::dvec3 aim(l.axis), c0(l.c0);
  const glm::dvec3 o = lightsolver::to_world(sampler.sample_origin(rng), aim, c0);
  const glm::dvec3 at(offset_ray_origin(l.position + vec3(o), l.axis));
  const glm::dvec3 v = x - at;
  const double d2 = glm::dot(v, v);
  if (!(d2 > 0.0) || !(sampler.integrated_flux_lm() > 0.0)) return {at, 0.0};
  // to_world maps local (x, y, z) to x c0 + y c90 - z aim (c90 = c0 x aim, orthonormal frame):
  // its inverse is the dot products.
  const glm::dvec3 w = v / std::sqrt(d2), c90 = glm::cross(c0, aim);
  const glm::dvec3 local{glm::dot(w, c0), glm::dot(w, c90), -glm::dot(w, aim)};
  const double intensity = l.flux_lm * sampler.intensity_cd(local) / sampler.integrated_flux_lm();
  return {at, intensity / d2};
}

// The lamp's output at its tilt (type C TILT tables; 1 otherwise).
double photometric_flux(const Luminaire& l) { return l.flux_lm * photometric_tilt_factor(l); }

// Largest gamma a type C file emits at: the cell past its last non-zero row still has light
// (intensity is interpolated across a cell). Other types: every direction.
double photometric_half_angle(const PhotometricData& d) {
  constexpr double kPi = std::numbers::pi;
  if (d.type != PhotometricType::C || d.vertical_angles_deg.empty()) return kPi;
  const std::size_t nv = d.vertical_angles_deg.size();
  std::size_t last = nv;  // none yet
  for (std::size_t h = 0; h < d.horizontal_angles_deg.size(); ++h) {
    for (std::size_t v = 0; v < nv; ++v) {
      if (d.candela_at(h, v) > 0.0 && (last == nv || v > last)) last = v;
    }
  }
  if (last == nv) return 0.0;  // emits nothing (0 lm: no support claim needed either way)
  const std::size_t edge = std::min(last + 1, nv - 1);
  return d.vertical_angles_deg[edge] * kPi / 180.0;
}

// From anywhere in the file's luminous opening, within its distribution's cone.
EmissionSupport support_photometric(const PreparedLuminaire& l) {
  EmissionSupport s = from_point(l, std::numbers::pi);
  const PhotometricData* d = l.source ? l.source->photometry.get() : nullptr;
  if (!d) return s;  // no file data: every direction, a generous opening
  s.radius = 0.5 * std::hypot(d->opening_length_m, d->opening_width_m, d->opening_height_m);
  s.half_angle_rad = photometric_half_angle(*d);
  return s;
}

// Intensity as traced: the file's candela scaled to the emitted flux, at its tilt.
GlareShape glare_photometric(const Luminaire& l) {
  if (!l.sampler || !(l.sampler->integrated_flux_lm() > 0.0)) return no_glare("emits nothing");
  GlareShape g;
  g.kind = GlareShape::Kind::PhotometricBody;
  g.centre = l.position;
  g.aim = glm::normalize(l.aim);
  g.c0 = photometric_c0(l);
  g.candela_scale = l.flux_lm / l.sampler->integrated_flux_lm() * photometric_tilt_factor(l);
  return g;
}

}  // namespace

LuminaireType photometric_luminaire_type() {
  return {.type = Luminaire::Type::Photometric,
          .name = "photometric",
          .keys = kPhotometricKeys,
          .read = read_photometric,
          .check = check_photometric,
          .prepare = prepare_photometric,
          .emit = emit_photometric,
          .emitted_flux = photometric_flux,
          .support = support_photometric,
          .glare_kind = GlareShape::Kind::PhotometricBody,
          .glare = glare_photometric,
          .effect = "photometric_emission",
          .anchor = at_position,
          .centre = at_position,
          .move_to = move_position,
          .aim = file_aim,
          .placed = true,
          .direct = direct_photometric};
}

}  // namespace lightsolver::detail
