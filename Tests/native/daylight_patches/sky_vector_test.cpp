// Sky vectors (src/daylight/sky_vector.cpp): each patch's integral of the sky model, the sun kept
// apart (or put into patches as gendaymtx does), the horizontal illuminance rebuilt from them.
#include "daylight/sky_vector.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "daylight/sky_models.hpp"
#include "lightsolver/angles.hpp"
#include "lightsolver/sky_patches.hpp"

namespace {

using lightsolver::kPi;

using namespace lightsolver::daylight;
using lightsolver::SkyPatches;

Direction sun_at(double alt_deg, double azi_deg) {  // Radiance's frame: x east, y north
  const double a = alt_deg * kPi / 180, z = azi_deg * kPi / 180;
  return {std::cos(a) * std::sin(z), std::cos(a) * std::cos(z), std::sin(a)};
}

SkySpec perez(double dhi, double dni, double alt, double azi) {
  SkySpec s;
  s.model = SkyModel::Perez;
  s.sun = sun_at(alt, azi);
  s.perez.diffuse_horizontal = dhi;
  s.perez.direct_normal = dni;
  return s;
}

SkySpec cie(int type, double alt, double azi) {
  SkySpec s;
  s.model = SkyModel::CieGeneral;
  s.cie_type = type;
  s.sun = sun_at(alt, azi);
  s.level = 20000.0;
  return s;
}

// Σ patches × their mean cos Z: the horizontal illuminance daylight coefficients give an
// unobstructed upward sensor (each patch taken as uniform), and the same at the centres.
double rebuilt(const SkyVector& v, const SkyPatches& p, bool centre = false) {
  double e = 0.0;
  for (int i = 1; i < p.count(); ++i)
    e += v.patches[static_cast<std::size_t>(i)] *
         (centre ? p.patch(i).centre.z : p.patch(i).mean_cos_zenith);
  return e;
}

TEST(SkyVector, UniformSkyIsExact) {
  SkySpec s;
  s.model = SkyModel::Uniform;
  s.normalisation = SkyNormalisation::ZenithLuminance;
  s.level = 1000.0;
  s.ground_reflectance = 0.3;
  for (int mf : {1, 2, 4}) {
    const SkyPatches p(mf, 25.0);
    const SkyVector v = sky_vector(s, p);
    for (int i = 1; i < p.count(); ++i)
      ASSERT_NEAR(v.patches[static_cast<std::size_t>(i)], 1000.0 * p.patch(i).solid_angle_sr,
                  1e-12 * 1000.0);
    EXPECT_NEAR(rebuilt(v, p), 1000.0 * kPi, 1e-9);
    EXPECT_NEAR(v.patches[0], 0.3 * 1000.0 * kPi / kPi * 2 * kPi, 1e-9);  // ρ E / π × 2π
    EXPECT_LT(v.quadrature_error, 1e-9);
    EXPECT_EQ(v.sun_direct_normal_lx, 0.0);
  }
}

// The skies the checks below run on: CIE types, overcast, Perez in several bins and sun heights.
std::vector<std::pair<std::string, SkySpec>> skies() {
  std::vector<std::pair<std::string, SkySpec>> r;
  SkySpec over;
  over.model = SkyModel::CieOvercast;
  over.level = 10000.0;
  r.push_back({"overcast", over});
  r.push_back({"cie12 sun 36.7", cie(12, 36.7, 200)});
  r.push_back({"cie12 sun 8", cie(12, 8, 100)});
  r.push_back({"cie3 sun 60", cie(3, 60, 170)});
  r.push_back({"perez overcast", perez(150, 0, 30, 160)});
  r.push_back({"perez intermediate", perez(200, 300, 45, 190)});
  r.push_back({"perez clear", perez(100, 850, 60, 180)});
  r.push_back({"perez clear low sun", perez(40, 500, 5, 250)});
  r.push_back({"perez clear sun on a patch centre", perez(100, 850, 6.0, 0)});
  return r;
}

TEST(SkyVector, EntriesFiniteNonNegativeAndTheQuadratureMatchesTheModel) {
  for (int mf : {1, 2, 4}) {
    const SkyPatches p(mf);
    double worst = 0.0;
    std::string where;
    for (const auto& [name, spec] : skies()) {
      const SkyVector v = sky_vector(spec, p);
      for (double x : v.patches) ASSERT_TRUE(std::isfinite(x) && x >= 0.0) << name;
      // The same rule weighted by cos Z against the model's own horizontal integral (1e-6).
      EXPECT_LT(v.quadrature_error, 5e-5) << name << " MF " << mf;
      if (v.quadrature_error > worst) worst = v.quadrature_error, where = name;
    }
    std::printf("[ sky vector ] MF %d: largest quadrature error of E_h %.1e (%s)\n", mf, worst,
                where.c_str());
  }
}

// Per patch: 4 × 4 points against 12 × 12 (the largest relative difference of any patch holding
// more than 1e-4 of the sky's light): the quadrature's own error.
TEST(SkyVector, FourPointsAgreeWithTwelvePerPatch) {
  for (int mf : {1, 2, 4}) {
    const SkyPatches p(mf);
    double worst = 0.0;
    std::string where;
    for (const auto& [name, spec] : skies()) {
      const SkyVector a = sky_vector(spec, p, {4, false});
      const SkyVector b = sky_vector(spec, p, {12, false});
      double total = 0.0;
      for (int i = 1; i < p.count(); ++i) total += b.patches[static_cast<std::size_t>(i)];
      for (int i = 1; i < p.count(); ++i) {
        const auto k = static_cast<std::size_t>(i);
        if (b.patches[k] < 1e-4 * total) continue;
        const double rel = std::abs(a.patches[k] - b.patches[k]) / b.patches[k];
        if (rel > worst) worst = rel, where = name + " patch " + std::to_string(i);
      }
    }
    std::printf("[ sky vector ] MF %d: 4x4 vs 12x12 points, largest patch difference %.2e (%s)\n",
                mf, worst, where.c_str());
    EXPECT_LT(worst, 1e-3) << where;
  }
}

// Daylight coefficients take each patch as uniform: the horizontal illuminance rebuilt from the
// vector (patch × mean cos Z) differs from the model's by the luminance's variation within a
// patch. It must shrink with MF; the figures are docs/daylight.md's table.
TEST(SkyVector, DiscretisationErrorOfTheHorizontalIlluminanceShrinksWithMf) {
  std::vector<double> worst_by_mf;
  for (int mf : {1, 2, 4}) {
    const SkyPatches p(mf);
    double worst = 0.0, worst_centre = 0.0;
    for (const auto& [name, spec] : skies()) {
      const SkyVector v = sky_vector(spec, p);
      const double e = v.diffuse_horizontal_lx;
      const double rel = std::abs(rebuilt(v, p) - e) / e;
      const double rel_c = std::abs(rebuilt(v, p, true) - e) / e;
      worst = std::max(worst, rel);
      worst_centre = std::max(worst_centre, rel_c);
      std::printf("[ sky vector ] MF %d %-34s E_h %9.1f lx  rebuilt %+.2e  at centres %+.2e\n", mf,
                  name.c_str(), e, (rebuilt(v, p) - e) / e, (rebuilt(v, p, true) - e) / e);
    }
    worst_by_mf.push_back(worst);
    EXPECT_LT(worst, 0.02 / (mf * mf)) << "MF " << mf;
  }
  EXPECT_LT(worst_by_mf[1], worst_by_mf[0]);
  EXPECT_LT(worst_by_mf[2], worst_by_mf[1]);
}

TEST(SkyVector, SunKeptApartOrPutIntoTheNearestPatchesAsGendaymtx) {
  const SkyPatches p(1);
  const SkySpec spec = perez(100, 850, 60, 180);
  const Sky sky(spec);
  const SkyVector apart = sky_vector(spec, p);
  EXPECT_DOUBLE_EQ(apart.sun_direct_normal_lx, sky.perez()->direct_normal_lx);
  EXPECT_GT(apart.sun_direct_normal_lx, 50000.0);
  EXPECT_NEAR(apart.sun_direction.z, std::sin(60 * kPi / 180), 1e-12);
  const SkyVector smeared = sky_vector(spec, p, {4, true});
  EXPECT_EQ(smeared.sun_direct_normal_lx, 0.0);
  double added = 0.0;
  int changed = 0;
  for (int i = 0; i < p.count(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    const double d = smeared.patches[k] - apart.patches[k];
    if (d != 0.0) ++changed, added += d;
    if (d != 0.0)
      EXPECT_LT(std::acos(p.patch(i).centre.z * apart.sun_direction.z +
                          p.patch(i).centre.y * apart.sun_direction.y +
                          p.patch(i).centre.x * apart.sun_direction.x),
                20 * kPi / 180);
  }
  EXPECT_EQ(changed, 4);
  EXPECT_NEAR(added, apart.sun_direct_normal_lx, 1e-9 * added);
  // The ground carries the sun's light on it either way: ρ (E_dh + E_n sin alt).
  EXPECT_NEAR(
      apart.patches[0],
      0.2 * (sky.diffuse_horizontal_lx() + apart.sun_direct_normal_lx * std::sin(kPi / 3)) * 2.0,
      1e-9 * apart.patches[0]);
  // A CIE sky's sun is the given one.
  SkySpec c = cie(12, 30, 90);
  c.sun_direct_normal_lx = 70000.0;
  EXPECT_DOUBLE_EQ(sky_vector(c, p).sun_direct_normal_lx, 70000.0);
}

}  // namespace
