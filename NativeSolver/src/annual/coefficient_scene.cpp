// The scene daylight coefficients are traced in (lightsolver/daylight_coefficients.hpp): the
// scene's sky replaced by one uniform sky per Reinhart patch and its sun by one sun per bin of
// the year's sun positions, each its own luminaire group, so that one trace gives every group's
// light apart and an hour is a weighted sum of them; every grid followed by a reflected-only twin
// (the sun's reflected light comes from its bin's group, its beam from shadow rays:
// docs/daylight.md, "Daylight coefficients").
#include <cmath>
#include <glm/geometric.hpp>
#include <string>

#include "lightsolver/daylight_coefficients.hpp"
#include "lightsolver/error.hpp"

namespace lightsolver {
namespace {

// The scene's luminaire of `type` into *out (null when none and not `needed`); InputError when
// there is none but one is needed, or more than one.
void the_one(const Scene& s, Luminaire::Type type, const char* what, bool needed,
             const Luminaire** out) {
  int count = 0;
  for (const Luminaire& l : s.luminaires) {
    if (l.type != type) continue;
    if (++count == 1) *out = &l;
  }
  if ((needed && count != 1) || count > 1) {
    throw InputError(s.source_file, "luminaires",
                     std::string("an annual run needs ") +
                         (needed ? "exactly one " : "at most one ") + what +
                         " luminaire (its openings), the scene has " + std::to_string(count));
  }
}

// Patch p's sky: the scene's sky's openings and glazing, uniform luminance `luminance` over the
// patch; the ground patch's luminance is the uniform sky's ground, ρ_g E_h / π = ρ_g L, so
// ρ_g = 1 gives it the same L.
Luminaire patch_sky(const Luminaire& sky, int mf, int index, double north_deg, double luminance) {
  Luminaire l;
  l.name = "sky patch " + std::to_string(index);
  l.type = Luminaire::Type::Sky;
  l.sky.model = "uniform";
  l.sky.zenith_luminance_cd_m2 = luminance;
  l.sky.ground_reflectance = 1.0;
  l.sky.portals = sky.sky.portals;
  l.sky.site_centre = sky.sky.site_centre;
  l.sky.site_radius_m = sky.sky.site_radius_m;
  l.sky.patch = SkyDefinition::Patch{mf, index, north_deg};
  return l;
}

// A sun bin's sun: beam along −toward at kSunBinLx, through the scene's sun's opening, else the
// sky's portals, else a square across the beam that covers the site's sphere (2R wide, R beyond
// its centre: every point of the sphere is in the beam).
Luminaire bin_sun(const Luminaire* sun, const Luminaire& sky, std::size_t bin,
                  const glm::dvec3& toward) {
  Luminaire l;
  if (sun) {
    l.corner = sun->corner;
    l.edge1 = sun->edge1;
    l.edge2 = sun->edge2;
    l.glazing = sun->glazing;
    l.sky.portals = sun->sky.portals;
  } else if (!sky.sky.portals.empty()) {
    l.sky.portals = sky.sky.portals;
  } else {
    const double r = sky.sky.site_radius_m;
    const glm::dvec3 helper = std::abs(toward.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
    const glm::dvec3 e1 = glm::normalize(glm::cross(helper, toward));
    const glm::dvec3 e2 = glm::cross(toward, e1);
    l.corner = sky.sky.site_centre + r * toward - r * e1 - r * e2;
    l.edge1 = 2.0 * r * e1;
    l.edge2 = 2.0 * r * e2;
  }
  l.name = "sun bin " + std::to_string(bin);
  l.type = Luminaire::Type::Sun;
  l.direction = -toward;
  l.illuminance_lx = DaylightCoefficients::kSunBinLx;
  return l;
}

}  // namespace

Scene coefficient_scene(const Scene& scene, const SkyMatrix& year,
                        const DaylightCoefficientOptions& o,
                        const std::vector<glm::dvec3>& sun_bins) {
  const Luminaire* sky = nullptr;
  const Luminaire* sun = nullptr;
  the_one(scene, Luminaire::Type::Sky, "sky", true, &sky);
  the_one(scene, Luminaire::Type::Sun, "sun", false, &sun);  // at most one: its openings
  if (year.mf != o.mf) {
    throw InputError(scene.source_file, "mf",
                     "the sky matrix has MF " + std::to_string(year.mf) + ", the options " +
                         std::to_string(o.mf));
  }
  Scene s;
  s.source_file = scene.source_file;
  s.materials = scene.materials;
  s.meshes = scene.meshes;
  s.settings = scene.settings;
  s.settings.contributions = true;
  s.settings.decide = false;
  s.settings.accuracy_per_cell = false;
  for (const Target& t : scene.targets) {
    if (t.type != Target::Type::Grid) continue;
    Target g = t;
    g.requirements = {};
    g.quantity = Target::Quantity::Illuminance;
    s.targets.push_back(g);
    g.name += " (reflected)";
    g.reflected_only = true;
    s.targets.push_back(g);
  }
  if (s.targets.empty()) {
    throw InputError(scene.source_file, "targets",
                     "an annual run reports grids: the scene has no grid target");
  }
  // Patch luminances are set by the caller (trace_daylight_coefficients) once it knows the year;
  // here every patch gets 1 cd/m².
  for (int p = 0; p < year.patch_count; ++p) {
    s.luminaires.push_back(patch_sky(*sky, o.mf, p, o.north_deg, 1.0));
  }
  for (std::size_t b = 0; b < sun_bins.size(); ++b) {
    s.luminaires.push_back(bin_sun(sun, *sky, b, sun_bins[b]));
  }
  return s;
}

}  // namespace lightsolver
