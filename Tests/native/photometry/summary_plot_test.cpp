// photometry_summary() and write_polar_plot_png().

#include <filesystem>

#include "photometry_test_util.hpp"

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

namespace lightsolver {
namespace {

bool contains(const std::string& text, const std::string& needle) {
  return text.find(needle) != std::string::npos;
}

// Numbers printed after `label` (e.g. "C0-C180 " -> 54.0).
double number_after(const std::string& text, const std::string& line_start,
                    const std::string& label) {
  const auto line = text.find(line_start);
  const auto pos = text.find(label, line);
  return pos == std::string::npos ? NAN : std::stod(text.substr(pos + label.size()));
}

TEST(Summary, DownlightBeamAndFieldAnglesMatchTheCosinePower) {
  const auto d = load_photometry(test::sample_file("downlight.ies"));
  const std::string s = photometry_summary(d);
  EXPECT_TRUE(contains(s, "Format: IES LM-63-2002")) << s;
  EXPECT_TRUE(contains(s, "Photometric type: C, symmetry: rotational")) << s;
  EXPECT_TRUE(contains(s, "Lumens (file): 1500.0 lm lamp lumens (1 lamp)")) << s;
  EXPECT_TRUE(contains(s, "[MANUFAC] Lighting project")) << s;
  EXPECT_NEAR(number_after(s, "Lumens (integrated)", ": "), 1500.0, 7.5) << s;
  EXPECT_NEAR(number_after(s, "Peak:", "Peak: "), 1671.1, 0.1) << s;
  // I = I0 cos^6: 50 % at acos(0.5^(1/6)) = 27.0 deg, 10 % at acos(0.1^(1/6)) = 47.1 deg.
  const double beam = 2 * std::acos(std::pow(0.5, 1.0 / 6)) * 180 / std::numbers::pi;
  const double field = 2 * std::acos(std::pow(0.1, 1.0 / 6)) * 180 / std::numbers::pi;
  EXPECT_NEAR(number_after(s, "Beam angle", "C0-C180 "), beam, 0.3) << s;
  EXPECT_NEAR(number_after(s, "Beam angle", "C90-C270 "), beam, 0.3) << s;
  EXPECT_NEAR(number_after(s, "Field angle", "C0-C180 "), field, 0.3) << s;
  EXPECT_TRUE(contains(s, "Opening: disk/ellipse 0.150 x 0.150")) << s;
}

TEST(Summary, AbsoluteTypeBAndWarnings) {
  const std::string a =
      photometry_summary(load_photometry(test::corpus_file("ies/lm63_2002_type_a.ies")));
  EXPECT_TRUE(contains(a, "absolute photometry")) << a;
  EXPECT_TRUE(contains(a, "Beam angle (50 %): H = 0")) << a;
  const std::string b =
      photometry_summary(load_photometry(test::corpus_file("ies/lm63_1995_type_b.ies")));
  EXPECT_TRUE(contains(b, "Peak: 2000.0 cd at H 0.0, V 0.0 deg")) << b;
  const auto odd = parse_ies(
      "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 2 1 1 2 -0.2 0.3 0\n1 1 1\n"
      "0 90\n0\n100 0\n",
      "odd.ies");
  EXPECT_TRUE(contains(photometry_summary(odd), "Warning: luminous opening"));
  const auto dark = parse_ies(
      "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 2 1 1 2 0 0 0\n1 1 1\n"
      "0 90\n0\n0 0\n",
      "dark.ies");
  EXPECT_TRUE(contains(photometry_summary(dark), "Lumens (integrated): 0.0 lm"));
}

TEST(Summary, TiltTableAndHowItIsApplied) {
  const std::string s =
      photometry_summary(load_photometry(test::corpus_file("ies/lm63_1991_tilt_include.ies")));
  EXPECT_TRUE(contains(s, "Tilt: INCLUDE (lamp geometry 1; factor at tilt: 0°=1 15°=0.95")) << s;
  EXPECT_TRUE(contains(s, "applied at the aim's angle from straight down")) << s;
}

TEST(PolarPlot, DrawsBothPlanesOfTheWallWasher) {
  const auto path = (std::filesystem::temp_directory_path() / "lightsolver_polar.png").string();
  write_polar_plot_png(load_photometry(test::sample_file("wallwasher.ldt")), path);
  int w = 0, h = 0, n = 0;
  unsigned char* px = stbi_load(path.c_str(), &w, &h, &n, 3);
  ASSERT_NE(px, nullptr);
  ASSERT_EQ(w, 640);
  ASSERT_EQ(h, 640);
  long red_right = 0, red_left = 0, blue = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const unsigned char* p = px + 3 * (y * w + x);
      if (p[0] == 200 && p[1] == 30 && p[2] == 30) (x > w / 2 ? red_right : red_left)++;
      if (p[0] == 30 && p[1] == 70 && p[2] == 200) ++blue;
    }
  stbi_image_free(px);
  std::filesystem::remove(path);
  // The C0-C180 curve (red) bulges toward C0, drawn on the right; C90-C270 is drawn too.
  EXPECT_GT(red_right, 3 * red_left);
  EXPECT_GT(blue, 200);
  EXPECT_THROW(write_polar_plot_png(load_photometry(test::sample_file("downlight.ies")),
                                    "/nonexistent/dir/plot.png"),
               std::runtime_error);
}

}  // namespace
}  // namespace lightsolver
