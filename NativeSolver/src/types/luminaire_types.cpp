// The luminaire types, one section each: scene-file keys, value checks, emission parameters and
// the CPU emission itself (the point's, area's and directional's are Shaders/shared/luminaires.h,
// the text the GPU runs too). Numbers and messages are those the reader, validator, prepare() and
// emitter had before the table; the golden results (Tests/golden) pin that nothing moved.
#include "types/luminaire_types.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <numbers>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "io/json_reader.hpp"
#include "types/luminaire_rows.hpp"
#include "model/prepared_scene.hpp"
#include "model/sampling.hpp"
#include "lightsolver/photometry.hpp"
#include "shared/spot.h"

namespace lightsolver::detail {
namespace luminaire_rows {

// Numbers in messages: 6 significant digits, as the validator prints them.
std::string show(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

glm::dvec3 at_position(const Luminaire& l) { return l.position; }
void move_position(Luminaire& l, const glm::dvec3& c) { l.position = c; }
glm::dvec3* file_aim(Luminaire& l) { return &l.aim; }

EmissionSupport from_point(const PreparedLuminaire& l, double half_angle_rad) {
  EmissionSupport s;
  s.axis = glm::normalize(glm::dvec3(l.axis));
  s.points = {glm::dvec3(l.position)};
  s.half_angle_rad = half_angle_rad;
  return s;
}

GlareShape no_glare(std::string why_not) {
  GlareShape g;
  g.why_not = std::move(why_not);
  return g;
}

void unit_direction(const LuminaireChecks& c, const char* key, glm::dvec3& v) {
  c.direction(key, v);
  v = glm::normalize(v);
}

void check_beam_illuminance(const LuminaireChecks& c, const Luminaire& l) {
  if (!(l.illuminance_lx >= 0.0 && std::isfinite(l.illuminance_lx))) {
    c.fail("illuminance_lx", "must be a finite value >= 0 (got " + show(l.illuminance_lx) + ")");
  }
  if (l.illuminance_lx > limits::kMaxIlluminance_lx) {
    c.fail("illuminance_lx", "more than 10^7 lx (got " + show(l.illuminance_lx) +
                                 "; direct sunlight is about 10^5 lx)");
  }
}

void check_beam_flux(const LuminaireChecks& c, const Luminaire& l) {
  if (!(l.flux_lm <= limits::kMaxFlux_lm)) {
    c.fail("illuminance_lx", "the beam carries " + show(l.flux_lm) +
                                 " lm (illuminance_lx x the opening's area across the beam), "
                                 "more than 10^12 lm: beyond any physical light source");
  }
}

}  // namespace luminaire_rows

namespace {

using namespace luminaire_rows;

void read_parallelogram(const JsonNode& n, Luminaire& l) {
  l.corner = n.at("corner").vec3();
  l.edge1 = n.at("edge1").vec3();
  l.edge2 = n.at("edge2").vec3();
}

glm::dvec3 at_corner(const Luminaire& l) { return l.corner; }
glm::dvec3 centre_of_parallelogram(const Luminaire& l) {
  return l.corner + 0.5 * (l.edge1 + l.edge2);
}
void move_parallelogram(Luminaire& l, const glm::dvec3& c) {
  l.corner = c - 0.5 * (l.edge1 + l.edge2);
}
glm::dvec3* no_aim(Luminaire&) { return nullptr; }
glm::dvec3* direction_aim(Luminaire& l) { return &l.direction; }

double own_flux(const Luminaire& l) { return l.flux_lm; }

// Support from a parallelogram's corners (a half space or a beam along the axis), in the
// prepared luminaire's local coordinates.
EmissionSupport from_parallelogram(const PreparedLuminaire& l, double half_angle_rad) {
  EmissionSupport s;
  s.axis = glm::normalize(glm::dvec3(l.axis));
  const glm::dvec3 corner(l.corner), e1(l.edge1), e2(l.edge2);
  s.points = {corner, corner + e1, corner + e2, corner + e1 + e2};
  s.half_angle_rad = half_angle_rad;
  return s;
}

GlareShape small_source_glare(const Luminaire&) {
  return no_glare(
      "a point or spot luminaire has no luminous area (CIE 117 needs one; CIE 147's "
      "small-source rating is not implemented)");
}

// --- point: isotropic ---------------------------------------------------------------------

constexpr const char* kPointKeys[] = {"name", "type", "flux_lm", "position"};

void read_point(const JsonNode& n, Luminaire& l, const std::string&) {
  n.require_object(kPointKeys);
  l.position = n.at("position").vec3();
  l.flux_lm = n.at("flux_lm").number();
}

void check_point(const LuminaireChecks& c, Luminaire& l) {
  c.coordinates("position", l.position);
  c.flux(l, "");
}

void prepare_point(const Luminaire& l, PreparedLuminaire& p) { p.axis = vec3(l.direction); }

EmissionSupport support_point(const PreparedLuminaire& l) {
  return from_point(l, std::numbers::pi);
}

// From a point of intensity I toward x: I / d^2 on a surface facing it.
LightSample from_point_intensity(const glm::dvec3& at, const glm::dvec3& x, double intensity_cd) {
  const glm::dvec3 v = at - x;
  const double d2 = glm::dot(v, v);
  return {at, d2 > 0.0 ? intensity_cd / d2 : 0.0};
}

// Isotropic: I = flux / (4 pi).
LightSample direct_point(const PreparedLuminaire& l, const glm::dvec3& x, PathRng&) {
  return from_point_intensity(glm::dvec3(l.position), x, l.flux_lm / (4.0 * std::numbers::pi));
}

// --- spot: smooth beam/field profile about an axis ------------------------------------------

constexpr const char* kSpotKeys[] = {"name",      "type",           "flux_lm",        "position",
                                     "direction", "beam_angle_deg", "field_angle_deg"};

void read_spot(const JsonNode& n, Luminaire& l, const std::string&) {
  n.require_object(kSpotKeys);
  l.position = n.at("position").vec3();
  l.direction = n.at("direction").vec3();
  l.beam_angle_deg = n.at("beam_angle_deg").number();
  l.field_angle_deg = n.at("field_angle_deg").number();
  l.flux_lm = n.at("flux_lm").number();
}

void check_spot(const LuminaireChecks& c, Luminaire& l) {
  c.coordinates("position", l.position);
  unit_direction(c, "direction", l.direction);
  if (!(l.beam_angle_deg > 0.0 && l.beam_angle_deg < l.field_angle_deg)) {
    c.fail("beam_angle_deg", "need 0 < beam_angle_deg < field_angle_deg");
  }
  if (!(l.field_angle_deg <= 360.0)) c.fail("field_angle_deg", "must be <= 360");
  c.flux(l, "");
}

// The profile's solid angle, 2 pi * integral of profile(t) sin t dt over the field: piecewise
// linear in t, so Simpson's rule on each piece with 512 panels is exact to ~1e-12.
double spot_solid_angle(double half_beam, double half_field) {
  const auto piece = [&](double a, double b) {
    constexpr int kPanels = 512;
    const double h = (b - a) / kPanels;
    double sum = 0.0;
    for (int i = 0; i <= kPanels; ++i) {
      const double t = a + i * h;
      const double w = (i == 0 || i == kPanels) ? 1.0 : (i % 2 ? 4.0 : 2.0);
      sum += w * spot_profile(t, half_beam, half_field) * std::sin(t);
    }
    return sum * h / 3.0;
  };
  return 2.0 * std::numbers::pi * (piece(0.0, half_beam) + piece(half_beam, half_field));
}

void prepare_spot(const Luminaire& l, PreparedLuminaire& p) {
  p.half_beam_rad = static_cast<float>(glm::radians(0.5 * l.beam_angle_deg));
  p.half_field_rad = static_cast<float>(glm::radians(0.5 * l.field_angle_deg));
  p.cos_half_field = std::cos(p.half_field_rad);  // in float, as the GPU computes it
  p.axis = vec3(l.direction);
  p.direct_norm = spot_solid_angle(p.half_beam_rad, p.half_field_rad);
}

EmissionSupport support_spot(const PreparedLuminaire& l) { return from_point(l, l.half_field_rad); }

// I(theta) = flux * profile(theta) / (the profile's solid angle): emit_spot's density.
LightSample direct_spot(const PreparedLuminaire& l, const glm::dvec3& x, PathRng&) {
  const glm::dvec3 at(l.position), to_x = x - at;
  const double d = glm::length(to_x);
  if (!(d > 0.0) || !(l.direct_norm > 0.0)) return {at, 0.0};
  const double cos_t = std::clamp(glm::dot(to_x / d, glm::dvec3(l.axis)), -1.0, 1.0);
  if (cos_t < double(l.cos_half_field)) return {at, 0.0};  // outside the cone emit_spot draws in
  const double f = spot_profile(std::acos(cos_t), l.half_beam_rad, l.half_field_rad);
  return from_point_intensity(at, x, l.flux_lm * f / l.direct_norm);
}

}  // namespace

// Relative spot intensity: piecewise linear in angle through (0, 1), (beam/2, 0.5),
// (field/2, 0.1), and 0 beyond field/2. The formula is Shaders/shared/spot.h, which the shaders
// include too (in float there).
double spot_profile(double theta, double half_beam, double half_field) {
  return shared::spot_profile<double>(theta, half_beam, half_field);
}

namespace {

// Rejection sampling of the spot profile inside the field cone: uniform in solid angle over
// the cone, accepted with probability equal to the relative intensity. Exact, and the
// acceptance rate stays above 0.2 for any valid beam/field pair.
EmittedRay emit_spot(const PreparedLuminaire& l, PathRng& rng) {
  for (;;) {
    const float cos_t = 1.0f - rng.uniform() * (1.0f - l.cos_half_field);
    const float phi = 2.0f * std::numbers::pi_v<float> * rng.uniform();
    const float theta = std::acos(std::clamp(cos_t, -1.0f, 1.0f));
    const double f = spot_profile(theta, l.half_beam_rad, l.half_field_rad);
    if (rng.uniform() < f) return {l.position, cone_direction(cos_t, phi, l.axis)};
  }
}

// --- area: Lambertian parallelogram, emitting along edge1 x edge2 ---------------------------

constexpr const char* kAreaKeys[] = {"name", "type", "flux_lm", "corner", "edge1", "edge2"};

void read_area(const JsonNode& n, Luminaire& l, const std::string&) {
  n.require_object(kAreaKeys);
  read_parallelogram(n, l);
  l.flux_lm = n.at("flux_lm").number();
}

void check_area(const LuminaireChecks& c, Luminaire& l) {
  c.parallelogram(l, "the area is zero");
  c.flux(l, "");
}

void prepare_area(const Luminaire& l, PreparedLuminaire& p) {
  p.axis = vec3(glm::normalize(glm::cross(l.edge1, l.edge2)));
}

EmissionSupport support_area(const PreparedLuminaire& l) {
  return from_parallelogram(l, 0.5 * std::numbers::pi);
}

// A uniform point p of the parallelogram (pushed off it as emit_area pushes photons): radiance
// L = flux / (pi A) seen at cos_e, over 1/A of density: L cos_e A / d^2 on a surface facing p.
LightSample direct_area(const PreparedLuminaire& l, const glm::dvec3& x, PathRng& rng) {
  const vec3 p = offset_ray_origin(point_on_parallelogram(l.corner, l.edge1, l.edge2, rng), l.axis);
  const glm::dvec3 at(p), v = x - at;
  const double d2 = glm::dot(v, v);
  const double cos_e = glm::dot(v, glm::dvec3(l.axis)) / std::sqrt(d2);
  if (!(d2 > 0.0) || !(cos_e > 0.0)) return {at, 0.0};
  // flux / (pi A) * cos_e * A / d^2: the area cancels.
  return {at, l.flux_lm / std::numbers::pi * cos_e / d2};
}

// Uniform luminance over the rectangle toward its front: L = flux / (pi A).
GlareShape glare_area(const Luminaire& l) {
  GlareShape g;
  g.kind = GlareShape::Kind::LambertianArea;
  g.centre = centre_of_parallelogram(l);
  g.normal = glm::cross(l.edge1, l.edge2);
  g.area_m2 = glm::length(g.normal);
  g.flux_lm = l.flux_lm;
  return g;
}

// --- directional: a parallel beam (sunlight) through a parallelogram opening ----------------

constexpr const char* kDirectionalKeys[] = {"name",   "type",  "illuminance_lx", "direction",
                                            "corner", "edge1", "edge2"};

void read_directional(const JsonNode& n, Luminaire& l, const std::string&) {
  n.require_object(kDirectionalKeys);
  l.direction = n.at("direction").vec3();
  l.illuminance_lx = n.at("illuminance_lx").number();
  read_parallelogram(n, l);
}

// Its flux follows from the illuminance and the opening: derived here, then bounded.
void check_directional(const LuminaireChecks& c, Luminaire& l) {
  unit_direction(c, "direction", l.direction);
  c.parallelogram(l, "the area is zero");
  check_beam_illuminance(c, l);
  if (std::abs(glm::dot(glm::normalize(glm::cross(l.edge1, l.edge2)), l.direction)) < 1e-9) {
    c.fail("direction", "the beam runs parallel to its parallelogram");
  }
  l.flux_lm = directional_flux_lm(l);
  check_beam_flux(c, l);
}

void prepare_directional(const Luminaire& l, PreparedLuminaire& p) { p.axis = vec3(l.direction); }

EmissionSupport support_directional(const PreparedLuminaire& l) {
  return from_parallelogram(l, 0.0);
}

// The beam reaches x when the line back against it meets the opening: its illuminance across
// the beam, flux / (A |n.d|), from the opening's point q (deterministic: no random number).
LightSample direct_directional(const PreparedLuminaire& l, const glm::dvec3& x, PathRng&) {
  const glm::dvec3 d(l.axis), c(l.corner), e1(l.edge1), e2(l.edge2);
  const glm::dvec3 n = glm::cross(e1, e2);
  const double across = std::abs(glm::dot(n, d));  // A |n.d|
  const double denom = glm::dot(n, d);
  if (!(across > 0.0)) return {c, 0.0};
  const double t = glm::dot(c - x, n) / denom;  // x + t d on the opening's plane
  if (!(t < 0.0)) return {c, 0.0};              // the opening must lie upstream of x
  const glm::dvec3 q = x + t * d;
  // q's coordinates in (e1, e2): dual vectors in the plane.
  const double g11 = glm::dot(e1, e1), g12 = glm::dot(e1, e2), g22 = glm::dot(e2, e2);
  const double det = g11 * g22 - g12 * g12;
  const glm::dvec3 rel = q - c;
  const double r1 = glm::dot(rel, e1), r2 = glm::dot(rel, e2);
  const double a = (g22 * r1 - g12 * r2) / det, b = (g11 * r2 - g12 * r1) / det;
  if (!(a >= 0.0 && a < 1.0 && b >= 0.0 && b < 1.0)) return {c, 0.0};
  const vec3 from = offset_ray_origin(vec3(q), l.axis);  // as emit_directional pushes photons
  return {glm::dvec3(from), l.flux_lm / across};
}

GlareShape glare_directional(const Luminaire&) {
  return no_glare("a directional beam (daylight) is not a luminaire in the field of view");
}

using T = Luminaire::Type;
using G = GlareShape::Kind;
const auto kTypes = std::to_array<LuminaireType>({
    {.type = T::Point,
     .name = "point",
     .keys = kPointKeys,
     .read = read_point,
     .check = check_point,
     .prepare = prepare_point,
     .emit = shared_emission<shared::emit_point>,
     .emitted_flux = own_flux,
     .support = support_point,
     .glare_kind = G::None,
     .glare = small_source_glare,
     .effect = "point_emission",
     .anchor = at_position,
     .centre = at_position,
     .move_to = move_position,
     .aim = no_aim,
     .placed = true,
     .direct = direct_point},
    {.type = T::Spot,
     .name = "spot",
     .keys = kSpotKeys,
     .read = read_spot,
     .check = check_spot,
     .prepare = prepare_spot,
     .emit = emit_spot,
     .emitted_flux = own_flux,
     .support = support_spot,
     .glare_kind = G::None,
     .glare = small_source_glare,
     .effect = "spot_emission",
     .anchor = at_position,
     .centre = at_position,
     .move_to = move_position,
     .aim = direction_aim,
     .placed = true,
     .direct = direct_spot},
    {.type = T::Area,
     .name = "area",
     .keys = kAreaKeys,
     .read = read_area,
     .check = check_area,
     .prepare = prepare_area,
     .emit = shared_emission<shared::emit_area>,
     .emitted_flux = own_flux,
     .support = support_area,
     .glare_kind = G::LambertianArea,
     .glare = glare_area,
     .effect = "area_emission",
     .anchor = at_corner,
     .centre = centre_of_parallelogram,
     .move_to = move_parallelogram,
     .aim = no_aim,
     .placed = true,
     .direct = direct_area},
    {.type = T::Directional,
     .name = "directional",
     .keys = kDirectionalKeys,
     .read = read_directional,
     .check = check_directional,
     .prepare = prepare_directional,
     .emit = shared_emission<shared::emit_directional>,
     .emitted_flux = own_flux,
     .support = support_directional,
     .glare_kind = G::None,
     .glare = glare_directional,
     .effect = "directional_emission",
     .anchor = at_corner,
     .centre = centre_of_parallelogram,
     .move_to = move_parallelogram,
     .aim = direction_aim,
     .placed = false,
     .direct = direct_directional},
    photometric_luminaire_type(),
    sun_luminaire_type(),
    sky_luminaire_type(),
});
static_assert(kTypes.size() <= kMaxLuminaireTypes);

}  // namespace

void read_luminaire_keys(const LuminaireType& row, const JsonNode& n, Luminaire& l,
                         const std::string& base_dir) {
  if (!n.has("power_w") && !n.has("group")) return row.read(n, l, base_dir);
  if (n.has("power_w")) l.power_w = n.at("power_w").number();  // range: validate()
  if (n.has("group")) {
    l.group = n.at("group").string();
    if (l.group.empty()) n.at("group").fail("must be a non-empty name (leave it out: own group)");
  }
  nlohmann::json own = n.object();
  own.erase("power_w");
  own.erase("group");
  row.read(JsonNode(own, n.path(), n.file()), l, base_dir);
}

std::span<const LuminaireType> luminaire_types() { return kTypes; }

std::size_t luminaire_type_index(Luminaire::Type type) {
  return static_cast<std::size_t>(&luminaire_type(type) - kTypes.data());
}

const LuminaireType& luminaire_type(Luminaire::Type type) {
  for (const auto& row : kTypes) {
    if (row.type == type) return row;
  }
  throw std::logic_error("luminaire type without a row in luminaire_types.cpp");
}

const LuminaireType* find_luminaire_type(std::string_view name) {
  for (const auto& row : kTypes) {
    if (name == row.name) return &row;
  }
  return nullptr;
}

namespace {

// "a, b or c" of the rows `keep` accepts.
template <class Keep>
std::string names_of(Keep keep) {
  std::vector<const char*> names;
  for (const auto& row : kTypes) {
    if (keep(row)) names.push_back(row.name);
  }
  std::string s;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) s += i + 1 == names.size() ? " or " : ", ";
    s += names[i];
  }
  return s;
}

}  // namespace

