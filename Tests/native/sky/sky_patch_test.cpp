// The sky restricted to one Reinhart patch (the sky luminaire's `patch` key; docs/daylight.md,
// "Daylight coefficients"): the patches' fluxes add up to the whole sky's, a uniform patch through
// a skylight sends A·L·Ω·(mean cos Z), and traced, each patch's group lights an open probe with
// L·Ω·(mean cos Z) and the patches together with the whole sky's π L, on every backend.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "lightsolver/angles.hpp"
#include "lightsolver/error.hpp"
#include "lightsolver/sky_patches.hpp"
#include "scene_builders.hpp"
#include "sky_rooms.hpp"

namespace lightsolver::test {
namespace {

Luminaire patch_of(Luminaire l, int mf, int index, double north_deg = 0.0) {
  l.name = "patch " + std::to_string(index);
  l.group = l.name;
  l.sky.patch = SkyDefinition::Patch{mf, index, north_deg};
  return l;
}

double validated_flux(const Luminaire& l) {
  Scene s;
  s.luminaires.push_back(l);
  validate_luminaires(s);
  return s.luminaires[0].flux_lm;
}

Luminaire clear_sky_through(std::vector<SkyDefinition::Portal> portals) {
  Luminaire l = sky("cie", 4000.0, 0.2);
  l.sky.cie_type = 12;
  l.sky.sun_direction = dvec3(0.3, -0.6, 0.5);
  l.sky.portals = std::move(portals);
  return l;
}

// Σ over every patch (ground included) of the patch's flux = the whole sky's: each is the same
// integrand's quadrature over a box, so they differ by the quadratures' errors alone (< 1e-5 of
// the flux each, SkyEmitter::flux_error).
TEST(SkyPatch, PatchFluxesAddUpToTheWholeSky) {
  GlazingDefinition dbl;
  dbl.transmittance = 0.7;
  dbl.panes = 2;
  const std::vector<std::vector<SkyDefinition::Portal>> openings = {
      {{{0, 0, 3}, {0, 1, 0}, {1, 0, 0}, std::nullopt}},  // skylight, light going down
      {{{0, 0, 0}, {1.5, 0, 0}, {0, 0, 1.2}, dbl}},       // window in y = 0 facing -y
  };
  for (const auto& portals : openings) {
    // MF 2 for one case only: each patch builds its own CIE sky (~10 ms of quadrature).
    for (int mf : {1, 2}) {
      for (double north : {0.0, 37.0}) {
        if (mf == 2 && (north != 37.0 || portals[0].glazing)) continue;
        const Luminaire whole = clear_sky_through(portals);
        const double total = validated_flux(whole);
        const SkyPatches patches(mf, north);
        double sum = 0.0;
        for (int p = 0; p < patches.count(); ++p) {
          const double f = validated_flux(patch_of(whole, mf, p, north));
          EXPECT_GE(f, 0.0);
          sum += f;
        }
        EXPECT_NEAR(sum, total, 2e-5 * total) << "MF " << mf << ", north " << north;
      }
    }
  }
}

// A uniform sky of luminance L through a horizontal 1 m² skylight: patch p sends
// L ∫_p cos Z dω = L Ω_p (mean cos Z)_p, exactly (SkyPatch::mean_cos_zenith), and the ground
// nothing (it lies below the skylight's plane).
TEST(SkyPatch, UniformPatchThroughASkylightIsLOmegaMeanCosZ) {
  const Luminaire whole = [] {
    Luminaire l = sky("uniform", 1000.0, 0.5);
    l.sky.portals.push_back({{0, 0, 3}, {0, 1, 0}, {1, 0, 0}, std::nullopt});
    return l;
  }();
  const SkyPatches patches(1, 15.0);
  for (int p = 0; p < patches.count(); ++p) {
    const SkyPatch& sp = patches.patch(p);
    const double exact = 1000.0 * sp.solid_angle_sr * sp.mean_cos_zenith;
    EXPECT_NEAR(validated_flux(patch_of(whole, 1, p, 15.0)), exact, 1e-7 * 1000.0 * kPi)
        << "patch " << p;
  }
}

TEST(SkyPatch, BadPatchIsNamed) {
  const Luminaire whole = clear_sky_through({{{0, 0, 3}, {0, 1, 0}, {1, 0, 0}, std::nullopt}});
  const std::pair<Luminaire, std::string> cases[] = {
      {patch_of(whole, 0, 3), "patch.mf"},
      {patch_of(whole, 65, 3), "patch.mf"},
      {patch_of(whole, 1, 146), "patch.index"},
      {patch_of(whole, 1, -1), "patch.index"},
      {patch_of(whole, 1, 3, std::nan("")), "patch.north_deg"},
  };
  for (const auto& [l, field] : cases) {
    try {
      validated_flux(l);
      ADD_FAILURE() << field << " accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
    }
  }
}

class SkyPatchTraced : public ::testing::TestWithParam<std::string> {};

// No geometry, the uniform sky (L 1000, ground 0.2 L) split into its 146 MF 1 patches, each its
// own group, over a site disc: a 1 m² probe facing up reads L Ω_p (mean cos Z)_p from patch p
// (each within its interval) and π L from all of them (the ground's light crosses it from behind
// and is not counted).
TEST_P(SkyPatchTraced, EachPatchLightsAnOpenProbeByItsSolidAngle) {
  Luminaire whole = sky("uniform", 1000.0, 0.2);
  whole.sky.site_centre = dvec3(0, 0, 0);
  whole.sky.site_radius_m = 1.0;
  const SkyPatches patches(1);
  Scene s;
  for (int p = 0; p < patches.count(); ++p) s.luminaires.push_back(patch_of(whole, 1, p));
  s.targets.push_back(grid("up", {-0.5, -0.5, 0}, {1, 0, 0}, {0, 1, 0}, 1, 1));
  s.settings.contributions = true;
  const Results r = run_on_backend(GetParam(), s, 4'000'000, 5);
  expect_in_ci(r.targets[0].estimate, kPi * 1000.0, 0.03, "all patches");
  const auto& parts = r.targets[0].contributions;
  ASSERT_EQ(parts.size(), std::size_t(patches.count()));
  int outside = 0;
  for (int p = 0; p < patches.count(); ++p) {
    const SkyPatch& sp = patches.patch(p);
    const double exact = 1000.0 * sp.solid_angle_sr * sp.mean_cos_zenith;
    const Estimate& e = parts[p].estimate;
    EXPECT_LE(e.ci_low, e.mean);
    EXPECT_GE(e.ci_high, e.mean);
    if (exact < e.ci_low || exact > e.ci_high) ++outside;
  }
  // 146 intervals at the tests' 5σ level: a miss is a ~6e-7 event each.
  EXPECT_EQ(outside, 0);
}

INSTANTIATE_TEST_SUITE_P(Backends, SkyPatchTraced, ::testing::ValuesIn(backends()));

}  // namespace
}  // namespace lightsolver::test
