// Exact sky direction sampling and the portal / disc emitter (src/daylight/sky_sampler.*).
#include "daylight/sky_sampler.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <memory>

#include "lightsolver/angles.hpp"
#include "sky_directions.hpp"

namespace lightsolver::daylight {
namespace {

using test::sun_at;

std::shared_ptr<const Sky> make_sky(SkyModel model, int type, double alt, double ground = 0.2) {
  SkySpec spec;
  spec.model = model;
  spec.cie_type = type;
  spec.sun = sun_at(alt, 200.0);
  spec.normalisation = SkyNormalisation::ZenithLuminance;
  spec.level = 1000.0;
  spec.ground_reflectance = ground;
  return std::make_shared<const Sky>(spec);
}

// A 2 x 1.5 m skylight: light goes down (edge1 x edge2 = -z).
const SkyEmitter::Portal kSkylight{{0, 0, 3}, {0, 1.5, 0}, {2, 0, 0}};

TEST(SkySampler, SkylightFluxIsAreaTimesHorizontalIlluminance) {
  for (auto [model, type] :
       {std::pair{SkyModel::Uniform, 0}, std::pair{SkyModel::CieOvercast, 0},
        std::pair{SkyModel::CieGeneral, 12}, std::pair{SkyModel::CieGeneral, 15},
        std::pair{SkyModel::CieGeneral, 3}}) {
    const auto sky = make_sky(model, type, 30.0);
    const SkyEmitter e(sky, {kSkylight}, {0, 0, 0}, 0.0);
    // Two quadratures: the emitter's per-cell Gauss rule, the model's hemisphere rule.
    EXPECT_NEAR(e.flux_lm(), 3.0 * sky->diffuse_horizontal_lx(), 1e-6 * e.flux_lm()) << type;
    EXPECT_LT(e.flux_error(), 1e-5);
    EXPECT_GE(e.directions(0).tries_per_sample(), 1.0);
    EXPECT_LT(e.directions(0).tries_per_sample(), 2.5);
  }
  const auto uniform = make_sky(SkyModel::Uniform, 0, 30.0);
  EXPECT_NEAR(SkyEmitter(uniform, {kSkylight}, {}, 0.0).flux_lm(), 3.0 * kPi * 1000.0, 1e-6 * 3e3);
  const auto overcast = make_sky(SkyModel::CieOvercast, 0, 30.0);
  EXPECT_NEAR(SkyEmitter(overcast, {kSkylight}, {}, 0.0).flux_lm(), 3.0 * 7.0 * kPi * 1000.0 / 9.0,
              1e-6 * 7e3);
}

// Without portals: pi R^2 times the luminance over the whole sphere (sky above, ground below).
TEST(SkySampler, DiscFluxCoversSkyAndGround) {
  const auto uniform = make_sky(SkyModel::Uniform, 0, 30.0, 0.3);
  const SkyEmitter e(uniform, {}, {1, 2, 3}, 5.0);
  const double ground = 0.3 * kPi * 1000.0 / kPi;
  EXPECT_NEAR(e.flux_lm(), kPi * 25.0 * 2.0 * kPi * (1000.0 + ground), 1e-6 * e.flux_lm());
}

// The majorant holds: w / bound <= 1 at 16 random points in every cell, for peaked skies,
// a low sun, vertical and tilted portals and the Perez sky.
TEST(SkySampler, MajorantBoundsTheWeight) {
  SkySpec perez;
  perez.model = SkyModel::Perez;
  perez.sun = sun_at(20.0, 120.0);
  perez.perez.diffuse_horizontal = 90.0;
  perez.perez.direct_normal = 700.0;
  const std::shared_ptr<const Sky> skies[] = {
      make_sky(SkyModel::CieGeneral, 15, 5.0), make_sky(SkyModel::CieGeneral, 12, 60.0),
      make_sky(SkyModel::CieOvercast, 0, 0.0), std::make_shared<const Sky>(perez)};
  const SkyEmitter::Portal window{
      {0, 0, 0}, {0, 0, 1.2}, {1.0, 0, 0}};  // a wall window at y = 0, light along +y
  const SkyEmitter::Portal tilted{{0, 0, 0}, {1, 0, 0}, {0, 0.6, -0.8}};
  // Glazed: τ(θ) falls to 0 at grazing incidence (double and single panes, sky_glazing.hpp).
  SkyEmitter::Portal glazed_window = window, glazed_tilted = tilted;
  glazed_window.glazing = Glazing{0.7, 2, 0.8, 0.9};
  glazed_tilted.glazing = Glazing{0.01, 1, 1.0, 1.0};
  for (const auto& sky : skies) {
    const SkyEmitter e(sky, {kSkylight, window, tilted, glazed_window, glazed_tilted}, {}, 0.0);
    for (std::size_t p = 0; p < 5; ++p) {
      EXPECT_LE(e.directions(p).worst_bound_ratio(16), 1.0) << "portal " << p;
    }
    const SkyEmitter disc(sky, {}, {}, 1.0);
    EXPECT_LE(disc.directions(0).worst_bound_ratio(16), 1.0);
  }
}

// Sampled directions follow w: the share in zones (near the sun, high sky, low sky) against the
// zones' integrals, within 5 binomial sigma.
TEST(SkySampler, SampledDirectionsFollowTheWeight) {
  const auto sky = make_sky(SkyModel::CieGeneral, 12, 35.0);
  const SkyEmitter e(sky, {kSkylight}, {}, 0.0);
  const SkyDirections& dirs = e.directions(0);
  const Direction sd = sky->sun();
  const glm::dvec3 sun(sd.x, sd.y, sd.z);
  auto near_sun = [&](const glm::dvec3& d) { return glm::dot(d, sun) > std::cos(0.35); };
  auto high = [&](const glm::dvec3& d) { return d.z > 0.7; };
  // The zones' shares by quadrature (midpoint in zenith angle and azimuth, fine grid).
  double total = 0.0, in_sun = 0.0, in_high = 0.0;
  const int nz = 400, np = 800;
  for (int i = 0; i < nz; ++i) {
    const double z = kPi * (i + 0.5) / nz;
    for (int j = 0; j < np; ++j) {
      const double p = 2 * kPi * (j + 0.5) / np;
      const glm::dvec3 d(std::sin(z) * std::cos(p), std::sin(z) * std::sin(p), std::cos(z));
      const double w = dirs.weight(d) * std::sin(z);
      total += w;
      if (near_sun(d)) in_sun += w;
      if (high(d)) in_high += w;
    }
  }
  std::uint64_t state = 12345;
  auto uniform = [&]() {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) * 0x1.0p-53;
  };
  const int n = 200000;
  int got_sun = 0, got_high = 0;
  for (int k = 0; k < n; ++k) {
    const glm::dvec3 d = dirs.sample(uniform);
    EXPECT_GT(d.z, 0.0);
    got_sun += near_sun(d);
    got_high += high(d);
  }
  for (auto [got, want] :
       {std::pair{got_sun, in_sun / total}, std::pair{got_high, in_high / total}}) {
    const double sigma = std::sqrt(want * (1 - want) / n);
    EXPECT_NEAR(double(got) / n, want, 5 * sigma + 2e-4);
  }
}

}  // namespace
}  // namespace lightsolver::daylight
