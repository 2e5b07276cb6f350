// EULUMDAT parsing: symmetry indicators 0-4, lamp sets, cd/klm, absolute photometry.

#include "photometry_test_util.hpp"

namespace lightsolver {
namespace {

using test::corpus_file;
using test::sample_file;

// All corpus files use 2000 lm of lamps and conversion factor 1: cd = cd/klm x 2.
constexpr double kScale = 2.0;

void expect_row(const PhotometricData& d, std::size_t h, const std::vector<double>& cd_per_klm) {
  ASSERT_EQ(d.vertical_angles_deg.size(), cd_per_klm.size());
  for (std::size_t v = 0; v < cd_per_klm.size(); ++v)
    EXPECT_DOUBLE_EQ(d.candela_at(h, v), cd_per_klm[v] * kScale) << "plane " << h << " v " << v;
}

TEST(ParseLdt, Isym0KeepsEveryPlaneAndClosesTheCircle) {
  const auto d = load_photometry(corpus_file("ldt/isym0_none.ldt"));
  EXPECT_EQ(d.format, PhotometricFormat::Eulumdat);
  EXPECT_EQ(d.symmetry, PhotometricSymmetry::None);
  ASSERT_EQ(d.horizontal_angles_deg, (std::vector<double>{0, 90, 180, 270, 360}));
  expect_row(d, 0, {500, 300, 10});
  expect_row(d, 3, {450, 260, 40});
  expect_row(d, 4, {500, 300, 10});
  EXPECT_DOUBLE_EQ(d.rated_lumens_lm, 2000.0);
  EXPECT_DOUBLE_EQ(d.light_output_ratio_percent, 85.0);
}

TEST(ParseLdt, Isym1IsRotational) {
  const auto d = load_photometry(corpus_file("ldt/isym1_rotational.ldt"));
  EXPECT_EQ(d.symmetry, PhotometricSymmetry::Rotational);
  ASSERT_EQ(d.horizontal_angles_deg, (std::vector<double>{0, 360}));
  expect_row(d, 1, {400, 350, 150, 0});
  EXPECT_EQ(d.opening_shape, OpeningShape::Disk);  // luminous width 0: circular
  EXPECT_DOUBLE_EQ(d.opening_length_m, 0.12);
  EXPECT_DOUBLE_EQ(d.opening_width_m, 0.12);
}

TEST(ParseLdt, Isym2MirrorsAboutC0C180) {
  const auto d = load_photometry(corpus_file("ldt/isym2_c0_c180.ldt"));
  EXPECT_EQ(d.symmetry, PhotometricSymmetry::BilateralC0C180);
  ASSERT_EQ(d.horizontal_angles_deg, (std::vector<double>{0, 90, 180, 270, 360}));
  expect_row(d, 1, {400, 250, 20});
  expect_row(d, 2, {300, 200, 30});
  expect_row(d, 3, {400, 250, 20});  // C270 = C90
  EXPECT_EQ(d.opening_shape, OpeningShape::Rectangle);
  EXPECT_DOUBLE_EQ(d.opening_length_m, 0.6);
  EXPECT_DOUBLE_EQ(d.opening_width_m, 0.08);
}

TEST(ParseLdt, Isym3StoresC270ThroughC0ToC90AndMirrorsAboutC90C270) {
  const auto d = load_photometry(corpus_file("ldt/isym3_c90_c270.ldt"));
  EXPECT_EQ(d.symmetry, PhotometricSymmetry::BilateralC90C270);
  ASSERT_EQ(d.horizontal_angles_deg, (std::vector<double>{0, 90, 180, 270, 360}));
  expect_row(d, 0, {500, 300, 10});  // stored C0
  expect_row(d, 1, {400, 250, 20});  // stored C90
  expect_row(d, 2, {500, 300, 10});  // C180 = C0 mirrored about the C90-C270 plane
  expect_row(d, 3, {450, 260, 40});  // stored C270
}

TEST(ParseLdt, Isym4IsQuadrantSymmetric) {
  const auto d = load_photometry(corpus_file("ldt/isym4_quadrant.ldt"));
  EXPECT_EQ(d.symmetry, PhotometricSymmetry::Quadrant);
  ASSERT_EQ(d.horizontal_angles_deg.size(), 9u);  // 0, 45, ..., 360
  const std::vector<double> c0{300, 280, 200, 90, 0, 0, 0}, c45{300, 270, 180, 80, 0, 0, 0};
  expect_row(d, 1, c45);
  expect_row(d, 3, c45);  // C135
  expect_row(d, 4, c0);   // C180
  expect_row(d, 7, c45);  // C315
}

TEST(ParseLdt, NegativeLampCountMeansAbsolutePhotometry) {
  const auto d = load_photometry(corpus_file("ldt/absolute_negative_lamps.ldt"));
  EXPECT_TRUE(d.absolute_photometry);
  EXPECT_DOUBLE_EQ(d.rated_lumens_lm, 1200.0);  // the luminaire's flux
  // cd/klm x 1.2 klm x conversion factor 2.
  EXPECT_DOUBLE_EQ(d.candela_at(0, 0), 300.0 * 1.2 * 2.0);
  const PhotometricSampler s(d);
  EXPECT_NEAR(s.flux_scale(s.integrated_flux_lm()), 1.0, 1e-12);
}

TEST(ParseLdt, CommaDecimalSeparatorsAndLfLineEnds) {
  const auto d = load_photometry(corpus_file("ldt/comma_decimals.ldt"));
  EXPECT_DOUBLE_EQ(d.vertical_angles_deg[1], 22.5);
  EXPECT_DOUBLE_EQ(d.candela_at(0, 1), 290.25 * kScale);
}

TEST(ParseLdt, SampleFilesCarryTheirHeader) {
  const auto d = load_photometry(sample_file("batwing_panel.ldt"));
  EXPECT_EQ(d.symmetry, PhotometricSymmetry::Quadrant);
  EXPECT_DOUBLE_EQ(d.rated_lumens_lm, 3600.0);
  EXPECT_EQ(d.lamp_count, 4);
  EXPECT_DOUBLE_EQ(d.input_watts, 36.0);  // field 26f, wattage including ballast
  EXPECT_EQ(d.opening_shape, OpeningShape::Rectangle);
  bool found = false;
  for (const auto& [k, v] : d.keywords) found = found || (k == "LUMINAIRE" && v.find("LS-BW") == 0);
  EXPECT_TRUE(found);
  EXPECT_EQ(load_photometry(sample_file("linear_tube.ldt")).symmetry,
            PhotometricSymmetry::BilateralC0C180);
  EXPECT_EQ(load_photometry(sample_file("downlight.ldt")).symmetry,
            PhotometricSymmetry::Rotational);
  EXPECT_EQ(load_photometry(sample_file("wallwasher.ldt")).symmetry, PhotometricSymmetry::None);
}

TEST(ParseLdt, MultipleLampSetsAddTheirFlux) {
  std::vector<std::string> lines{"Two sets", "1",   "1",    "1",    "0",  "2",  "90", "r", "n", "c",
                                 "f",        "d",   "0",    "0",    "0",  "0",  "0",  "0", "0", "0",
                                 "0",        "100", "100",  "1",    "0",  "2",  "1",  "2", "A", "B",
                                 "1000",     "500", "3000", "3000", "80", "80", "10", "10"};
  for (int k = 0; k < 10; ++k) lines.push_back("0");
  for (const char* v : {"0", "0", "90", "100", "0"}) lines.push_back(v);
  const auto d = parse_ldt(test::join_lines(lines), "sets.ldt");
  EXPECT_DOUBLE_EQ(d.rated_lumens_lm, 1500.0);
  EXPECT_EQ(d.lamp_count, 3);
  EXPECT_DOUBLE_EQ(d.input_watts, 20.0);  // each set's wattage, summed
  EXPECT_DOUBLE_EQ(d.candela_at(0, 0), 100.0 * 1.5);
}

}  // namespace
}  // namespace lightsolver
