// UGR at an observer: luminance and solid angle of an area luminaire, and a configuration
// computed by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "lightsolver/glare.hpp"

namespace lightsolver {
namespace {

constexpr double kPi = std::numbers::pi;

// A 0.6 m x 0.6 m Lambertian panel of 3000 lm facing down, 2 m above the eye.
GlareSource panel(const std::string& name, double x, double y) {
  return lambertian_glare_source(name, {x, y, 3.2}, {0, 0, -1}, 0.36, 3000.0);
}

TEST(ObserverUgr, LuminanceAndSolidAngleOfAnAreaLuminaire) {
  const GlareObserver eye{{0, 0, 1.2}, {0, 1, 0}, {0, 0, 1}};
  const UgrResult r = compute_ugr(eye, {panel("a", 0.0, 4.0)}, 40.0);
  ASSERT_EQ(r.contributions.size(), 1u);
  const GlareContribution& c = r.contributions[0];
  ASSERT_TRUE(c.counted);
  // By hand: L = 3000 / (pi 0.36) = 2652.58 cd/m2 whatever the direction (Lambertian);
  // r^2 = 4^2 + 2^2 = 20, cos = 2 / sqrt(20), A_p = 0.36 cos = 0.160997 m2,
  // omega = A_p / r^2 = 0.0080498 sr; H/R = 0.5, T/R = 0 -> p = 2.86.
  EXPECT_NEAR(c.luminance_cd_m2, 2652.582, 1e-3);
  EXPECT_NEAR(c.solid_angle_sr, 0.00804984, 1e-8);
  EXPECT_NEAR(c.h_over_r, 0.5, 1e-12);
  EXPECT_NEAR(c.t_over_r, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(c.position_index, 2.86);
  EXPECT_NEAR(c.distance_m, std::sqrt(20.0), 1e-12);
}

TEST(ObserverUgr, HandComputedConfiguration) {
  const GlareObserver eye{{0, 0, 1.2}, {0, 1, 0}, {0, 0, 1}};
  const std::vector<GlareSource> sources{
      panel("ahead", 0.0, 4.0),     // term 2652.58^2 0.0080498 / 2.86^2 = 6924.58
      panel("aside", 2.0, 4.0),     // T/R = 0.5, p = 2.91, omega = 0.0061237: term 5088.24
      panel("behind", 0.0, -2.0),   // behind the eye
      panel("overhead", 0.0, 1.0),  // H/R = 2: beyond the table
  };
  const UgrResult r = compute_ugr(eye, sources, 40.0);
  // UGR = 8 log10(0.25 / 40 (6924.58 + 5088.24)) = 15.0042.
  ASSERT_TRUE(r.ugr.has_value());
  EXPECT_NEAR(*r.ugr, 15.0042, 1e-3);
  EXPECT_NEAR(r.contributions[0].term, 6924.58, 0.01);
  EXPECT_NEAR(r.contributions[1].term, 5088.24, 0.01);
  EXPECT_NEAR(*r.contributions[0].ugr_alone, 13.0902, 1e-3);
  EXPECT_FALSE(r.contributions[2].counted);
  EXPECT_FALSE(r.contributions[3].counted);
  EXPECT_FALSE(r.contributions[2].ugr_alone.has_value());
  // Doubling the background luminance lowers UGR by 8 log10(2).
  EXPECT_NEAR(*compute_ugr(eye, sources, 80.0).ugr, *r.ugr - 8.0 * std::log10(2.0), 1e-9);
}

TEST(ObserverUgr, NoSourceInViewGivesNoValue) {
  const GlareObserver eye{{0, 0, 1.2}, {0, 1, 0}, {0, 0, 1}};
  const UgrResult r = compute_ugr(eye, {panel("behind", 0.0, -3.0)}, 40.0);
  EXPECT_FALSE(r.ugr.has_value());
  EXPECT_EQ(r.sum, 0.0);
}

TEST(ObserverUgr, SourcesOutsideCie117RangeAreFlagged) {
  const GlareObserver eye{{0, 0, 1.2}, {0, 1, 0}, {0, 0, 1}};
  // 0.01 m2 at 8.2 m: omega = 0.01 (2 / 8.25) / 68 = 3.6e-5 sr < 0.0003 sr.
  const UgrResult small = compute_ugr(
      eye, {lambertian_glare_source("tiny", {0, 8, 3.2}, {0, 0, -1}, 0.01, 100.0)}, 40.0);
  ASSERT_EQ(small.warnings.size(), 1u);
  EXPECT_NE(small.warnings[0].find("tiny"), std::string::npos);
  EXPECT_TRUE(small.ugr.has_value());  // still computed
  const UgrResult normal = compute_ugr(eye, {panel("ahead", 0.0, 4.0)}, 40.0);
  EXPECT_TRUE(normal.warnings.empty());
}

TEST(ObserverUgr, BadBackgroundIsAnInputError) {
  const GlareObserver eye;
  EXPECT_THROW(compute_ugr(eye, {}, 0.0), InputError);
  EXPECT_THROW(compute_ugr(eye, {}, std::nan("")), InputError);
}

TEST(ObserverUgr, PhotometricRectangleMatchesItsLambertianEquivalent) {
  // A rectangle opening with a cosine distribution has constant luminance I0 / A.
  auto data = std::make_shared<PhotometricData>();
  data->source_file = "cosine.ies";
  data->absolute_photometry = true;
  data->horizontal_angles_deg = {0.0, 360.0};
  for (int g = 0; g <= 180; g += 5) data->vertical_angles_deg.push_back(g);
  for (int h = 0; h < 2; ++h)
    for (double g : data->vertical_angles_deg)
      data->candela.push_back(g <= 90.0 ? 1000.0 * std::cos(g * kPi / 180.0) : 0.0);
  data->opening_shape = OpeningShape::Rectangle;
  data->opening_length_m = 0.6;
  data->opening_width_m = 0.6;
  auto sampler = std::make_shared<PhotometricSampler>(*data);
  const GlareObserver eye{{0, 0, 1.2}, {0, 1, 0}, {0, 0, 1}};
  const GlareSource s =
      photometric_glare_source("cos", data, sampler, {1.0, 4.0, 3.2}, {0, 0, -1}, {1, 0, 0});
  const UgrResult r = compute_ugr(eye, {s}, 40.0);
  ASSERT_TRUE(r.contributions[0].counted);
  // Bilinear interpolation of cos over 5 degree steps errs by < 0.1 %.
  EXPECT_NEAR(r.contributions[0].luminance_cd_m2, 1000.0 / 0.36, 1000.0 / 0.36 * 1e-3);
  // A point opening has no luminance: refused.
  data->opening_shape = OpeningShape::Point;
  EXPECT_THROW(photometric_glare_source("p", data, sampler, {0, 4, 3.2}, {0, 0, -1}, {1, 0, 0}),
               InputError);
}

TEST(ObserverUgr, ProjectedAreaOfOpenings) {
  PhotometricData d;
  d.opening_shape = OpeningShape::Box;
  d.opening_length_m = 1.2;
  d.opening_width_m = 0.1;
  d.opening_height_m = 0.05;
  const double s = std::sqrt(0.5);
  // Seen from 45 degrees in the C0 plane: bottom 0.12 cos45 + end face 0.1 x 0.05 sin45.
  EXPECT_NEAR(projected_luminous_area_m2(d, {s, 0, -s}), (0.12 + 0.005) * s, 1e-12);
  d.opening_shape = OpeningShape::Disk;
  d.opening_length_m = d.opening_width_m = 0.2;
  EXPECT_NEAR(projected_luminous_area_m2(d, {0, 0, -1}), kPi * 0.01, 1e-12);
  d.opening_shape = OpeningShape::Sphere;
  d.opening_height_m = 0.2;
  EXPECT_NEAR(projected_luminous_area_m2(d, {s, 0, -s}), kPi * 0.01, 1e-12);
}

}  // namespace
}  // namespace lightsolver
