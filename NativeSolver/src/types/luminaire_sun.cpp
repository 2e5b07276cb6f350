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

}  // namespace

// The glazing was checked (check_sun; direct_sun_lx checks its own openings').
double beam_glazing(const std::optional<GlazingDefinition>& g, double cos_i) {
  if (!g) return 1.0;
  const daylight::Glazing glazing{g->transmittance, static_cast<unsigned>(g->panes),
                                  g->frame_factor, g->maintenance_factor};
  return glazing.tau(cos_i) * glazing.factor();
}

// The disc's share through an opening whose normal n (into the room) makes cos θ = t = n·d with
// the beam: (1 / (π sin²α)) ∫_disc max(0, n·ω) dω, so that Φ = E · A · share. The disc wholly in
// front (t ≥ sin α): t exactly (the cap projects to π sin²α cos θ); wholly behind: 0; straddling
// the plane: the closed form of the projected solid angle of a cap cut by the horizon (Snyder
// 1996, "Area light sources for real-time graphics"; x = cot α, y = −x cot θ), its two O(α)
// terms cancelling to O(α³): relative error ~10⁻¹¹ in double, held to an independent quadrature
// (Tests/native/sun/sun_straddling_test.cpp). At θ = 90° it is (α − sin α cos α) / (π sin²α).
double sun_disc_share(double t) {
  const double sa = std::sin(kSunRadiusRad), ca = std::cos(kSunRadiusRad);
  if (t >= sa) return t;
  if (t <= -sa) return 0.0;
  const double st = std::sqrt((1.0 - t) * (1.0 + t));  // sin θ
  const double x = ca / sa;
  const double y = std::clamp(-x * t / st, -1.0, 1.0);
  const double sy = std::sqrt((1.0 - y) * (1.0 + y));
  const double i = (t * std::acos(y) - x * st * sy) * sa * sa + std::atan(st * sy / x);
  return std::clamp(i / (std::numbers::pi * sa * sa), 0.0, sa);
}

namespace {

// Portal k's flux: E · A · share(n·d) · τ(θ) · f (n = edge1 × edge2, into the room, as a sky's):
// the part of the disc in front of the portal, 0 for a portal with the disc wholly behind it.
// Glazing: τ at the disc's centre (θ ≤ 90°; for a straddling disc τ ≈ 0 there anyway).
double portal_flux(const Luminaire& l, std::size_t k) {
  const SkyDefinition::Portal& p = l.sky.portals[k];
  const glm::dvec3 area = glm::cross(p.edge1, p.edge2);
  const double t = glm::dot(glm::normalize(area), glm::normalize(l.direction));
  const double share = sun_disc_share(t);
  if (share <= 0.0) return 0.0;
  return l.illuminance_lx * glm::length(area) * share * beam_glazing(p.glazing, std::max(t, 0.0));
}

// A sun through the sky's portals (docs/daylight.md, "The sun through portals"): each portal's
// shape and glazing; the flux is the sum over the portals facing the sun. `corner`, `edge1` and
// `edge2` become the first portal's (the anchor the sun moves by).
void check_sun_portals(const LuminaireChecks& c, Luminaire& l) {
  for (std::size_t k = 0; k < l.sky.portals.size(); ++k) {
    const SkyDefinition::Portal& p = l.sky.portals[k];
    const std::string at = "portals[" + std::to_string(k) + "]";
    Luminaire edges;  // the shared parallelogram check, on this portal
    edges.corner = p.corner;
    edges.edge1 = p.edge1;
    edges.edge2 = p.edge2;
    c.parallelogram(edges, (at + "'s area is zero").c_str());
    if (p.glazing) glazing_factor(c, at + ".glazing", *p.glazing, 1.0);
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
  // The own opening passes the beam whichever way it turns: its inside is the disc centre's side,
  // so a disc straddling its plane passes its larger part (sun_disc_share, exact).
  const glm::dvec3 area = glm::cross(l.edge1, l.edge2);
  const double n_dot_d = std::abs(glm::dot(glm::normalize(area), glm::normalize(l.direction)));
  l.flux_lm = l.illuminance_lx * glm::length(area) * sun_disc_share(n_dot_d);
  // Glazing: the beam's τ(θ) at the disc's centre (τ is smooth: over the 0.265° disc its mean
  // differs from the centre's by ~τ''α²/4, below 10^-5), times frame and maintenance.
  if (l.glazing) l.flux_lm *= glazing_factor(c, "glazing", *l.glazing, n_dot_d);
  check_beam_flux(c, l);
}

// The record emit_sun reads (Shaders/shared/luminaires.h): axis d (the beam), position u (d's
// direction along the opening's plane), half_beam_rad sin α (the disc's angular radius),
// half_field_rad n·d (n = edge1 × edge2, normalised) and cos_half_field 1 − sin θ cos α, where
// cos θ = |n·d|, computed without cancellation (1 − sin θ = cos² θ / (1 + sin θ)). A disc
// straddling the plane (|n·d| < sin α): cos_half_field −sin(e_c + α) (e_c = asin(n·d), the
// centre's elevation above the plane; the top of the disc), 10⁻⁵ high so that the float sampler's
// box holds the whole cap; the own opening (`own`, two-sided) has its edges swapped to turn n
// toward the disc's centre.
void prepare_opening(const Luminaire& l, glm::dvec3 e1, glm::dvec3 e2, PreparedLuminaire& p,
                     bool own) {
  const glm::dvec3 d = glm::normalize(l.direction);
  const double sa = std::sin(kSunRadiusRad), ca = std::cos(kSunRadiusRad);
  glm::dvec3 n = glm::normalize(glm::cross(e1, e2));
  double t = glm::dot(n, d);
  if (own && t < 0.0 && -t < sa) {
    std::swap(e1, e2);
    std::swap(p.edge1, p.edge2);
    n = -n;
    t = -t;
  }
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
  if (std::abs(t) < sa) {  // sin(e_c + α) = t cos α + cos e_c sin α, cos e_c = sin θ
    p.cos_half_field = static_cast<float>(-(t * ca + sin_theta * sa) * (1.0 + 1e-5));
  }
}

// The sun's own opening, or one record per portal facing the sun (placed relative to the first
// portal, the prepared corner: no float rounding of far coordinates), chosen by flux.
void prepare_sun(const Luminaire& l, PreparedLuminaire& p) {
  prepare_opening(l, l.edge1, l.edge2, p, l.sky.portals.empty());
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
    prepare_opening(l, portal.edge1, portal.edge2, r, false);
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
