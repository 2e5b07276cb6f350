// The sun luminaire type (docs/scene-format.md, `sun`; docs/daylight.md, "Sun"): the directional
// beam through a parallelogram opening, its direction given or computed from a site and a time,
// its directions spread over the solar disc. Its row of the table in luminaire_types.cpp; the
// emission both backends run is `emit_sun` in Shaders/shared/luminaires.h.
#include <algorithm>
#include <bit>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "daylight/sky_glazing.hpp"
#include "io/json_reader.hpp"
#include "lightsolver/daylight.hpp"
#include "model/prepared_scene.hpp"
#include "types/luminaire_rows.hpp"

namespace lightsolver::detail {
namespace {

using namespace luminaire_rows;

// The solar disc's angular diameter, 0.53° (its mean; 0.524° … 0.542° over the year).
constexpr double kSunDiameterDeg = 0.53;
constexpr double kSunRadiusRad = 0.5 * kSunDiameterDeg * std::numbers::pi / 180.0;

constexpr const char* kSunKeys[] = {"name",  "type",  "illuminance_lx", "direction",
                                    "site",  "time",  "north_deg",      "corner",
                                    "edge1", "edge2", "glazing",        "portals"};
constexpr const char* kSiteKeys[] = {"latitude_deg", "longitude_deg", "elevation_m"};

void read_sun(const JsonNode& n, Luminaire& l, const std::string&) {
  n.require_object(kSunKeys);
  l.illuminance_lx = n.at("illuminance_lx").number();
  if (n.has("portals")) {  // the sky's portals, each with its own glazing
    for (const char* key : {"corner", "edge1", "edge2", "glazing"}) {
      if (n.has(key)) {
        n.at(key).fail(
            "a sun through `portals` takes no opening of its own (each portal "
            "carries its glazing)");
      }
    }
    l.sky.portals = read_portals(n.at("portals"));
    if (l.sky.portals.empty()) n.at("portals").fail("must list at least one portal");
  } else {
    l.corner = n.at("corner").vec3();
    l.edge1 = n.at("edge1").vec3();
    l.edge2 = n.at("edge2").vec3();
    if (n.has("glazing")) l.glazing = read_glazing(n.at("glazing"));
  }
  const bool computed = n.has("site") || n.has("time") || n.has("north_deg");
  if (n.has("direction") == computed)
    n.fail("a sun gives either its beam's `direction` or `site` and `time` (with `north_deg`)");
  if (!computed) {
    l.direction = n.at("direction").vec3();
    return;
  }
  const JsonNode site = n.at("site");
  site.require_object(kSiteKeys);
  l.site = Site{site.at("latitude_deg").number(), site.at("longitude_deg").number(),
                site.number_or("elevation_m", 0.0)};
  l.time = n.at("time").string();
  l.north_deg = n.number_or("north_deg", 0.0);
}

// The sun position's own error as the scene's: its key (site.latitude_deg, time, north_deg) and
// its message without the "sun position: field: " the library puts first.
[[noreturn]] void fail_as_scene(const LuminaireChecks& c, const InputError& e) {
  std::string what = e.what();
  const std::string prefix = e.file() + ": " + e.where() + ": ";
  if (what.rfind(prefix, 0) == 0) what = what.substr(prefix.size());
  const std::string& w = e.where();
  const std::string key = w.rfind("time", 0) == 0 ? "time" : w == "north_deg" ? w : "site." + w;
  c.fail(key.c_str(), what);
  throw e;  // not reached (fail throws); GCC does not carry [[noreturn]] through a virtual call
}

// The beam's direction from the site and time: the way the light travels, away from the sun.
void position_the_sun(const LuminaireChecks& c, Luminaire& l) {
  try {
    l.sun = sun_position(*l.site, parse_iso8601(l.time, std::nullopt, "time"));
    l.direction = -sun_direction(*l.sun, l.north_deg);
  } catch (const InputError& e) {
    fail_as_scene(c, e);
  }
}

// The factor glazing puts on a beam at cos θ = `cos_i` to its opening (1: an open hole); the
// glazing was checked (check_sun).
double beam_glazing(const std::optional<GlazingDefinition>& g, double cos_i) {
  if (!g) return 1.0;
  const daylight::Glazing glazing{g->transmittance, static_cast<unsigned>(g->panes),
                                  g->frame_factor, g->maintenance_factor};
  return glazing.tau(cos_i) * glazing.factor();
}

// Portal k's flux: E · A · (n·d) · τ(θ) · f for a portal facing the sun (n = edge1 × edge2, into
// the room, as a sky's), 0 for one facing away. The disc must not straddle its plane.
double portal_flux(const Luminaire& l, std::size_t k) {
  const SkyDefinition::Portal& p = l.sky.portals[k];
  const glm::dvec3 area = glm::cross(p.edge1, p.edge2);
  const double t = glm::dot(glm::normalize(area), glm::normalize(l.direction));
  if (t <= 0.0) return 0.0;
  return l.illuminance_lx * glm::length(area) * t * beam_glazing(p.glazing, t);
}

// A sun through the sky's portals (docs/daylight.md, "The sun through portals"): each portal's
// shape and glazing; the flux is the sum over the portals facing the sun. `corner`, `edge1` and
// `edge2` become the first portal's (the anchor the sun moves by).
void check_sun_portals(const LuminaireChecks& c, Luminaire& l) {
  const double sin_alpha = std::sin(kSunRadiusRad);
  const glm::dvec3 d = glm::normalize(l.direction);
  for (std::size_t k = 0; k < l.sky.portals.size(); ++k) {
    const SkyDefinition::Portal& p = l.sky.portals[k];
    const std::string at = "portals[" + std::to_string(k) + "]";
    Luminaire edges;  // the shared parallelogram check, on this portal
    edges.corner = p.corner;
    edges.edge1 = p.edge1;
    edges.edge2 = p.edge2;
    c.parallelogram(edges, (at + "'s area is zero").c_str());
    if (p.glazing) glazing_factor(c, at + ".glazing", *p.glazing, 1.0);
    const double t = glm::dot(glm::normalize(glm::cross(p.edge1, p.edge2)), d);
    const bool below = l.sun && l.sun->elevation_deg <= 0.0;
    if (!below && std::abs(t) < sin_alpha) {
      c.fail(at.c_str(),
             "the sun's disc (0.53°) reaches the portal's plane: the beam runs within " +
                 show(std::asin(std::abs(t)) * 180.0 / std::numbers::pi) +
                 "° of it (a sun through a window in its own wall's plane is not traced yet)");
    }
  }
  const SkyDefinition::Portal& first = l.sky.portals.front();
  l.corner = first.corner;
  l.edge1 = first.edge1;
  l.edge2 = first.edge2;
  l.flux_lm = 0.0;
  if (l.sun && l.sun->elevation_deg <= 0.0) return;  // below the horizon: switched off
  for (std::size_t k = 0; k < l.sky.portals.size(); ++k) l.flux_lm += portal_flux(l, k);
  check_beam_flux(c, l);
}

void check_sun(const LuminaireChecks& c, Luminaire& l) {
  if (l.site) {
    position_the_sun(c, l);
  } else {
    unit_direction(c, "direction", l.direction);
  }
  if (!l.sky.portals.empty()) {
    check_beam_illuminance(c, l);
    check_sun_portals(c, l);
    return;
  }
  c.parallelogram(l, "the area is zero");
  check_beam_illuminance(c, l);
  if (l.glazing) glazing_factor(c, "glazing", *l.glazing, 1.0);  // its keys, even below the horizon
  // Below the horizon (its centre, refraction included) the sun lights nothing: switched off.
  if (l.sun && l.sun->elevation_deg <= 0.0) {
    l.flux_lm = 0.0;
    return;
  }
  const double n_dot_d =
      std::abs(glm::dot(glm::normalize(glm::cross(l.edge1, l.edge2)), l.direction));
  if (n_dot_d <= std::sin(kSunRadiusRad)) {
    c.fail(l.site ? "time" : "direction",
           "the sun's disc (0.53°) reaches the plane of its opening: the beam runs within " +
               show(std::asin(n_dot_d) * 180.0 / std::numbers::pi) +
               "° of the parallelogram; turn the opening toward the sun");
  }
  l.flux_lm = directional_flux_lm(l);  // E · area · |n·d|: exact for the disc (luminaires.h)
  // Glazing: the beam's τ(θ) at the disc's centre (τ is smooth: over the 0.265° disc its mean
  // differs from the centre's by ~τ''α²/4, below 10^-5), times frame and maintenance.
  if (l.glazing) l.flux_lm *= glazing_factor(c, "glazing", *l.glazing, n_dot_d);
  check_beam_flux(c, l);
}

// The record emit_sun reads (Shaders/shared/luminaires.h): axis d (the beam), position u (d's
// direction along the opening's plane), half_beam_rad sin α (the disc's angular radius),
// half_field_rad n·d (n = edge1 × edge2, normalised) and cos_half_field 1 − sin θ cos α, where
// cos θ = |n·d|, computed without cancellation (1 − sin θ = cos² θ / (1 + sin θ)).
void prepare_opening(const Luminaire& l, const glm::dvec3& e1, const glm::dvec3& e2,
                     PreparedLuminaire& p) {
  const glm::dvec3 d = glm::normalize(l.direction);
  const glm::dvec3 n = glm::normalize(glm::cross(e1, e2));
  const double t = glm::dot(n, d);
  const glm::dvec3 along = d - t * n;
  const double sin_theta = glm::length(along);
  const glm::dvec3 u = sin_theta > 1e-12 ? along / sin_theta : glm::normalize(e1);
  const double half = std::sin(0.5 * kSunRadiusRad);
  p.axis = vec3(d);
  p.position = vec3(u);
  p.half_beam_rad = static_cast<float>(std::sin(kSunRadiusRad));
  p.half_field_rad = static_cast<float>(t);
  p.cos_half_field =
      static_cast<float>(2.0 * half * half + std::cos(kSunRadiusRad) * t * t / (1.0 + sin_theta));
}

// The sun's own opening, or one record per portal facing the sun (placed relative to the first
// portal, the prepared corner: no float rounding of far coordinates), chosen by flux.
void prepare_sun(const Luminaire& l, PreparedLuminaire& p) {
  prepare_opening(l, l.edge1, l.edge2, p);
  if (l.sky.portals.empty()) return;
  double total = 0.0;
  std::vector<double> flux;
  for (std::size_t k = 0; k < l.sky.portals.size(); ++k) {
    const double f = portal_flux(l, k);
    if (!(f > 0.0)) continue;
    const SkyDefinition::Portal& portal = l.sky.portals[k];
    PreparedLuminaire r = p;
    r.corner = p.corner + vec3(portal.corner - l.corner);
    r.edge1 = vec3(portal.edge1);
    r.edge2 = vec3(portal.edge2);
    prepare_opening(l, portal.edge1, portal.edge2, r);
    p.portals.push_back(r);
    flux.push_back(total += f);
  }
  for (double f : flux) p.portal_cdf.push_back(f / total);
}

// The shared emission, through an opening: its way out is tested (Shaders/shared/luminaires.h,
// opening_escape_origin; the origin was pushed along the beam).
EmittedRay emit_sun(const PreparedLuminaire& l, PathRng& rng) {
  EmittedRay ray;
  if (l.portals.empty()) {
    shared::emit_sun(l, ray.origin, ray.direction, rng);
  } else {  // a portal by flux, drawn as pick_luminaire draws (the GPU compares 53-bit integers)
    const double u = rng.uniform_double();
    const auto it = std::upper_bound(l.portal_cdf.begin(), l.portal_cdf.end(), u);
    const std::size_t k = std::min<std::size_t>(it - l.portal_cdf.begin(), l.portals.size() - 1);
    shared::emit_sun(l.portals[k], ray.origin, ray.direction, rng);
  }
  ray.opening_push = l.axis;
  return ray;
}

EmissionSupport support_sun(const PreparedLuminaire& l) {
  EmissionSupport s;
  s.axis = glm::normalize(glm::dvec3(l.axis));
  for (const PreparedLuminaire& o :
       l.portals.empty() ? std::vector<PreparedLuminaire>{l} : l.portals) {
    const glm::dvec3 corner(o.corner), e1(o.edge1), e2(o.edge2);
    s.points.insert(s.points.end(), {corner, corner + e1, corner + e2, corner + e1 + e2});
  }
  s.half_angle_rad = kSunRadiusRad;
  return s;
}

GlareShape glare_sun(const Luminaire&) {
  return no_glare("the sun's beam (daylight) is not a luminaire in the field of view");
}

double own_flux(const Luminaire& l) { return l.flux_lm; }
glm::dvec3 at_corner(const Luminaire& l) { return l.corner; }
glm::dvec3 centre(const Luminaire& l) { return l.corner + 0.5 * (l.edge1 + l.edge2); }
// Moves the opening, or every portal with the first (the anchor).
void move_opening(Luminaire& l, const glm::dvec3& c) {
  const glm::dvec3 delta = c - 0.5 * (l.edge1 + l.edge2) - l.corner;
  l.corner += delta;
  for (auto& p : l.sky.portals) p.corner += delta;
}
// A given beam can be aimed; a sun placed by site and time cannot (its time is the variable).
glm::dvec3* aim_sun(Luminaire& l) { return l.site ? nullptr : &l.direction; }

}  // namespace

std::uint32_t pack_sun_record(const PreparedLuminaire& l, std::vector<float>& floats,
                              std::vector<std::uint64_t>& thresholds,
                              std::uint64_t (*threshold)(double c, double total)) {
  if (l.portals.empty()) return 0xFFFFFFFFu;
  const auto base = static_cast<std::uint32_t>(floats.size());
  floats.push_back(std::bit_cast<float>(static_cast<std::uint32_t>(l.portals.size())));
  floats.push_back(std::bit_cast<float>(static_cast<std::uint32_t>(thresholds.size())));
  for (double c : l.portal_cdf) thresholds.push_back(threshold(c, 1.0));
  for (const PreparedLuminaire& p : l.portals) {
    for (const vec3& v : {p.corner, p.edge1, p.edge2, p.position}) {
      floats.insert(floats.end(), {v.x, v.y, v.z});
    }
    floats.insert(floats.end(), {p.half_field_rad, p.cos_half_field});
  }
  return base;
}

LuminaireType sun_luminaire_type() {
  return {.type = Luminaire::Type::Sun,
          .name = "sun",
          .keys = kSunKeys,
          .read = read_sun,
          .check = check_sun,
          .prepare = prepare_sun,
          .emit = emit_sun,
          .emitted_flux = own_flux,
          .support = support_sun,
          .glare_kind = GlareShape::Kind::None,
          .glare = glare_sun,
          .effect = "sun_emission",
          .anchor = at_corner,
          .centre = centre,
          .move_to = move_opening,
          .aim = aim_sun,
          .placed = false};
}

}  // namespace lightsolver::detail
