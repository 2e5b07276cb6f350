// Daylight coefficients (src/annual/; docs/daylight.md, "Daylight coefficients"): hours of the
// Chicago year rebuilt from one trace of patches and suns agree with point-in-time runs of the
// same Perez sky and sun in a side-lit room, on every backend; an open horizontal probe reads the
// model's diffuse horizontal illuminance plus the sun's beam every hour, and its year sums to the
// weather file's global horizontal illuminance as the sky matrix does.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "lightsolver/daylight_coefficients.hpp"
#include "lightsolver/error.hpp"
#include "lightsolver/weather.hpp"
#include "scene_builders.hpp"
#include "sky_rooms.hpp"

namespace lightsolver::test {
namespace {

const std::filesystem::path kChicago = std::filesystem::path(LIGHTSOLVER_SOURCE_DIR) /
                                       "Tests/native/sun/data/" /
                                       "USA_IL_Chicago-OHare.Intl.AP.725300_TMY3.epw";

const WeatherFile& chicago() {
  static const WeatherFile w = read_epw(kChicago);
  return w;
}

int day_of_year(int month, int day) {
  static constexpr int kBefore[] = {0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334};
  return kBefore[month - 1] + day;
}

// A grey 4 × 4 × 3 m room, a 2 × 1.5 m double-glazed window in its wall y = 0 (facing −y: south
// with north 0) as a portal, a 3 × 3 grid at 0.8 m.
Scene side_lit_room() {
  Scene s;
  add_material(s, "grey", Material::Type::Diffuse, 0.5);
  const Hole h{0.8 / 3.0, 2.3 / 3.0, 0.25, 0.75};  // s along z, t along x
  s.meshes.push_back(room_with_hole(0, {0, 0, 0}, {4, 4, 3}, false, h));
  Luminaire l = sky("uniform", 1000.0, 0.2);  // the annual run takes only its openings
  GlazingDefinition g;
  g.transmittance = 0.75;
  g.panes = 2;
  l.sky.portals.push_back({{1, 0, 0.8}, {0, 0, 1.5}, {2, 0, 0}, g});  // into the room: +y
  s.luminaires.push_back(l);
  s.targets.push_back(grid("work plane", {0.2, 0.2, 0.8}, {3.6, 0, 0}, {0, 3.6, 0}, 3, 3));
  return s;
}

// The same hour as one Perez sky and its sun, through the same portal.
Scene point_in_time(const Scene& room, const WeatherHour& w, const SkyMatrix& y, int h) {
  Scene s = room;
  const auto portals = s.luminaires[0].sky.portals;
  Luminaire l;
  l.name = "sky";
  l.type = Luminaire::Type::Sky;
  l.sky.model = "perez";
  l.sky.perez_diffuse_horizontal = *w.diffuse_horizontal_w_m2;
  l.sky.perez_direct_normal = *w.direct_normal_w_m2;
  l.sky.day_of_year = day_of_year(w.month, w.day);
  const float* d = &y.sun_direction[3 * h];
  l.sky.sun_direction = glm::normalize(dvec3(d[0], d[1], d[2]));
  l.sky.ground_reflectance = 0.2;
  l.sky.portals = portals;
  s.luminaires = {l};
  if (y.sun_direct_normal_lx[h] > 0.0f) {
    Luminaire sun;
    sun.name = "sun";
    sun.type = Luminaire::Type::Sun;
    sun.direction = -*l.sky.sun_direction;
    sun.illuminance_lx = y.sun_direct_normal_lx[h];
    sun.sky.portals = portals;
    s.luminaires.push_back(sun);
  }
  return s;
}

// Three hours of the year: January's brightest sun through the south window, the dullest
// overcast hour with no sun (the most diffuse light), a June morning with the sun behind the
// window's wall.
std::vector<std::size_t> chosen_hours(const WeatherFile& w) {
  std::size_t sunny = 0, overcast = 0, behind = 0;
  double best_sun = 0.0, best_diffuse = 0.0, best_behind = 0.0;
  for (std::size_t i = 0; i < w.hours.size(); ++i) {
    const WeatherHour& r = w.hours[i];
    const double dni = r.direct_normal_w_m2.value_or(0),
                 dhi = r.diffuse_horizontal_w_m2.value_or(0);
    if (r.month == 1 && r.hour == 13 && dni > best_sun) best_sun = dni, sunny = i;
    if (dni == 0.0 && dhi > best_diffuse) best_diffuse = dhi, overcast = i;
    if (r.month == 6 && r.hour == 8 && dni > best_behind) best_behind = dni, behind = i;
  }
  return {sunny, overcast, behind};
}

class DaylightCoefficientsTraced : public ::testing::TestWithParam<std::string> {};

// Each cell of each hour: |E_dc − E_pit| within the two runs' intervals combined (5σ level) plus
// the patches' discretisation (luminance taken uniform within each MF 4 patch: ~0.1 % of the
// horizontal illuminance, docs/daylight.md; allowed 1 %).
TEST_P(DaylightCoefficientsTraced, HoursEqualPointInTimeRuns) {
  const std::vector<std::size_t> picked = chosen_hours(chicago());
  WeatherFile few = chicago();
  few.hours.clear();
  for (std::size_t i : picked) few.hours.push_back(chicago().hours[i]);
  SkyMatrixOptions mo;
  mo.mf = 4;
  const SkyMatrix y = sky_matrix(few, mo);
  ASSERT_EQ(y.status[0], 2);
  ASSERT_EQ(y.status[1], 2);
  ASSERT_GT(y.sun_direct_normal_lx[0], 1e4f);
  ASSERT_EQ(y.sun_direct_normal_lx[1], 0.0f);
  ASSERT_GT(y.sun_direction[3 * 2 + 1], 0.0f);  // June 7–8 h: the sun north of east, behind
  const Scene room = side_lit_room();
  const double z = z_for_confidence(kCheckConfidence);
  DaylightCoefficientOptions o;
  o.mf = 4;
  o.photons = 3'000'000;
  o.seed = 3;
  o.backend = GetParam();
  o.z = z;
  const DaylightCoefficients dc = trace_daylight_coefficients(room, y, o);
  EXPECT_EQ(dc.patches, 2306);
  EXPECT_EQ(dc.grids[0].direct.size(), 3u * 9u);
  EXPECT_EQ(dc.sun_bins.size(), 2u);  // the overcast hour has no sun
  const HourlyIlluminance e = hourly_illuminance(dc, y, 0);
  for (int h = 0; h < y.hours; ++h) {
    Scene pit = point_in_time(room, few.hours[h], y, h);
    const Results r = run_on_backend(GetParam(), pit, 800'000, 17 + h);
    const TargetResult& t = r.targets[0];
    for (int c = 0; c < e.cells; ++c) {
      const std::size_t at = static_cast<std::size_t>(h) * e.cells + c;
      const Estimate& p = t.cells[c];
      const double diff = e.mean[at] - p.mean;
      const double dc_side = diff > 0 ? z * e.spread_low[at] + e.direct_below[at]
                                      : z * e.spread_high[at] + e.direct_above[at];
      const double pit_side = diff > 0 ? p.ci_high - p.mean : p.mean - p.ci_low;
      const double allowed = std::hypot(dc_side, pit_side) + 0.01 * p.mean;
      std::printf(
          "[ dc       ] hour %d cell %d: coefficients %.1f (−%.1f +%.1f; direct −%.1f "
          "+%.1f), point in time %.1f [%.1f, %.1f]\n",
          h, c, e.mean[at], z * e.spread_low[at], z * e.spread_high[at], e.direct_below[at],
          e.direct_above[at], p.mean, p.ci_low, p.ci_high);
      EXPECT_LE(std::abs(diff), allowed) << "hour " << h << " cell " << c;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, DaylightCoefficientsTraced, ::testing::ValuesIn(backends()));

// No geometry, a site disc: an upward 1 m² probe at its centre reads, every sky hour, the light of
// the MF 2 patches through it plus E_n sin(altitude) within the hour's interval; those patches
// give the model's diffuse horizontal illuminance within their discretisation; the year's sum
// against the weather file's global horizontal column.
TEST(DaylightCoefficients, OpenProbeReadsTheSkyAndSunEveryHour) {
  Scene s;
  Luminaire l = sky("uniform", 1000.0, 0.2);
  l.sky.site_centre = dvec3(0, 0, 0);
  l.sky.site_radius_m = 1.0;
  s.luminaires.push_back(l);
  s.targets.push_back(grid("up", {-0.5, -0.5, 0}, {1, 0, 0}, {0, 1, 0}, 1, 1));
  SkyMatrixOptions mo;
  mo.mf = 2;
  const SkyMatrix y = sky_matrix(chicago(), mo);
  const double z = z_for_confidence(kCheckConfidence);
  DaylightCoefficientOptions o;
  o.mf = 2;
  o.photons = 20'000'000;
  o.seed = 5;
  o.backend = "embree";
  o.z = z;
  const DaylightCoefficients dc = trace_daylight_coefficients(s, y, o);
  const HourlyIlluminance e = hourly_illuminance(dc, y, 0);
  const SkyPatches patches(2);
  double ours = 0.0, file = 0.0, worst = 0.0;
  int outside = 0, sky_hours = 0;
  for (int h = 0; h < y.hours; ++h) {
    ours += e.mean[h];
    file += chicago().hours[h].global_horizontal_lx.value_or(0.0);
    if (y.status[h] != 2) {
      EXPECT_EQ(e.mean[h], 0.0f) << "hour " << h;
      continue;
    }
    ++sky_hours;
    // What the coefficients must give: each patch's light through an upward sensor (its mean
    // cos Z, exact for uniform luminance) plus the beam; the tracing is held to it.
    double patched = 0.0;
    for (int p = 1; p < y.patch_count; ++p) {
      patched += y.sky[std::size_t(h) * y.patch_count + p] * patches.patch(p).mean_cos_zenith;
    }
    const double alt = y.sun_altitude_deg[h] * std::numbers::pi / 180.0;
    const double beam = y.sun_direct_normal_lx[h] * std::sin(alt);
    const double diff = e.mean[h] - (patched + beam);
    const double side = z * (diff > 0 ? e.spread_low[h] : e.spread_high[h]);
    if (std::abs(diff) > side + 1e-4 * (patched + beam)) ++outside;  // + float rounding
    // And against the model's own horizontal illuminance (its fine quadrature): the patches'
    // discretisation (docs/daylight.md: 0.41 % at MF 2 for nine test skies, 1.29 % at worst
    // over Chicago's year, a sun just above the horizon).
    const double model = y.diffuse_horizontal_lx[h];
    worst = std::max(worst, std::abs(patched - model) / model);
  }
  std::printf(
      "[ dc       ] open probe: %d sky hours; the patches' discretisation at most %.3f %% of the "
      "diffuse light; year %.5g lx·h, the file's %.5g (%+.2f %%); coefficients %.1f MB, %zu "
      "groups, %.1f s\n",
      sky_hours, 100.0 * worst, ours, file, 100.0 * (ours / file - 1.0), dc.bytes() / 1e6,
      dc.trace.groups.size(), dc.trace.seconds);
  EXPECT_EQ(outside, 0);
  EXPECT_LT(worst, 0.02);
  EXPECT_NEAR(ours / file, 1.0, 0.03);  // the sky matrix' +1.7 % (irradiance + Perez efficacy)
}

// `annual --decide` continues a trace: 2·10⁵ then 4·10⁵ photons give the coefficients of one
// trace of 4·10⁵, bit for bit.
TEST(DaylightCoefficients, ContinuedTraceEqualsOneTrace) {
  WeatherFile few = chicago();
  few.hours.assign(chicago().hours.begin() + 4000, chicago().hours.begin() + 4024);
  const SkyMatrix y = sky_matrix(few, SkyMatrixOptions{});
  const Scene room = side_lit_room();
  DaylightCoefficientOptions o;
  o.backend = "embree";
  o.seed = 9;
  CoefficientTracer tracer(room, y, o);
  tracer.trace(200'000, 3.0);
  const DaylightCoefficients continued = tracer.trace(400'000, 3.0);
  o.photons = 400'000;
  o.z = 3.0;
  const DaylightCoefficients once = trace_daylight_coefficients(room, y, o);
  EXPECT_EQ(continued.trace.photons, 400'000u);
  EXPECT_EQ(continued.grids[0].mean, once.grids[0].mean);
  EXPECT_EQ(continued.grids[0].above, once.grids[0].above);
  EXPECT_EQ(continued.grids[0].reflected_mean, once.grids[0].reflected_mean);
}

TEST(DaylightCoefficients, SceneWithoutSkyOrGridIsNamed) {
  SkyMatrixOptions mo;
  WeatherFile few = chicago();
  few.hours.resize(24);
  const SkyMatrix y = sky_matrix(few, mo);
  Scene room = side_lit_room();
  DaylightCoefficientOptions o;
  auto field_of = [&](const Scene& s) -> std::string {
    try {
      trace_daylight_coefficients(s, y, o);
    } catch (const InputError& e) {
      return e.where();
    }
    return "accepted";
  };
  Scene no_sky = room;
  no_sky.luminaires.clear();
  EXPECT_EQ(field_of(no_sky), "luminaires");
  Scene two_skies = room;
  two_skies.luminaires.push_back(room.luminaires[0]);
  EXPECT_EQ(field_of(two_skies), "luminaires");
  Scene no_grid = room;
  no_grid.targets.clear();
  EXPECT_EQ(field_of(no_grid), "targets");
  DaylightCoefficientOptions other = o;
  other.mf = 2;
  EXPECT_THROW(trace_daylight_coefficients(room, y, other), InputError);
}

}  // namespace
}  // namespace lightsolver::test
