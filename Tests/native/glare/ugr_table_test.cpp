// The tabular method (CIE 190): transfer factors against CIE 190's Table 5, and the table's
// internal consistency on shipped luminaires (the published tables of CIE 190's example
// luminaire: ugr_table_reference_test.cpp; docs/glare.md).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "lightsolver/glare.hpp"

namespace lightsolver {
namespace {

std::string luminaire(const char* name) {
  return std::string(LIGHTSOLVER_SOURCE_DIR) + "/Resources/luminaires/" + name;
}

// The batwing panel's table, computed once for the tests that only read it.
const UgrTable& batwing_table() {
  static const UgrTable t = ugr_table(load_photometry(luminaire("batwing_panel.ldt")));
  return t;
}

// A 0.6 m square opening with a cosine (Lambertian) distribution, 1000 cd at nadir.
PhotometricData cosine_panel() {
  PhotometricData d;
  d.source_file = "cosine.ies";
  d.absolute_photometry = true;
  d.horizontal_angles_deg = {0.0, 360.0};
  for (int g = 0; g <= 180; g += 5) d.vertical_angles_deg.push_back(g);
  for (int h = 0; h < 2; ++h)
    for (double g : d.vertical_angles_deg)
      d.candela.push_back(g <= 90.0 ? 1000.0 * std::cos(g * std::numbers::pi / 180.0) : 0.0);
  d.opening_shape = OpeningShape::Rectangle;
  d.opening_length_m = d.opening_width_m = 0.6;
  return d;
}

TEST(UgrTable, TransferFactorsReproduceCie190Table5) {
  // CIE 190:2010 Table 5, room 4H x 8H (k = 2.67), printed to three decimals
  // (F_T,FW, F_T,WW-1, F_T,CW) as quoted by the public eulumdat-ugr package (background.py).
  struct Row {
    RoomReflectances rho;
    double fw, ww, cw;
  };
  const Row rows[] = {{{0.7, 0.5, 0.2}, 0.115, 0.211, 0.307},
                      {{0.7, 0.3, 0.2}, 0.106, 0.117, 0.283},
                      {{0.5, 0.5, 0.2}, 0.100, 0.187, 0.211},
                      {{0.5, 0.3, 0.2}, 0.093, 0.104, 0.196},
                      {{0.3, 0.3, 0.2}, 0.081, 0.092, 0.114}};
  for (const Row& r : rows) {
    const WallTransferFactors t = wall_transfer_factors(8.0, 16.0, 2.0, r.rho);
    EXPECT_NEAR(t.floor_to_walls, r.fw, 6e-4) << r.rho.ceiling << "/" << r.rho.walls;
    EXPECT_NEAR(t.walls_to_walls, r.ww, 6e-4) << r.rho.ceiling << "/" << r.rho.walls;
    EXPECT_NEAR(t.ceiling_to_walls, r.cw, 6e-4) << r.rho.ceiling << "/" << r.rho.walls;
  }
}

TEST(UgrTable, DirectFloorFluxOfALambertianArray) {
  // Room 4H x 8H (row 10), spacing 1 H: the array's direct flux on the reference plane is the
  // mean view factor from a downward-facing point to the floor rectangle, 0.72000 (closed
  // form, summed over the 32 luminaires by hand script); CIE 190's zonal factors for k = 2.67
  // (F_GL = 0.280, 0.165, 0.499, 0.006) give 0.7161 for the same distribution.
  UgrTableOptions o;
  o.spacing_to_height = 1.0;
  const UgrTable t = ugr_table(cosine_panel(), o);
  ASSERT_EQ(t.rows[10].x_h, 4.0);
  ASSERT_EQ(t.rows[10].y_h, 8.0);
  EXPECT_NEAR(t.rows[10].direct_floor_fraction, 0.72000, 1e-3);
  EXPECT_NEAR(t.rows[10].direct_floor_fraction, 0.7161, 6e-3);
}

TEST(UgrTable, HasTheStandardRoomsAndColumns) {
  const UgrTable& t = batwing_table();
  ASSERT_EQ(t.rows.size(), 19u);
  ASSERT_EQ(t.reflectances.size(), 5u);
  for (const UgrTableRow& row : t.rows) {
    ASSERT_EQ(row.crosswise.size(), 5u);
    ASSERT_EQ(row.endwise.size(), 5u);
    for (std::size_t k = 0; k < 5; ++k) {
      ASSERT_TRUE(row.crosswise[k] && row.endwise[k]);
      EXPECT_TRUE(std::isfinite(*row.crosswise[k]));
      EXPECT_GT(row.background_luminance_cd_m2[k], 0.0);
    }
  }
  EXPECT_EQ(t.rows.front().x_h, 2.0);
  EXPECT_EQ(t.rows.back().y_h, 8.0);
}

TEST(UgrTable, RotationalSymmetryGivesEqualCrosswiseAndEndwise) {
  const UgrTable t = ugr_table(load_photometry(luminaire("downlight.ies")));  // round, rotational
  for (const UgrTableRow& row : t.rows)
    for (std::size_t k = 0; k < 5; ++k)
      EXPECT_NEAR(*row.crosswise[k], *row.endwise[k], 0.02) << row.x_h << "x" << row.y_h;
}

TEST(UgrTable, DoublingTheFluxAddsEightLogTwo) {
  // L^2 grows 4-fold and L_b 2-fold: the ratio in the logarithm doubles.
  const PhotometricData d = load_photometry(luminaire("batwing_panel.ldt"));
  const UgrTable& one = batwing_table();
  UgrTableOptions twice;
  twice.flux_scale = 2.0;
  const UgrTable two = ugr_table(d, twice);
  for (std::size_t i = 0; i < one.rows.size(); ++i)
    for (std::size_t k = 0; k < 5; ++k)
      EXPECT_NEAR(*two.rows[i].crosswise[k] - *one.rows[i].crosswise[k], 8.0 * std::log10(2.0),
                  1e-9);
}

TEST(UgrTable, ScaleFree) {
  // Rooms are in multiples of H: the table does not depend on H itself.
  const PhotometricData d = load_photometry(luminaire("linear_tube.ldt"));
  UgrTableOptions low, tall;
  low.spacing_to_height = tall.spacing_to_height = 0.5;  // fewer luminaires: a faster test
  tall.height_m = 3.0;
  const UgrTable a = ugr_table(d, low), b = ugr_table(d, tall);
  // L is the same along the same directions, omega and L_b both scale as 1 / H^2; what is left
  // is the quadrature of the floor flux.
  for (std::size_t i = 0; i < a.rows.size(); ++i)
    EXPECT_NEAR(*a.rows[i].endwise[0], *b.rows[i].endwise[0], 1e-6);
}

TEST(UgrTable, WideSpreadGlareGrowsWithRoomLengthThenSaturates) {
  const UgrTable& t = batwing_table();
  // Rows 0..5: X = 2H, Y = 2H, 3H, 4H, 6H, 8H, 12H.
  for (std::size_t i = 1; i < 6; ++i)
    EXPECT_GT(*t.rows[i].crosswise[0], *t.rows[i - 1].crosswise[0]);
  const double first_step = *t.rows[1].crosswise[0] - *t.rows[0].crosswise[0];
  const double last_step = *t.rows[5].crosswise[0] - *t.rows[4].crosswise[0];
  EXPECT_LT(last_step, 0.25 * first_step);
}

TEST(UgrTable, DarkerRoomsGlareMore) {
  // Lower wall reflectance lowers L_b: UGR rises (columns 0.7/0.5 -> 0.7/0.3).
  const UgrTable& t = batwing_table();
  for (const UgrTableRow& row : t.rows) EXPECT_GT(*row.crosswise[1], *row.crosswise[0]);
}

TEST(UgrTable, ObserverMethodWithTheTablesGeometryGivesTheTablesValue) {
  // The documented conventions, through the public observer API: room 4H x 8H (H = 2 m),
  // S = 1 H, eye on the mid-wall at the reference plane looking along +y, luminaires aimed
  // down with C0 toward the observer (crosswise), L_b as the table computed it.
  const PhotometricData d = load_photometry(luminaire("batwing_panel.ldt"));
  UgrTableOptions o;
  o.spacing_to_height = 1.0;
  const UgrTable t = ugr_table(d, o);
  auto data = std::make_shared<const PhotometricData>(d);
  auto sampler = std::make_shared<const PhotometricSampler>(d);
  std::vector<GlareSource> sources;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 8; ++j)
      sources.push_back(photometric_glare_source(
          "", data, sampler, {-4.0 + 2.0 * i + 1.0, 2.0 * j + 1.0, 2.0}, {0, 0, -1}, {0, -1, 0}));
  const GlareObserver eye{{0, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const UgrTableRow& row = t.rows[10];
  const UgrResult r = compute_ugr(eye, sources, row.background_luminance_cd_m2[0]);
  ASSERT_TRUE(r.ugr.has_value());
  EXPECT_NEAR(*r.ugr, *row.crosswise[0], 1e-9);
}

TEST(UgrTable, PointOpeningIsRefused) {
  PhotometricData d = load_photometry(luminaire("downlight.ies"));
  d.opening_shape = OpeningShape::Point;
  EXPECT_THROW(ugr_table(d), InputError);
}

}  // namespace
}  // namespace lightsolver
