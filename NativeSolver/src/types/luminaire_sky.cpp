// The sky luminaire type (docs/daylight.md, "Sky"): a CIE, overcast, uniform or Perez sky with a
// uniform ground below the horizon, shining through portals (parallelogram openings) or, without
// one, from a disc covering the site. Its row of the table in luminaire_types.cpp. The sky
// models and the exact direction sampling are daylight/'s (sky_models, sky_sampler).
#include <algorithm>
#include <bit>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

#include "daylight/sky_sampler.hpp"
#include "io/json_reader.hpp"
#include "lightsolver/sky_patches.hpp"
#include "model/sampling.hpp"
#include "types/luminaire_rows.hpp"

namespace lightsolver::detail {
namespace {

using namespace luminaire_rows;

constexpr const char* kSkyKeys[] = {"name",
                                    "type",
                                    "model",
                                    "cie_type",
                                    "sun_direction",
                                    "zenith_luminance_cd_m2",
                                    "diffuse_horizontal_lx",
                                    "perez",
                                    "ground_reflectance",
                                    "sun_direct_normal_lx",
                                    "portals",
                                    "site",
                                    "patch"};
constexpr const char* kPerezKeys[] = {"diffuse_horizontal", "direct_normal", "units", "day_of_year",
                                      "dew_point_c"};
constexpr const char* kPortalKeys[] = {"corner", "edge1", "edge2", "glazing"};
constexpr const char* kGlazingKeys[] = {"transmittance", "panes", "frame_factor",
                                        "maintenance_factor"};
constexpr const char* kSiteKeys[] = {"centre", "radius_m"};
constexpr const char* kPatchKeys[] = {"mf", "index", "north_deg"};

int whole_number(const JsonNode& n) {
  const double v = n.number();
  if (v != std::floor(v) || std::abs(v) > 1e6) n.fail("must be a whole number");
  return static_cast<int>(v);
}

void read_sky(const JsonNode& n, Luminaire& l, const std::string&) {
  n.require_object(kSkyKeys);
  SkyDefinition& s = l.sky;
  s.model = n.at("model").string();
  if (s.model != "cie" && s.model != "cie_overcast" && s.model != "uniform" && s.model != "perez") {
    n.at("model").fail("must be \"cie\", \"cie_overcast\", \"uniform\" or \"perez\" (got \"" +
                       s.model + "\")");
  }
  if (n.has("cie_type")) s.cie_type = whole_number(n.at("cie_type"));
  if (n.has("sun_direction")) s.sun_direction = n.at("sun_direction").vec3();
  if (n.has("zenith_luminance_cd_m2"))
    s.zenith_luminance_cd_m2 = n.at("zenith_luminance_cd_m2").number();
  if (n.has("diffuse_horizontal_lx"))
    s.diffuse_horizontal_lx = n.at("diffuse_horizontal_lx").number();
  if (n.has("perez")) {
    const JsonNode p = n.at("perez");
    p.require_object(kPerezKeys);
    s.perez_diffuse_horizontal = p.at("diffuse_horizontal").number();
    s.perez_direct_normal = p.at("direct_normal").number();
    const std::string units = p.at("units").string();
    if (units != "W/m2" && units != "lx") p.at("units").fail("must be \"W/m2\" or \"lx\"");
    s.perez_lux = units == "lx";
    if (p.has("day_of_year")) s.day_of_year = whole_number(p.at("day_of_year"));
    s.dew_point_c = p.number_or("dew_point_c", s.dew_point_c);
  }
  s.ground_reflectance = n.number_or("ground_reflectance", s.ground_reflectance);
  s.sun_direct_normal_lx = n.number_or("sun_direct_normal_lx", 0.0);
  if (n.has("portals")) s.portals = read_portals(n.at("portals"));
  if (n.has("patch")) {
    const JsonNode p = n.at("patch");
    p.require_object(kPatchKeys);
    s.patch = SkyDefinition::Patch{whole_number(p.at("mf")), whole_number(p.at("index")),
                                   p.number_or("north_deg", 0.0)};
  }
  if (n.has("site")) {
    const JsonNode site = n.at("site");
    site.require_object(kSiteKeys);
    s.site_centre = site.at("centre").vec3();
    s.site_radius_m = site.at("radius_m").number();
  }
}

// An opening's glazing as the daylight module takes it; errors name `<at>.<key>`.
daylight::Glazing checked_glazing(const LuminaireChecks& c, const std::string& at,
                                  const GlazingDefinition& g) {
  auto in_unit = [&](const char* key, double v, const char* what) {
    if (!(v > 0.0 && v <= 1.0)) {
      c.fail((at + "." + key).c_str(),
             std::string("must be more than 0 and at most 1 (") + what + "; got " + show(v) + ")");
    }
  };
  in_unit("transmittance", g.transmittance,
          "τv at normal incidence; an opaque opening is no portal: leave it out");
  in_unit("frame_factor", g.frame_factor, "the glazed fraction of the opening");
  in_unit("maintenance_factor", g.maintenance_factor, "1: clean glass");
  if (g.panes != 1 && g.panes != 2) {
    c.fail((at + ".panes").c_str(),
           "must be 1 (single) or 2 (double glazing), got " + std::to_string(g.panes));
  }
  return {g.transmittance, static_cast<unsigned>(g.panes), g.frame_factor, g.maintenance_factor};
}

daylight::SkySpec sky_spec(const LuminaireChecks& c, const SkyDefinition& s) {
  daylight::SkySpec spec;
  spec.model = s.model == "cie"            ? daylight::SkyModel::CieGeneral
               : s.model == "cie_overcast" ? daylight::SkyModel::CieOvercast
               : s.model == "uniform"      ? daylight::SkyModel::Uniform
                                           : daylight::SkyModel::Perez;
  spec.cie_type = s.cie_type;
  if (s.sun_direction) {
    c.direction("sun_direction", *s.sun_direction);
    const glm::dvec3 d = glm::normalize(*s.sun_direction);
    spec.sun = daylight::Direction{d.x, d.y, d.z};
  }
  if (spec.model == daylight::SkyModel::Perez) {
    if (s.zenith_luminance_cd_m2 || s.diffuse_horizontal_lx) {
      c.fail(s.zenith_luminance_cd_m2 ? "zenith_luminance_cd_m2" : "diffuse_horizontal_lx",
             "the Perez sky takes its level from \"perez\" (the model's efficacies)");
    }
    spec.perez = {s.perez_diffuse_horizontal, s.perez_direct_normal, s.perez_lux, s.day_of_year,
                  s.dew_point_c};
  } else if (s.zenith_luminance_cd_m2.has_value() == s.diffuse_horizontal_lx.has_value()) {
    c.fail("zenith_luminance_cd_m2",
           "give exactly one of zenith_luminance_cd_m2 and diffuse_horizontal_lx");
  } else if (s.zenith_luminance_cd_m2) {
    spec.normalisation = daylight::SkyNormalisation::ZenithLuminance;
    spec.level = *s.zenith_luminance_cd_m2;
  } else {
    spec.normalisation = daylight::SkyNormalisation::DiffuseHorizontalIlluminance;
    spec.level = *s.diffuse_horizontal_lx;
  }
  spec.ground_reflectance = s.ground_reflectance;
  spec.sun_direct_normal_lx = s.sun_direct_normal_lx;
  return spec;
}

// The daylight module names its inputs ("level: ...", "perez.direct_normal: ..."): the name
// before the colon becomes the failing field of the scene file.
[[noreturn]] void fail_from(const LuminaireChecks& c, const SkyDefinition& s,
                            const std::invalid_argument& e) {
  static constexpr std::pair<const char*, const char*> kFields[] = {
      {"sun", "sun_direction"},
      {"cie_type", "cie_type"},
      {"ground_reflectance", "ground_reflectance"},
      {"sun_direct_normal_lx", "sun_direct_normal_lx"},
      {"perez.diffuse_horizontal", "perez.diffuse_horizontal"},
      {"perez.direct_normal", "perez.direct_normal"},
      {"perez.day_of_year", "perez.day_of_year"},
      {"perez.dew_point_c", "perez.dew_point_c"}};
  const std::string what = e.what();
  const auto colon = what.find(": ");
  const std::string name = colon == std::string::npos ? "" : what.substr(0, colon);
  const std::string rest = colon == std::string::npos ? what : what.substr(colon + 2);
  if (name == "level") {
    c.fail(s.zenith_luminance_cd_m2 ? "zenith_luminance_cd_m2" : "diffuse_horizontal_lx", rest);
  }
  for (const auto& [from, field] : kFields) {
    if (name == from) c.fail(field, rest);
  }
  c.fail("model", what);
  throw e;  // not reached (fail throws); GCC does not carry [[noreturn]] through a virtual call
}

// A patch's box of directions in the sampler's frame (azimuth atan2(y, x)): the patch's
// azimuth A (from north toward east) is 90° + north − A there.
daylight::SkyDirections::Region patch_region(const LuminaireChecks& c,
                                             const SkyDefinition::Patch& p) {
  if (p.mf < 1 || p.mf > 64) {
    c.fail("patch.mf", "the Reinhart subdivision must be 1 … 64, got " + std::to_string(p.mf));
  }
  if (!std::isfinite(p.north_deg)) c.fail("patch.north_deg", "must be a finite number");
  const SkyPatches patches(p.mf, p.north_deg);
  if (p.index < 0 || p.index >= patches.count()) {
    c.fail("patch.index", "must be 0 (the ground) … " + std::to_string(patches.count() - 1) +
                              " for MF " + std::to_string(p.mf) + ", got " +
                              std::to_string(p.index));
  }
  const SkyPatch& sp = patches.patch(p.index);
  constexpr double kDeg = std::numbers::pi / 180.0;
  daylight::SkyDirections::Region r;
  r.altitude0 = sp.altitude_min_deg * kDeg;
  r.altitude_span = (sp.altitude_max_deg - sp.altitude_min_deg) * kDeg;
  if (sp.azimuth_width_deg < 360.0) {
    const double a0 = 90.0 + p.north_deg - sp.azimuth_deg - 0.5 * sp.azimuth_width_deg;
    r.azimuth0 = std::fmod(std::fmod(a0, 360.0) + 360.0, 360.0) * kDeg;
    r.azimuth_span = sp.azimuth_width_deg * kDeg;
  }
  return r;
}

void check_sky(const LuminaireChecks& c, Luminaire& l) {
  SkyDefinition& s = l.sky;
  const daylight::SkySpec spec = sky_spec(c, s);
  std::vector<daylight::SkyEmitter::Portal> portals;
  for (std::size_t i = 0; i < s.portals.size(); ++i) {
    Luminaire edges;  // the shared parallelogram check, on this portal
    edges.corner = s.portals[i].corner;
    edges.edge1 = s.portals[i].edge1;
    edges.edge2 = s.portals[i].edge2;
    c.parallelogram(edges, ("portal " + std::to_string(i) + "'s area is zero").c_str());
    portals.push_back({edges.corner, edges.edge1, edges.edge2});
    if (s.portals[i].glazing) {
      portals.back().glazing =
          checked_glazing(c, "portals[" + std::to_string(i) + "].glazing", *s.portals[i].glazing);
    }
  }
  if (portals.empty()) {
    c.coordinates("site", s.site_centre);
    if (!(s.site_radius_m > 0.0) || !(s.site_radius_m <= 1e6)) {
      c.fail("site",
             "without portals the sky needs a site (centre and radius_m, 0 < radius_m "
             "<= 10^6 m) covering the scene");
    }
  }
  const daylight::SkyDirections::Region region =
      s.patch ? patch_region(c, *s.patch) : daylight::SkyDirections::Region{};
  try {
    auto sky = std::make_shared<const daylight::Sky>(spec);
    l.sky_emitter = std::make_shared<const daylight::SkyEmitter>(sky, portals, s.site_centre,
                                                                 s.site_radius_m, region);
  } catch (const std::invalid_argument& e) {
    fail_from(c, s, e);
  }
  l.flux_lm = l.sky_emitter->flux_lm();
  l.position = portals.empty() ? s.site_centre : portals.front().corner;
  if (!(l.flux_lm <= limits::kMaxFlux_lm)) {
    c.fail("portals",
           "the sky sends " + show(l.flux_lm) + " lm through its openings, more than 10^12 lm");
  }
}

void prepare_sky(const Luminaire&, PreparedLuminaire& p) { p.axis = vec3(0.0f, 0.0f, -1.0f); }

// World points are drawn relative to the luminaire's anchor (`position`, in double) and moved
// to the prepared scene's local frame by the anchor's local position: no float rounding of
// georeferenced coordinates. A portal's origin is pushed off its plane inward, so a portal
// coplanar with its wall is not blocked by the wall.
EmittedRay emit_sky(const PreparedLuminaire& l, PathRng& rng) {
  const Luminaire& src = *l.source;
  const daylight::SkyEmitter& e = *src.sky_emitter;
  glm::dvec3 world, dir;
  const std::size_t k = e.emit([&rng]() { return rng.uniform_double(); }, world, dir);
  const vec3 local = l.position + vec3(world - src.position);
  if (e.portals().empty()) return {local, vec3(dir)};
  const vec3 inward(e.inward(k));
  return {offset_ray_origin(local, inward), vec3(dir), inward};
}

// Through the portals' corners into the room, or from anywhere around the site.
EmissionSupport support_sky(const PreparedLuminaire& l) {
  const Luminaire& src = *l.source;
  EmissionSupport s;
  const glm::dvec3 shift = glm::dvec3(l.position) - src.position;
  if (src.sky.portals.empty()) {
    s.points = {src.sky.site_centre + shift};
    s.radius = 2.0 * src.sky.site_radius_m;
    return s;
  }
  for (const auto& p : src.sky.portals) {
    const glm::dvec3 c = p.corner + shift;
    s.points.insert(s.points.end(), {c, c + p.edge1, c + p.edge2, c + p.edge1 + p.edge2});
  }
  if (src.sky.portals.size() == 1) {
    s.axis = glm::normalize(glm::cross(src.sky.portals[0].edge1, src.sky.portals[0].edge2));
    s.half_angle_rad = 0.5 * std::numbers::pi;
  }
  return s;
}

GlareShape glare_sky(const Luminaire&) {
  return no_glare("the sky (daylight) is not a luminaire in the field of view");
}

double sky_flux(const Luminaire& l) { return l.flux_lm; }
glm::dvec3 sky_anchor(const Luminaire& l) {
  return l.sky.portals.empty() ? l.sky.site_centre : l.sky.portals.front().corner;
}
// Moves the openings (or the site) with the building: the anchor lands on `c`.
void move_sky(Luminaire& l, const glm::dvec3& c) {
  const glm::dvec3 delta = c - sky_anchor(l);
  for (auto& p : l.sky.portals) p.corner += delta;
  l.sky.site_centre += delta;
  l.position += delta;
}
glm::dvec3* sky_no_aim(Luminaire&) { return nullptr; }

}  // namespace

std::vector<SkyDefinition::Portal> read_portals(const JsonNode& ps) {
  std::vector<SkyDefinition::Portal> out;
  for (std::size_t i = 0; i < ps.array_size(); ++i) {
    const JsonNode p = ps[i];
    p.require_object(kPortalKeys);
    out.push_back(
        {p.at("corner").vec3(), p.at("edge1").vec3(), p.at("edge2").vec3(), std::nullopt});
    if (p.has("glazing")) out.back().glazing = read_glazing(p.at("glazing"));
  }
  return out;
}

GlazingDefinition read_glazing(const JsonNode& n) {
  n.require_object(kGlazingKeys);
  GlazingDefinition g;
  g.transmittance = n.at("transmittance").number();
  if (n.has("panes")) g.panes = whole_number(n.at("panes"));
  g.frame_factor = n.number_or("frame_factor", 1.0);
  g.maintenance_factor = n.number_or("maintenance_factor", 1.0);
  return g;
}

double glazing_factor(const LuminaireChecks& c, const std::string& at, const GlazingDefinition& g,
                      double cos_i) {
  const daylight::Glazing glazing = checked_glazing(c, at, g);
  return glazing.tau(cos_i) * glazing.factor();
}

// Floats per portal in the GPU record (Shaders/sky.glsl's kSkyPortal).
constexpr std::size_t kSkyPortalFloats = 20;

std::uint32_t pack_sky_record(const PreparedLuminaire& l, std::vector<float>& floats,
                              std::vector<std::uint64_t>& thresholds,
                              std::uint64_t (*threshold)(double c, double total)) {
  const Luminaire& src = *l.source;
  const daylight::SkyEmitter& e = *src.sky_emitter;
  const daylight::Sky& sky = e.sky();
  const daylight::SkyShape& sh = sky.shape();
  const auto base = static_cast<std::uint32_t>(floats.size());
  auto f = [&](double v) { floats.push_back(static_cast<float>(v)); };
  auto u = [&](std::size_t v) {
    floats.push_back(std::bit_cast<float>(static_cast<std::uint32_t>(v)));
  };
  auto v3 = [&](const glm::dvec3& v) { f(v.x), f(v.y), f(v.z); };
  // Local coordinates: world minus the anchor, plus the anchor's local position (emit_sky).
  const glm::dvec3 shift = glm::dvec3(l.position) - src.position;
  for (double x : {sh.a, sh.b, sh.m, sh.c, sh.d, sh.e, sh.k, sky.scale()}) f(x);
  v3({sky.sun().x, sky.sun().y, sky.sun().z});
  f(sky.ground_luminance());
  const std::size_t portals = e.portals().size();
  u(portals);
  u(static_cast<std::size_t>(e.directions(0).bands()));
  u(static_cast<std::size_t>(e.directions(0).sectors()));
  u(thresholds.size());
  const std::vector<double>& pf = e.portal_flux_lm();
  double total = 0.0;
  for (double x : pf) total += x;
  double run = 0.0;
  for (double x : pf) thresholds.push_back(threshold(run += x, total));
  v3(e.site_centre() + shift);
  f(e.site_radius_m());
  f(daylight::kMinCosZ);
  const daylight::SkyDirections::Region& r = e.directions(0).region();
  for (double x : {r.altitude0, r.altitude_span, r.azimuth0, r.azimuth_span}) f(x);
  u(r.whole() ? 0 : 1);
  while (floats.size() < base + 28) f(0.0);
  const std::size_t tables = std::max<std::size_t>(portals, 1);
  const auto first_portal = floats.size();
  floats.resize(first_portal + kSkyPortalFloats * tables, 0.0f);
  for (std::size_t k = 0; k < tables; ++k) {
    const daylight::SkyDirections& d = e.directions(k);
    const std::size_t bound_off = floats.size();
    for (double b : d.bounds()) {  // rounded up: float must not cut the majorant
      floats.push_back(std::nextafter(static_cast<float>(b), std::numeric_limits<float>::max()));
    }
    const std::size_t cdf_off = thresholds.size();
    const double cells_total = d.cumulative().back();
    std::size_t last = 0;
    for (std::size_t c = 0; c < d.cumulative().size(); ++c) {
      thresholds.push_back(threshold(d.cumulative()[c], cells_total));
      if (d.bounds()[c] > 0.0) last = c;
    }
    float* slot = floats.data() + first_portal + kSkyPortalFloats * k;
    if (portals > 0) {
      const auto& p = e.portals()[k];
      const glm::dvec3 corner = p.corner + shift, out = -e.inward(k);
      const glm::dvec3 vs[4] = {corner, p.edge1, p.edge2, out};
      for (int i = 0; i < 4; ++i) {
        slot[3 * i] = static_cast<float>(vs[i].x);
        slot[3 * i + 1] = static_cast<float>(vs[i].y);
        slot[3 * i + 2] = static_cast<float>(vs[i].z);
      }
      slot[16] = static_cast<float>(p.glazing.scale());
      slot[17] = std::bit_cast<float>(p.glazing.panes);
    }
    slot[12] = std::bit_cast<float>(static_cast<std::uint32_t>(bound_off));
    slot[13] = std::bit_cast<float>(static_cast<std::uint32_t>(cdf_off));
    slot[14] = std::bit_cast<float>(static_cast<std::uint32_t>(d.bounds().size()));
    slot[15] = std::bit_cast<float>(static_cast<std::uint32_t>(last));
  }
  return base;
}

LuminaireType sky_luminaire_type() {
  return {.type = Luminaire::Type::Sky,
          .name = "sky",
          .keys = kSkyKeys,
          .read = read_sky,
          .check = check_sky,
          .prepare = prepare_sky,
          .emit = emit_sky,
          .emitted_flux = sky_flux,
          .support = support_sky,
          .glare_kind = GlareShape::Kind::None,
          .glare = glare_sky,
          .effect = "sky_emission",
          .anchor = sky_anchor,
          .centre = sky_anchor,
          .move_to = move_sky,
          .aim = sky_no_aim,
          .placed = false};
}

}  // namespace lightsolver::detail
