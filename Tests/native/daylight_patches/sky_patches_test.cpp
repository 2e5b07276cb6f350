// Reinhart sky patches (include/lightsolver/sky_patches.hpp) against Radiance's reinhart.cal,
// transcribed here expression by expression, and the geometry's exact sums.
#include "lightsolver/sky_patches.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <random>

#include "lightsolver/angles.hpp"
#include "lightsolver/error.hpp"

namespace {

using lightsolver::kPi;

using lightsolver::SkyPatches;

// reinhart.cal (Radiance, G. Ward 2009), in its own terms: Dx east, Dy north, Dz up.
struct ReinhartCal {
  int MF;
  static int tnaz(int r) {  // select(r, 30, 30, 24, 24, 18, 12, 6), 1-based
    static const int t[7] = {30, 30, 24, 24, 18, 12, 6};
    return t[r - 1];
  }
  int rnaz(int r) const {
    return r - (7 * MF - .5) > 0 ? 1 : MF * tnaz(static_cast<int>(std::floor((r + .5) / MF)) + 1);
  }
  int raccum(int r) const { return r - .5 > 0 ? rnaz(r - 1) + raccum(r - 1) : 0; }
  int rbin(double Dx, double Dy, double Dz) const {
    const double DEGREE = kPi / 180;
    const double alt = (Dz >= 1 ? kPi / 2 : Dz <= -1 ? -kPi / 2 : std::asin(Dz)) / DEGREE;
    double a = std::atan2(Dx, Dy);
    if (-a > 0) a += 2 * kPi;
    const double azi = a / DEGREE;
    const double alpha = 90 / (MF * 7 + .5);
    if (-alt > 0) return 0;  // calc's if() evaluates only the branch it takes
    const int r_row = static_cast<int>(std::floor(alt / alpha));
    const double r_inc = 360.0 / rnaz(r_row);
    const int r_azn = 359.9999 - .5 * r_inc - azi > 0
                          ? static_cast<int>(std::floor((azi + .5 * r_inc) / r_inc))
                          : 0;
    return raccum(r_row) + r_azn + 1;
  }
  int nrbins() const { return raccum(7 * MF + 1) + 1; }
};

glm::dvec3 unit(double alt_deg, double azi_deg) {  // Radiance's frame
  const double a = alt_deg * kPi / 180, z = azi_deg * kPi / 180;
  return {std::cos(a) * std::sin(z), std::cos(a) * std::cos(z), std::sin(a)};
}

TEST(SkyPatches, CountsAreTregenzaAndReinhartsWithTheGround) {
  EXPECT_EQ(SkyPatches(1).count(), 146);
  EXPECT_EQ(SkyPatches(2).count(), 578);
  EXPECT_EQ(SkyPatches(4).count(), 2306);
  for (int mf = 1; mf <= 6; ++mf) {
    EXPECT_EQ(SkyPatches(mf).count(), 144 * mf * mf + 2) << mf;
    EXPECT_EQ(SkyPatches(mf).count(), ReinhartCal{mf}.nrbins()) << mf;
  }
}

TEST(SkyPatches, SolidAnglesSumToTheHemisphereExactly) {
  for (int mf : {1, 2, 3, 4, 8}) {
    const SkyPatches p(mf);
    double omega = 0.0, projected = 0.0;
    for (int i = 1; i < p.count(); ++i) {
      omega += p.patch(i).solid_angle_sr;
      projected += p.patch(i).solid_angle_sr * p.patch(i).mean_cos_zenith;
    }
    EXPECT_NEAR(omega, 2 * kPi, 1e-12) << mf;
    EXPECT_NEAR(projected, kPi, 1e-12) << mf;  // ∫ cos Z dω over the hemisphere
    EXPECT_DOUBLE_EQ(p.patch(0).solid_angle_sr, 2 * kPi);
    // Each row's patches share its band equally: width × (sin a1 − sin a0).
    const auto& q = p.patch(1);
    EXPECT_NEAR(
        q.solid_angle_sr,
        q.azimuth_width_deg * kPi / 180 *
            (std::sin(q.altitude_max_deg * kPi / 180) - std::sin(q.altitude_min_deg * kPi / 180)),
        1e-15);
  }
}

TEST(SkyPatches, IndexIsReinhartCalsRbin) {
  std::mt19937_64 rng(27);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int mf : {1, 2, 3, 4}) {
    const SkyPatches p(mf);
    const ReinhartCal cal{mf};
    for (int k = 0; k < 20000; ++k) {
      glm::dvec3 d{u(rng), u(rng), u(rng)};
      if (k % 4 == 0) d.z = std::abs(d.z) * 0.05;  // crowd the low rows
      ASSERT_EQ(p.index(d),
                cal.rbin(d.x / glm::length(d), d.y / glm::length(d), d.z / glm::length(d)))
          << mf << " " << d.x << " " << d.y << " " << d.z;
    }
  }
}

