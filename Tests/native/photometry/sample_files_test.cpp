// The sample luminaires: lumens, sampled histograms, orientation, and IES == LDT.

#include "photometry_test_util.hpp"

namespace lightsolver {
namespace {

using test::kZLimit;
using test::sample_file;

constexpr long kFileSamples = 200000;
const char* const kStems[] = {"downlight", "wallwasher", "batwing_panel", "linear_tube"};

struct Pair {
  PhotometricData ies, ldt;
};
Pair load_pair(const std::string& stem) {
  return {load_photometry(sample_file(stem + ".ies")), load_photometry(sample_file(stem + ".ldt"))};
}

TEST(SampleFiles, IntegratedFluxMatchesTheFileLumensWithinHalfAPercent) {
  for (const char* stem : kStems) {
    for (const char* ext : {".ies", ".ldt"}) {
      const auto d = load_photometry(sample_file(std::string(stem) + ext));
      const PhotometricSampler s(d);
      EXPECT_NEAR(s.integrated_flux_lm() / d.rated_lumens_lm, 1.0, 0.005) << stem << ext;
    }
  }
}

TEST(SampleFiles, SampledHistogramsMatchTheIntensity) {
  std::uint64_t seed = 100;
  for (const char* stem : kStems) {
    for (const char* ext : {".ies", ".ldt"}) {
      const PhotometricSampler s(load_photometry(sample_file(std::string(stem) + ext)));
      const test::SphereBins bins;
      const auto observed = test::sample_histogram(s, bins, kFileSamples, ++seed);
      const auto p = test::expected_probabilities(
          bins, [&](glm::dvec3 d) { return s.intensity_cd(d); }, s.integrated_flux_lm());
      EXPECT_LE(test::max_z_score(observed, p, kFileSamples), kZLimit) << stem << ext;
    }
  }
}

// The IES and LDT file of one luminaire were written from the same table: the LDT rounds
// cd/klm to 0.1, the IES rounds candela to 0.1 (x its multiplier), hence the tolerance.
TEST(SampleFiles, IesAndLdtHoldTheSameIntensities) {
  for (const char* stem : kStems) {
    const Pair pair = load_pair(stem);
    const PhotometricSampler a(pair.ies), b(pair.ldt);
    const double tol =
        0.05 * pair.ldt.rated_lumens_lm / 1000.0 + 0.05 * pair.ies.candela_multiplier + 1e-9;
    for (std::uint64_t k = 0; k < 4000; ++k) {
      PathRng rng(21, k);  // directions spread over the sphere
      const double mu = 2 * rng.uniform_double() - 1,
                   phi = 2 * std::numbers::pi * rng.uniform_double();
      const double s = std::sqrt(1 - mu * mu);
      const glm::dvec3 d{s * std::cos(phi), s * std::sin(phi), mu};
      ASSERT_NEAR(a.intensity_cd(d), b.intensity_cd(d), tol) << stem << " direction " << k;
    }
    EXPECT_NEAR(a.integrated_flux_lm() / b.integrated_flux_lm(), 1.0, 1e-3) << stem;
  }
}

TEST(SampleFiles, IesAndLdtSampleTheSameStatistics) {
  for (const char* stem : kStems) {
    const Pair pair = load_pair(stem);
    const PhotometricSampler a(pair.ies), b(pair.ldt);
    // The LDT's samples against the IES's intensity...
    const test::SphereBins bins;
    const auto observed = test::sample_histogram(b, bins, kFileSamples, 31);
    const auto p = test::expected_probabilities(
        bins, [&](glm::dvec3 d) { return a.intensity_cd(d); }, a.integrated_flux_lm());
    EXPECT_LE(test::max_z_score(observed, p, kFileSamples), kZLimit) << stem;
    // ...and the mean emission directions of both agree within their standard errors.
    glm::dvec3 mean[2], sq[2];
    const PhotometricSampler* samplers[2] = {&a, &b};
    for (int f = 0; f < 2; ++f) {
      mean[f] = sq[f] = glm::dvec3(0.0);
      for (long k = 0; k < kFileSamples; ++k) {
        PathRng rng(41 + f, static_cast<std::uint64_t>(k));
        const glm::dvec3 d = samplers[f]->sample_direction(rng);
        mean[f] += d / double(kFileSamples);
        sq[f] += d * d / double(kFileSamples);
      }
    }
    for (int c = 0; c < 3; ++c) {
      const double se = std::sqrt((sq[0][c] - mean[0][c] * mean[0][c]) / kFileSamples +
                                  (sq[1][c] - mean[1][c] * mean[1][c]) / kFileSamples);
      EXPECT_LE(std::abs(mean[0][c] - mean[1][c]), kZLimit * se + 1e-12) << stem << " axis " << c;
    }
  }
}

TEST(SampleFiles, WallWasherSendsItsLightTowardC0) {
  for (const char* ext : {".ies", ".ldt"}) {
    const PhotometricSampler s(load_photometry(sample_file(std::string("wallwasher") + ext)));
    const double r35 = 35 * std::numbers::pi / 180;
    // The beam axis is 35 degrees from nadir in the C0 plane (+x): strong there, weak opposite.
    EXPECT_GT(s.intensity_cd({std::sin(r35), 0, -std::cos(r35)}),
              20 * s.intensity_cd({-std::sin(r35), 0, -std::cos(r35)}));
    long toward_c0 = 0;
    double mean_x = 0, mean_y = 0;
    for (long k = 0; k < kFileSamples; ++k) {
      PathRng rng(51, static_cast<std::uint64_t>(k));
      const glm::dvec3 d = s.sample_direction(rng);
      toward_c0 += d.x > 0;
      mean_x += d.x / kFileSamples;
      mean_y += d.y / kFileSamples;
      ASSERT_LE(d.z, 1e-12) << "no uplight in this file";
    }
    EXPECT_GT(toward_c0, 0.85 * kFileSamples) << ext;
    EXPECT_GT(mean_x, 0.4) << ext;
    EXPECT_LT(std::abs(mean_y), kZLimit * std::sqrt(0.5 / kFileSamples)) << ext;  // |y| <= 1
    // Not vacuous: the samples contradict the same file turned by 180 degrees about z.
    const test::SphereBins bins;
    const auto observed = test::sample_histogram(s, bins, kFileSamples, 52);
    const auto turned = test::expected_probabilities(
        bins,
        [&](glm::dvec3 d) {
          return s.intensity_cd({-d.x, -d.y, d.z});
        },
        s.integrated_flux_lm());
    EXPECT_GT(test::max_z_score(observed, turned, kFileSamples), 50.0);
  }
}

TEST(SampleFiles, LinearTubeEmitsUpAndDownSymmetricallyAcrossItsAxis) {
  const PhotometricSampler s(load_photometry(sample_file("linear_tube.ies")));
  long up = 0;
  for (long k = 0; k < 20000; ++k) {
    PathRng rng(61, static_cast<std::uint64_t>(k));
    up += s.sample_direction(rng).z > 0;
  }
  EXPECT_GT(up, 0.3 * 20000);  // batten dims, but does not block, the uplight
  EXPECT_NEAR(s.intensity_cd({1, 0, 0}), 0.0, 1e-9);  // nothing along the tube's axis
  EXPECT_NEAR(s.intensity_cd({0, 1, -1}), s.intensity_cd({0, -1, -1}), 1e-9);
}

}  // namespace
}  // namespace lightsolver
