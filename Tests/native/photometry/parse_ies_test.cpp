// IES LM-63 parsing: every version, symmetry and photometric type, TILT, factors, openings.

#include <filesystem>
#include <fstream>

#include "photometry_test_util.hpp"

namespace lightsolver {
namespace {

using test::corpus_file;
using test::sample_file;

std::string keyword(const PhotometricData& d, const std::string& key) {
  for (const auto& [k, v] : d.keywords)
    if (k == key) return v;
  return "<absent>";
}

TEST(ParseIes, Lm63_1986WithoutVersionLineIsRotational) {
  const auto d = load_photometry(corpus_file("ies/lm63_1986_rotational.ies"));
  EXPECT_EQ(d.format_version, "LM-63-1986");
  EXPECT_EQ(d.type, PhotometricType::C);
  EXPECT_EQ(d.symmetry, PhotometricSymmetry::Rotational);
  EXPECT_EQ(keyword(d, ""), "Sample 1986 file without a version line");  // free-form labels
  // Unfolded: C0 and C360 carry the single stored plane.
  ASSERT_EQ(d.horizontal_angles_deg, (std::vector<double>{0, 360}));
  ASSERT_EQ(d.vertical_angles_deg.size(), 5u);
  EXPECT_DOUBLE_EQ(d.candela_at(0, 2), 200.0);
  EXPECT_DOUBLE_EQ(d.candela_at(1, 2), 200.0);
  EXPECT_DOUBLE_EQ(d.rated_lumens_lm, 1000.0);
  EXPECT_EQ(d.opening_shape, OpeningShape::Point);
}

TEST(ParseIes, Lm63_1991TiltIncludeAndOldBallastLampFactor) {
  const auto d = load_photometry(corpus_file("ies/lm63_1991_tilt_include.ies"));
  EXPECT_EQ(d.format_version, "LM-63-1991");
  EXPECT_EQ(keyword(d, "MANUFAC"), "Hand made");
  EXPECT_EQ(d.tilt, "INCLUDE");
  EXPECT_EQ(d.tilt_data.lamp_geometry, 1);
  ASSERT_EQ(d.tilt_data.angles_deg.size(), 7u);
  EXPECT_DOUBLE_EQ(d.tilt_data.angles_deg[6], 90.0);
  EXPECT_DOUBLE_EQ(d.tilt_data.factors[1], 0.95);
  // multiplier 1.5 x ballast 0.9 x ballast-lamp factor 0.8 (applied before LM-63-2002).
  EXPECT_DOUBLE_EQ(d.candela_at(0, 0), 200.0 * 1.5 * 0.9 * 0.8);
  EXPECT_DOUBLE_EQ(d.ballast_lamp_factor, 0.8);
  EXPECT_DOUBLE_EQ(d.rated_lumens_lm, 2 * 500.0);
  EXPECT_EQ(d.lamp_count, 2);
  // Width -0.5 ft with zero length: a disc 0.5 ft across (feet converted to metres).
  EXPECT_EQ(d.opening_shape, OpeningShape::Disk);
  EXPECT_NEAR(d.opening_length_m, 0.1524, 1e-12);
  EXPECT_NEAR(d.opening_width_m, 0.1524, 1e-12);
}

TEST(TiltTable, FactorIsLinearBetweenAnglesAndHoldsTheEndValues) {
  const TiltData t = load_photometry(corpus_file("ies/lm63_1991_tilt_include.ies")).tilt_data;
  EXPECT_DOUBLE_EQ(t.factor_at(0.0), 1.0);
  EXPECT_DOUBLE_EQ(t.factor_at(15.0), 0.95);
  EXPECT_DOUBLE_EQ(t.factor_at(90.0), 0.94);
  EXPECT_NEAR(t.factor_at(37.5), 0.92, 1e-12);  // halfway from .94 (30) to .90 (45)
  EXPECT_NEAR(t.factor_at(80.0), 0.87 + (0.94 - 0.87) / 3.0, 1e-12);
  EXPECT_DOUBLE_EQ(t.factor_at(-5.0), 1.0);           // before the first angle: its factor
  EXPECT_DOUBLE_EQ(t.factor_at(150.0), 0.94);         // after the last angle: its factor
  EXPECT_DOUBLE_EQ(TiltData{}.factor_at(40.0), 1.0);  // TILT=NONE
}

TEST(ParseIes, Lm63_1995Bilateral90To270UnfoldsByMirror) {
  const auto d = load_photometry(corpus_file("ies/lm63_1995_bilateral_90_270.ies"));
  EXPECT_EQ(d.symmetry, PhotometricSymmetry::BilateralC90C270);
  EXPECT_EQ(keyword(d, "LUMINAIRE"),
            "Wall mounted, symmetric about the 90-270 plane\nsecond line of the description");
  ASSERT_EQ(d.horizontal_angles_deg, (std::vector<double>{0, 90, 180, 270, 360}));
  // I(C) = I(180 - C): C0 takes the stored C180 plane; C90, C270 stay; C360 = C0.
  EXPECT_DOUBLE_EQ(d.candela_at(0, 0), 300.0);
  EXPECT_DOUBLE_EQ(d.candela_at(1, 1), 80.0);
  EXPECT_DOUBLE_EQ(d.candela_at(2, 2), 60.0);
  EXPECT_DOUBLE_EQ(d.candela_at(3, 1), 90.0);
  EXPECT_DOUBLE_EQ(d.candela_at(4, 0), 300.0);
  EXPECT_EQ(d.opening_shape, OpeningShape::Rectangle);
  EXPECT_DOUBLE_EQ(d.opening_length_m, 0.6);  // length runs along C0 (x)
  EXPECT_DOUBLE_EQ(d.opening_width_m, 0.3);
}

TEST(ParseIes, Bilateral0To180MirrorsAboutTheC0C180Plane) {
  const auto d = parse_ies(
      "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 2 3 1 2 0 0 0\n1 1 10\n0 90\n0 90 180\n"
      "100 10\n200 20\n300 30\n",
      "bilateral.ies");
  EXPECT_EQ(d.symmetry, PhotometricSymmetry::BilateralC0C180);
  ASSERT_EQ(d.horizontal_angles_deg, (std::vector<double>{0, 90, 180, 270, 360}));
  EXPECT_DOUBLE_EQ(d.candela_at(3, 0), 200.0);  // C270 = C90
  EXPECT_DOUBLE_EQ(d.candela_at(4, 1), 10.0);   // C360 = C0
  const PhotometricSampler s(d);
  EXPECT_NEAR(s.intensity_cd({0, -1, 0}), s.intensity_cd({0, 1, 0}), 1e-12);  // y mirror
  EXPECT_NEAR(s.intensity_cd({0, 1, 0}), 20.0, 1e-9);
}

TEST(ParseIes, Lm63_1995TypeBMirrorsLaterallyAndPointsAlongMinusZ) {
  const auto d = load_photometry(corpus_file("ies/lm63_1995_type_b.ies"));
  EXPECT_EQ(d.type, PhotometricType::B);
  EXPECT_EQ(d.symmetry, PhotometricSymmetry::LateralAB);
  ASSERT_EQ(d.horizontal_angles_deg, (std::vector<double>{-90, -45, 0, 45, 90}));
  EXPECT_DOUBLE_EQ(d.candela_at(1, 2), 1000.0);  // H -45 mirrors H 45
  const PhotometricSampler s(d);
  EXPECT_NEAR(s.intensity_cd({0, 0, -1}), 2000.0, 1e-9);  // H = V = 0 is the aim
  const double r = std::sqrt(0.5);
  EXPECT_NEAR(s.intensity_cd({0, r, -r}), 1000.0, 1e-6);   // H = 45: toward +y
  EXPECT_NEAR(s.intensity_cd({0, -r, -r}), 1000.0, 1e-6);  // H = -45
  EXPECT_NEAR(s.intensity_cd({r, 0, -r}), 1000.0, 1e-6);   // V = 45: toward +x
  EXPECT_DOUBLE_EQ(s.intensity_cd({0, 0, 1}), 0.0);        // behind: outside the data
}

TEST(ParseIes, Lm63_2002TypeAAbsolutePhotometry) {
  const auto d = load_photometry(corpus_file("ies/lm63_2002_type_a.ies"));
  EXPECT_EQ(d.type, PhotometricType::A);
  EXPECT_EQ(d.symmetry, PhotometricSymmetry::None);
  EXPECT_TRUE(d.absolute_photometry);
  EXPECT_DOUBLE_EQ(d.rated_lumens_lm, 0.0);
  const PhotometricSampler s(d);
  EXPECT_NEAR(s.intensity_cd({0, 0, -1}), 400.0, 1e-9);  // H = V = 0
  EXPECT_NEAR(s.intensity_cd({0, 1, 0}), 50.0, 1e-9);    // H = 90: +y
  EXPECT_NEAR(s.intensity_cd({0, -1, 0}), 100.0, 1e-9);  // H = -90
  EXPECT_NEAR(s.intensity_cd({1, 0, 0}), 0.0, 1e-9);     // V = 90: +x
  // Absolute photometry: a requested flux scales by the integrated flux.
  EXPECT_NEAR(s.flux_scale(2.0 * s.integrated_flux_lm()), 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(s.flux_scale(std::nullopt), 1.0);
}

TEST(ParseIes, Lm63_2002MultiplierBallastFeetAndOwn360Plane) {
  const auto d = load_photometry(corpus_file("ies/lm63_2002_absolute_feet.ies"));
  EXPECT_EQ(d.symmetry, PhotometricSymmetry::None);
  EXPECT_DOUBLE_EQ(d.candela_multiplier, 2.0);
  EXPECT_DOUBLE_EQ(d.ballast_factor, 0.9);
  EXPECT_DOUBLE_EQ(d.ballast_lamp_factor, 1.0);  // not applied from LM-63-2002 on
  EXPECT_DOUBLE_EQ(d.candela_at(0, 0), 100.0 * 2.0 * 0.9);
  EXPECT_DOUBLE_EQ(d.candela_at(3, 1), 80.0 * 2.0 * 0.9);
  ASSERT_EQ(d.horizontal_angles_deg.size(), 5u);  // its own 360 plane, no duplicate
  EXPECT_EQ(d.opening_shape, OpeningShape::Box);
  EXPECT_NEAR(d.opening_width_m, 0.3048, 1e-12);
  EXPECT_NEAR(d.opening_length_m, 0.6096, 1e-12);
  EXPECT_NEAR(d.opening_height_m, 0.1524, 1e-12);
}

TEST(ParseIes, Lm63_2019QuadrantSphereAndFileGenerationType) {
  const auto d = load_photometry(corpus_file("ies/lm63_2019_quadrant.ies"));
  EXPECT_EQ(d.format_version, "LM-63-2019");
  EXPECT_EQ(d.symmetry, PhotometricSymmetry::Quadrant);
  EXPECT_DOUBLE_EQ(d.file_generation_type, 1.1);
  EXPECT_DOUBLE_EQ(d.ballast_lamp_factor, 1.0);  // the 2019 field is not a factor
  ASSERT_EQ(d.horizontal_angles_deg,
            (std::vector<double>{0, 45, 90, 135, 180, 225, 270, 315, 360}));
  const std::vector<double> c45{100, 80, 20}, c90{100, 90, 30}, c0{100, 60, 10};
  for (int v = 0; v < 3; ++v) {
    EXPECT_DOUBLE_EQ(d.candela_at(3, v), c45[v]);  // C135 = C45
    EXPECT_DOUBLE_EQ(d.candela_at(4, v), c0[v]);   // C180 = C0
    EXPECT_DOUBLE_EQ(d.candela_at(5, v), c45[v]);  // C225 = C45
    EXPECT_DOUBLE_EQ(d.candela_at(6, v), c90[v]);  // C270 = C90
    EXPECT_DOUBLE_EQ(d.candela_at(8, v), c0[v]);   // C360 = C0
  }
  EXPECT_EQ(d.opening_shape, OpeningShape::Sphere);
  EXPECT_DOUBLE_EQ(d.opening_length_m, 0.2);
}

TEST(ParseIes, TiltFileResolvedNextToTheIesFile) {
  const auto dir = std::filesystem::temp_directory_path() / "lightsolver_tilt_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "lamp_tilt.dat") << "2\n3\n0 45 90\n1 0.9 0.8\n";
  std::filesystem::copy_file(corpus_file("ies/lm63_1995_tilt_file.ies"), dir / "lum.ies",
                             std::filesystem::copy_options::overwrite_existing);
  const auto d = load_photometry((dir / "lum.ies").string());
  EXPECT_EQ(d.tilt, "lamp_tilt.dat");
  EXPECT_EQ(d.tilt_data.lamp_geometry, 2);
  EXPECT_EQ(d.tilt_data.factors, (std::vector<double>{1, 0.9, 0.8}));
  // In memory there is no directory to look in.
  test::expect_input_error([] { parse_ies("IESNA:LM-63-1995\nTILT=x.dat\n", "mem.ies"); }, 2,
                           "no directory");
  std::filesystem::remove(dir / "lamp_tilt.dat");
  test::expect_input_error([&] { load_photometry((dir / "lum.ies").string()); }, 3,
                           "TILT file not found");
  std::filesystem::remove_all(dir);
}

TEST(ParseIes, SampleFilesDeclareTheirVersionsAndShapes) {
  const auto tube = load_photometry(sample_file("linear_tube.ies"));
  EXPECT_EQ(tube.format_version, "LM-63-2019");
  EXPECT_EQ(tube.symmetry, PhotometricSymmetry::BilateralC0C180);
  EXPECT_EQ(tube.opening_shape, OpeningShape::HorizontalCylinderC0);
  EXPECT_DOUBLE_EQ(tube.opening_length_m, 1.2);
  EXPECT_DOUBLE_EQ(tube.opening_width_m, 0.026);
  const auto down = load_photometry(sample_file("downlight.ies"));
  EXPECT_EQ(down.format_version, "LM-63-2002");
  EXPECT_EQ(down.opening_shape, OpeningShape::Disk);
  const auto panel = load_photometry(sample_file("batwing_panel.ies"));
  EXPECT_EQ(panel.symmetry, PhotometricSymmetry::Quadrant);
  EXPECT_DOUBLE_EQ(panel.candela_multiplier, 0.5);
  EXPECT_EQ(panel.lamp_count, 4);
  EXPECT_DOUBLE_EQ(panel.rated_lumens_lm, 3600.0);
  const auto wash = load_photometry(sample_file("wallwasher.ies"));
  EXPECT_EQ(wash.symmetry, PhotometricSymmetry::None);
  EXPECT_EQ(wash.horizontal_angles_deg.size(), 73u);
}

TEST(ParseIes, OpeningShapesOfLm63_2002Table) {
  const auto opening = [](const std::string& wlh) {
    const std::string text =
        "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 2 1 1 2 " + wlh + "\n1 1 10\n0 90\n0\n100 0\n";
    return parse_ies(text, "shape.ies");
  };
  EXPECT_EQ(opening("0 0 0").opening_shape, OpeningShape::Point);
  EXPECT_EQ(opening("0.2 0.4 0").opening_shape, OpeningShape::Rectangle);
  EXPECT_EQ(opening("0.2 0.4 0.1").opening_shape, OpeningShape::Box);
  EXPECT_EQ(opening("-0.2 -0.3 0").opening_shape, OpeningShape::Disk);
  EXPECT_EQ(opening("-0.2 -0.2 0.1").opening_shape, OpeningShape::VerticalCylinder);
  EXPECT_EQ(opening("-0.2 -0.2 -0.2").opening_shape, OpeningShape::Sphere);
  EXPECT_EQ(opening("-0.1 0.5 -0.1").opening_shape, OpeningShape::HorizontalCylinderC0);
  EXPECT_EQ(opening("0.5 -0.1 -0.1").opening_shape, OpeningShape::HorizontalCylinderC90);
  const auto vdisk = opening("0 -0.3 -0.3");
  EXPECT_EQ(vdisk.opening_shape, OpeningShape::VerticalDisk);
  EXPECT_DOUBLE_EQ(vdisk.opening_length_m, 0.0);
  EXPECT_DOUBLE_EQ(vdisk.opening_width_m, 0.3);
  const auto odd = opening("-0.2 0.3 0");  // no LM-63 shape: warned, kept as a rectangle
  EXPECT_EQ(odd.opening_shape, OpeningShape::Rectangle);
  EXPECT_EQ(odd.warnings.size(), 1u);
}

TEST(ParseIes, CommasAndCrOnlyLineEndsAreAccepted) {
  const std::string text =
      "IESNA:LM-63-2002\r[TEST] cr\rTILT=NONE\r1,1000,1,2,1,1,2,0,0,0\r1,1,10\r0,90\r0\r100,0\r";
  const auto d = parse_ies(text, "cr.ies");
  EXPECT_DOUBLE_EQ(d.candela_at(0, 0), 100.0);
}

}  // namespace
}  // namespace lightsolver
