// The sampler on synthetic distributions: exact cell flux, exact sampling inside coarse cells,
// types A and B, luminous openings, flux scaling and the luminaire frame.

#include "photometry_test_util.hpp"

namespace lightsolver {
namespace {

using test::kZLimit;

constexpr long kSamples = 200000;

// Type C, no symmetry, deliberately coarse (cells of 60 x 120 degrees) and uneven, so the
// sampling inside one cell (not only the choice of cell) is what the histogram checks.
PhotometricData coarse_c() {
  return parse_ies(
      "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 4 4 1 2 0 0 0\n1 1 10\n0 60 120 180\n"
      "0 120 240 360\n"
      "500 400 0 0\n500 50 300 20\n500 900 10 0\n500 400 0 0\n",
      "coarse.ies");
}

double z_score_of(const PhotometricSampler& s, const std::function<double(glm::dvec3)>& I,
                  std::uint64_t seed) {
  const test::SphereBins bins;
  const auto observed = test::sample_histogram(s, bins, kSamples, seed);
  const auto p = test::expected_probabilities(bins, I, s.integrated_flux_lm());
  return test::max_z_score(observed, p, kSamples);
}

TEST(Sampler, CellFluxIsTheExactIntegralOfTheBilinearPatch) {
  // Isotropic 100 cd: the bilinear patch is exact, 4 pi 100 lm.
  const auto iso = parse_ies(
      "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 3 1 1 2 0 0 0\n1 1 10\n0 90 180\n0\n100 100 100\n",
      "iso.ies");
  EXPECT_NEAR(PhotometricSampler(iso).integrated_flux_lm(), 4 * std::numbers::pi * 100, 1e-9);
  // I falls linearly from 100 cd at gamma 0 to 0 at 90: 2 pi 100 (1 - 2 / pi) in closed form.
  const auto ramp = parse_ies(
      "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n100 0\n", "r.ies");
  EXPECT_NEAR(PhotometricSampler(ramp).integrated_flux_lm(),
              2 * std::numbers::pi * 100 * (1 - 2 / std::numbers::pi), 1e-9);
}

TEST(Sampler, FineCosineGridIntegratesToPiTimesPeak) {
  std::string text = "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 901 1 1 2 0 0 0\n1 1 10\n";
  std::string values;
  for (int k = 0; k <= 900; ++k) {
    text += std::to_string(k * 0.1) + " ";
    values += std::to_string(1000.0 * std::cos(k * 0.1 * std::numbers::pi / 180)) + " ";
  }
  const auto d = parse_ies(text + "\n0\n" + values + "\n", "cos.ies");
  EXPECT_NEAR(PhotometricSampler(d).integrated_flux_lm() / (std::numbers::pi * 1000), 1.0, 1e-5);
}

TEST(Sampler, IntensityInterpolatesBilinearlyBetweenNodes) {
  const PhotometricSampler s(coarse_c());
  const auto dir = [](double c_deg, double g_deg) {
    const double c = c_deg * std::numbers::pi / 180, g = g_deg * std::numbers::pi / 180;
    return glm::dvec3{std::sin(g) * std::cos(c), std::sin(g) * std::sin(c), -std::cos(g)};
  };
  EXPECT_NEAR(s.intensity_cd(dir(0, 60)), 400.0, 1e-9);
  EXPECT_NEAR(s.intensity_cd(dir(120, 120)), 300.0, 1e-9);
  EXPECT_NEAR(s.intensity_cd(dir(60, 60)), 0.5 * (400 + 50), 1e-9);   // halfway in C
  EXPECT_NEAR(s.intensity_cd(dir(240, 90)), 0.5 * (900 + 10), 1e-9);  // halfway in gamma
  EXPECT_NEAR(s.intensity_cd(dir(180, 90)), 0.25 * (50 + 300 + 900 + 10), 1e-9);
  EXPECT_NEAR(s.intensity_cd(dir(359.9999, 60)), 400.0, 1e-3);  // C360 = C0 closes the circle
  EXPECT_NEAR(s.intensity_cd(2.0 * dir(0, 60)), 400.0, 1e-9);   // need not be normalised
}

TEST(Sampler, SamplesInsideCoarseCellsFollowTheBilinearIntensity) {
  const PhotometricSampler s(coarse_c());
  const auto I = [&](glm::dvec3 d) { return s.intensity_cd(d); };
  const test::SphereBins bins;
  const auto p = test::expected_probabilities(bins, I, s.integrated_flux_lm());
  double sum = 0;
  for (double x : p) sum += x;
  EXPECT_NEAR(sum, 1.0, 1e-3);  // quadrature of intensity_cd agrees with the exact cell fluxes
  EXPECT_LE(z_score_of(s, I, 11), kZLimit);
  // Not vacuous: the same samples are far from a distribution turned by 60 degrees.
  const auto turned = [&](glm::dvec3 d) {
    const double c = std::cos(std::numbers::pi / 3), sn = std::sin(std::numbers::pi / 3);
    return s.intensity_cd({c * d.x - sn * d.y, sn * d.x + c * d.y, d.z});
  };
  EXPECT_GT(z_score_of(s, turned, 11), 20.0);
}

TEST(Sampler, TypesAAndBSampleTheirIntensity) {
  for (const char* name : {"ies/lm63_1995_type_b.ies", "ies/lm63_2002_type_a.ies"}) {
    const PhotometricSampler s(load_photometry(test::corpus_file(name)));
    EXPECT_LE(z_score_of(
                  s, [&](glm::dvec3 d) { return s.intensity_cd(d); }, 12),
              kZLimit)
        << name;
  }
}

TEST(Sampler, DirectionsAreUnitAndReproducible) {
  const PhotometricSampler s(coarse_c());
  for (std::uint64_t k = 0; k < 1000; ++k) {
    PathRng a(5, k), b(5, k);
    const glm::dvec3 d = s.sample_direction(a), e = s.sample_direction(b);
    EXPECT_NEAR(d.x * d.x + d.y * d.y + d.z * d.z, 1.0, 1e-12);
    EXPECT_EQ(d, e);
  }
}

TEST(Sampler, OriginsCoverTheOpening) {
  const auto rect = load_photometry(test::sample_file("wallwasher.ies"));  // 0.2 x 0.1 m
  const auto disc = load_photometry(test::sample_file("downlight.ies"));   // 0.15 m across
  const auto point = load_photometry(test::corpus_file("ies/lm63_1986_rotational.ies"));
  const PhotometricSampler r(rect), c(disc), p(point);
  const long n = 20000;
  double sx = 0, sxx = 0;
  long inner = 0;
  for (long k = 0; k < n; ++k) {
    PathRng rng(3, static_cast<std::uint64_t>(k));
    const glm::dvec3 o = r.sample_origin(rng);
    ASSERT_LE(std::abs(o.x), 0.1);
    ASSERT_LE(std::abs(o.y), 0.05);
    ASSERT_EQ(o.z, 0.0);
    sx += o.x, sxx += o.x * o.x;
    const glm::dvec3 q = c.sample_origin(rng);
    ASSERT_LE(std::hypot(q.x, q.y), 0.075 + 1e-15);
    inner += std::hypot(q.x, q.y) < 0.075 / std::sqrt(2.0);  // half the disc's area
    ASSERT_EQ(p.sample_origin(rng), glm::dvec3(0.0));
  }
  // Uniform on [-0.1, 0.1]: mean 0, variance 0.2^2 / 12; binomial half for the disc.
  const double var = 0.04 / 12;
  EXPECT_LE(std::abs(sx / n), kZLimit * std::sqrt(var / n));
  EXPECT_NEAR(sxx / n, var, kZLimit * var * std::sqrt(0.8 / n));  // var of x^2 is 0.8 var^2
  EXPECT_LE(std::abs(inner - 0.5 * n), kZLimit * std::sqrt(0.25 * n));
}

TEST(Sampler, FluxScaleForRelativePhotometry) {
  const PhotometricSampler s(load_photometry(test::sample_file("batwing_panel.ies")));
  EXPECT_DOUBLE_EQ(s.flux_scale(std::nullopt), 1.0);
  EXPECT_DOUBLE_EQ(s.flux_scale(7200.0), 2.0);  // rated 4 x 900 lm
  EXPECT_DOUBLE_EQ(s.emitted_flux_lm(7200.0), 2.0 * s.integrated_flux_lm());
  EXPECT_DOUBLE_EQ(s.flux_scale(0.0), 0.0);
  test::expect_input_error([&] { s.flux_scale(-1.0); }, 0, "flux_lm");
  test::expect_input_error([&] { s.flux_scale(std::nan("")); }, 0, "flux_lm");
}

TEST(Sampler, DarkDistributionIsAnInputError) {
  const auto dark = parse_ies(
      "IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 2 1 1 2 0 0 0\n1 1 10\n0 90\n0\n0 0\n", "dark.ies");
  test::expect_input_error([&] { PhotometricSampler s(dark); }, 0, "emits no light");
}

TEST(Sampler, ToWorldMapsTheLuminaireFrame) {
  const glm::dvec3 down{0, 0, -1}, x{1, 0, 0};
  EXPECT_EQ(to_world({0, 0, -1}, down, x), down);
  EXPECT_EQ(to_world({0, 1, 0}, down, x), glm::dvec3(0, 1, 0));
  // Aimed along +x (a wall-mounted luminaire) with C0 pointing up.
  const glm::dvec3 aim{1, 0, 0}, c0{0, 0, 1};
  EXPECT_EQ(to_world({0, 0, -1}, aim, c0), aim);
  EXPECT_EQ(to_world({1, 0, 0}, aim, c0), c0);
  EXPECT_EQ(to_world({0, 1, 0}, aim, c0), glm::dvec3(0, 1, 0));  // cross(c0, aim)
}

}  // namespace
}  // namespace lightsolver