std::string luminaire_type_names() {
  return names_of([](const LuminaireType&) { return true; });
}

std::string aimable_luminaire_type_names() {
  // Asks the hook with a scratch luminaire: a row aims a field or it does not.
  return names_of([](const LuminaireType& row) {
    Luminaire scratch;
    return row.aim(scratch) != nullptr;
  });
}

}  // namespace lightsolver::detail

namespace lightsolver {
namespace {

// Exact integral of (a + b*theta) sin(theta) over [t0, t1].
double linear_times_sin(double a, double b, double t0, double t1) {
  auto F = [&](double t) { return -a * std::cos(t) + b * (std::sin(t) - t * std::cos(t)); };
  return F(t1) - F(t0);
}

}  // namespace

double spot_relative_intensity(const Luminaire& l, double angle_rad) {
  return detail::spot_profile(angle_rad, glm::radians(0.5 * l.beam_angle_deg),
                              glm::radians(0.5 * l.field_angle_deg));
}

double spot_peak_intensity_cd(const Luminaire& l) {
  const double hb = glm::radians(0.5 * l.beam_angle_deg);
  const double hf = glm::radians(0.5 * l.field_angle_deg);
  // Solid-angle integral of the profile: 2*pi * sum over both linear pieces.
  const double inner = linear_times_sin(1.0, -0.5 / hb, 0.0, hb);
  const double slope = -0.4 / (hf - hb);
  const double outer = linear_times_sin(0.5 - slope * hb, slope, hb, hf);
  return l.flux_lm / (2.0 * std::numbers::pi * (inner + outer));
}

}  // namespace lightsolver