TEST(SkyPatches, KnownDirections) {
  const SkyPatches p(1);                // rows 12° high: 30, 30, 24, 24, 18, 12, 6, then the cap
  EXPECT_EQ(p.index(unit(5, 0)), 1);    // north, first row
  EXPECT_EQ(p.index(unit(5, 359)), 1);  // the half patch west of north is patch 1 too
  EXPECT_EQ(p.index(unit(5, 5.9)), 1);
  EXPECT_EQ(p.index(unit(5, 6.1)), 2);   // from north toward east
  EXPECT_EQ(p.index(unit(5, 90)), 9);    // east
  EXPECT_EQ(p.index(unit(13, 0)), 31);   // second row starts at 12°
  EXPECT_EQ(p.index(unit(80, 0)), 139);  // seventh row, 72°–84°
  EXPECT_EQ(p.index(unit(85, 200)), 145);
  EXPECT_EQ(p.index({0, 0, 1}), 145);
  EXPECT_EQ(p.index({0, 1, 0}), 1);  // the horizon is sky (reinhart.cal: only alt < 0 is ground)
  EXPECT_EQ(p.index({0.3, 0.2, -0.01}), 0);
  // north_deg 90: north is −x; a low direction toward −x is patch 1, toward +y (east: (cos n, sin
  // n, 0)) patch 9.
  const SkyPatches turned(1, 90);
  EXPECT_EQ(turned.index({-1, 0, 0.05}), 1);
  EXPECT_EQ(turned.index({0, 1, 0.05}), 9);
  EXPECT_EQ(turned.index({0, -1, 0.05}), 24);  // west, 270°: 1 + 270 / 12
  // Patch 9's centre is at azimuth 96° (8 × 12°; 90° is its lower edge), altitude 6°.
  const double c6 = std::cos(6 * kPi / 180), a96 = 96 * kPi / 180;
  EXPECT_NEAR(
      glm::length(turned.patch(9).centre -
                  glm::dvec3(-c6 * std::cos(a96), c6 * std::sin(a96), std::sin(6 * kPi / 180))),
      0.0, 1e-12);
}

TEST(SkyPatches, EveryPatchOwnsItsBoxAndItsCentre) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.001, 0.999);
  for (int mf : {1, 2, 4}) {
    for (double north : {0.0, 37.0}) {
      const SkyPatches p(mf, north);
      for (int i = 1; i < p.count(); ++i) {
        const auto& q = p.patch(i);
        ASSERT_EQ(p.index(q.centre), i) << mf << " " << i;
        ASSERT_NEAR(glm::length(q.centre), 1.0, 1e-12);
        for (int k = 0; k < 8; ++k) {
          const double alt =
              q.altitude_min_deg + u(rng) * (q.altitude_max_deg - q.altitude_min_deg);
          const double azi = q.azimuth_deg + (u(rng) - 0.5) * q.azimuth_width_deg;
          ASSERT_EQ(p.index(p.direction(alt, azi)), i)
              << mf << " " << i << " " << alt << " " << azi;
        }
      }
      EXPECT_EQ(p.index(p.patch(0).centre), 0);
    }
  }
}

TEST(SkyPatches, BadInputNamesTheField) {
  auto what = [](auto f) {
    try {
      f();
    } catch (const lightsolver::InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(what([] { SkyPatches(0); }).find("mf"), std::string::npos);
  EXPECT_NE(what([] { SkyPatches(1, NAN); }).find("north_deg"), std::string::npos);
  EXPECT_NE(what([] { SkyPatches(1).index({0, 0, 0}); }).find("direction"), std::string::npos);
  EXPECT_NE(what([] { SkyPatches(1).index({NAN, 0, 1}); }).find("direction"), std::string::npos);
}

}  // namespace
