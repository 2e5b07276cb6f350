// The sun's disc straddling its opening's plane (docs/daylight.md, "The sun as a luminaire"):
// only the part in front of the opening passes, weighted by the opening's area across each
// direction. Its share of E (sun_disc_share) against the half-disc closed form, an independent
// quadrature and its continuity with n·d; the emission's directions (in front, in the disc, the
// |n·ω| weighting's first moment); the float sampler's acceptance bound; and traced on both
// backends, a probe just inside a grazing window reading E × share within its 5σ interval.
#include <gtest/gtest.h>

#include <cmath>

#include "lightsolver/angles.hpp"
#include "lightsolver/rng.hpp"
#include "model/prepared_scene.hpp"
#include "scene_builders.hpp"
#include "types/luminaire_rows.hpp"

namespace lightsolver::test {
namespace {

constexpr double kStraddleLux = 100'000.0;
const double kStraddleAlpha = 0.265 * kDeg;  // the disc's angular radius
const double kSinA = std::sin(kStraddleAlpha);

// ∫_0^{2π} max(0, c − s cos φ)^k dφ for k = 1, 2 (s ≥ 0), elementary.
double ring(double c, double s, int k) {
  if (c >= s) return k == 1 ? 2 * kPi * c : 2 * kPi * (c * c + 0.5 * s * s);
  if (c <= -s) return 0.0;
  const double f = std::acos(c / s), rest = kPi - f;
  if (k == 1) return 2 * (c * rest + s * std::sin(f));
  return 2 *
         (c * c * rest + 2 * c * s * std::sin(f) + s * s * (0.5 * rest - 0.25 * std::sin(2 * f)));
}

// ∫_disc max(0, n·ω)^k dω by the midpoint rule over the polar angle β from the axis (n·ω =
// cos β cos θ − sin β sin θ cos φ, the azimuth φ in closed form): an integrand with two kinks, so
// 20 000 steps hold it to ~10⁻⁹.
double cap_moment(double t, int k) {
  const double st = std::sqrt(1 - t * t);
  const int m = 20'000;
  const double h = kStraddleAlpha / m;
  double sum = 0.0;
  for (int i = 0; i < m; ++i) {
    const double b = (i + 0.5) * h;
    sum += std::sin(b) * ring(std::cos(b) * t, std::sin(b) * st, k);
  }
  return sum * h;
}

TEST(SunDiscShare, AxisInThePlaneIsTheHalfDisc) {
  const double half = (kStraddleAlpha - kSinA * std::cos(kStraddleAlpha)) / (kPi * kSinA * kSinA);
  EXPECT_NEAR(detail::sun_disc_share(0.0), half, 1e-9 * half);
  EXPECT_NEAR(half, 2 * kStraddleAlpha / (3 * kPi), 1e-4 * half);  // ≈ 0.001: (2/3)α³ / (π α²)
}

TEST(SunDiscShare, MatchesQuadratureAndIsContinuous) {
  const double norm = kPi * kSinA * kSinA;
  for (int i = -20; i <= 24; ++i) {  // t from −sin α to 1.2 sin α
    const double t = kSinA * i / 20.0;
    const double q = std::max(0.0, cap_moment(t, 1)) / norm;
    EXPECT_NEAR(detail::sun_disc_share(t), q, 1e-8 * kSinA) << "n·d = " << t;
  }
  // Across the edges of the straddling range: the cut cap meets n·d and 0.
  for (double eps : {1e-6, 1e-9}) {
    EXPECT_NEAR(detail::sun_disc_share(kSinA * (1 - eps)), kSinA * (1 - eps), 1e-9 * kSinA);
    EXPECT_NEAR(detail::sun_disc_share(-kSinA * (1 - eps)), 0.0, 1e-9 * kSinA);
  }
  EXPECT_EQ(detail::sun_disc_share(kSinA * 1.0001), kSinA * 1.0001);
  EXPECT_EQ(detail::sun_disc_share(-kSinA * 1.0001), 0.0);
}

// The float sampler's box (Shaders/shared/luminaires.h, emit_sun_straddling) holds the cut cap
// with room to spare: its projected measure sin²(e_c + α) ψ_h over the cap's, ≥ 0.5 across the
// straddling range, so 64 tries all fail with probability < 2⁻⁶⁴.
TEST(SunDiscShare, TheSamplersBoxAcceptsAtLeastHalf) {
  const double ca = std::cos(kStraddleAlpha);
  double worst = 1.0;
  for (int i = -999; i < 1000; ++i) {
    const double t = kSinA * i / 1000.0, cc = std::sqrt(1 - t * t);
    const double q_hi = t * ca + cc * kSinA;
    double psi;
    if (t >= 0) {
      psi = std::asin(kSinA / cc);
    } else {
      const double cos_psi = ca / cc;
      psi = std::acos(cos_psi);
    }
    const double box = q_hi * q_hi * psi;  // ∫ q dq over [0, q_hi] × 2ψ_h
    worst = std::min(worst, cap_moment(t, 1) / box);
  }
  std::printf("[ sun      ] worst acceptance over the straddling range: %.3f\n", worst);
  EXPECT_GT(worst, 0.5);
}

// The emission through a portal 0.1° behind the beam (its disc mostly behind the plane): every
// direction in front and in the disc, the mean of n·ω that of the density ∝ n·ω,
// ∫(n·ω)² / ∫ n·ω (a uniform draw over the front part would be 20σ off).
TEST(SunStraddlingEmission, InFrontInTheDiscWeightedByTheOpening) {
  Scene s;
  add_material(s, "black", Material::Type::Diffuse, 0.0);
  s.meshes.push_back(quad_mesh("ground", 0, {-50, -50, -5}, {100, 0, 0}, {0, 100, 0}));
  const double e = -0.1 * kDeg;                  // the centre's elevation above the portal's plane
  const dvec3 d(-std::sin(e), 0, -std::cos(e));  // n = −x: n·d = sin e
  Luminaire l;
  l.name = "sun";
  l.type = Luminaire::Type::Sun;
  l.direction = d;
  l.illuminance_lx = kStraddleLux;
  l.sky.portals.push_back({{5, -1, 0}, {0, 0, 2}, {0, 2, 0}, std::nullopt});  // n = −x
  s.luminaires.push_back(l);
  s.targets.push_back(surface("ground", 0));
  validate(s);
  const double t = std::sin(e);
  EXPECT_NEAR(s.luminaires[0].flux_lm, kStraddleLux * 4 * detail::sun_disc_share(t),
              1e-9 * kStraddleLux);
  const detail::PreparedScene p = detail::prepare(s);
  const detail::PreparedLuminaire& pl = p.luminaires[0];
  const dvec3 n(-1, 0, 0);
  const int count = 1'000'000;
  double min_front = 1.0, max_angle = 0.0, sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < count; ++i) {
    PathRng rng(7, i);
    const dvec3 w = glm::normalize(dvec3(pl.emit(pl, rng).direction));
    const double f = glm::dot(w, n);
    min_front = std::min(min_front, f);
    max_angle = std::max(max_angle, std::acos(std::min(1.0, glm::dot(w, d))));
    sum += f;
    sum2 += f * f;
  }
  EXPECT_GE(min_front, 0.0);
  EXPECT_LE(max_angle, kStraddleAlpha * 1.001);
  const double mean = sum / count, sigma = std::sqrt((sum2 / count - mean * mean) / count);
  const double expected = cap_moment(t, 2) / cap_moment(t, 1);
  std::printf("[ sun      ] mean n·ω %.6g (exact %.6g, σ %.2g)\n", mean, expected, sigma);
  EXPECT_NEAR(mean, expected, 4 * sigma);
}

// A long window strip in the plane x = 5 (n = −x into the room), its length along the beam's
// way back p = (0, ½, √¾): a probe 1 mm inside, facing the window, 1 m from its lower end, sees
// through it every direction of the disc's front part whose way back crosses the plane within
// 48 m, all but those with n·ω < 2·10⁻⁵ (a share < 10⁻⁴ of the light): it reads E × share.
Scene grazing_window(const dvec3& d, bool portal) {
  Scene s;
  add_material(s, "black", Material::Type::Diffuse, 0.0);
  s.meshes.push_back(quad_mesh("ground", 0, {-50, -50, -5}, {100, 0, 0}, {0, 100, 0}));
  const dvec3 p(0, 0.5, std::sqrt(0.75)), q(0, std::sqrt(0.75), -0.5);  // p × q = −x
  const dvec3 corner = dvec3(5, 0, 0) - 1.1 * q, e1 = 50.0 * p, e2 = 2.2 * q;
  Luminaire l;
  l.name = "sun";
  l.type = Luminaire::Type::Sun;
  l.direction = d;
  l.illuminance_lx = kStraddleLux;
  if (portal) {
    l.sky.portals.push_back({corner, e1, e2, std::nullopt});
  } else {
    l.corner = corner;
    l.edge1 = e1;
    l.edge2 = e2;
  }
  s.luminaires.push_back(l);
  // Lateral room: the disc spreads ±0.0047 rad over ≤ 50 m, 0.24 m; the probe is 1 m wide of 2.2.
  s.targets.push_back(grid("probe", dvec3(4.999, 0, 0) + 1.0 * p - 0.5 * q, q, p, 1, 1));
  return s;
}

class SunStraddling : public ::testing::TestWithParam<std::string> {};

// The beam's axis in the window's plane: half the disc passes, E (α − sin α cos α)/(π sin²α).
TEST_P(SunStraddling, AxisInTheWindowsPlane) {
  const dvec3 d(0, -0.5, -std::sqrt(0.75));
  const Results r = run_on_backend(GetParam(), grazing_window(d, false), 2'000'000, 11);
  const double exact = kStraddleLux * detail::sun_disc_share(0.0);
  std::printf("[ sun      ] axis in the plane: %.6g [%.6g, %.6g] exact %.6g\n",
              r.targets[0].estimate.mean, r.targets[0].estimate.ci_low,
              r.targets[0].estimate.ci_high, exact);
  expect_in_ci(r.targets[0].estimate, exact, 0.05, "axis in the window's plane");
}

// Through a portal with the disc's centre 0.1° behind its plane: the front sliver alone.
TEST_P(SunStraddling, CentreATenthOfADegreeBehindAPortal) {
  const double e = -0.1 * kDeg;
  const dvec3 d = std::cos(e) * dvec3(0, -0.5, -std::sqrt(0.75)) + std::sin(e) * dvec3(-1, 0, 0);
  const Scene s = grazing_window(d, true);
  const Results r = run_on_backend(GetParam(), s, 2'000'000, 11);
  const double exact = kStraddleLux * detail::sun_disc_share(std::sin(e));
  std::printf("[ sun      ] 0.1° behind: %.6g [%.6g, %.6g] exact %.6g\n",
              r.targets[0].estimate.mean, r.targets[0].estimate.ci_low,
              r.targets[0].estimate.ci_high, exact);
  expect_in_ci(r.targets[0].estimate, exact, 0.08, "centre 0.1° behind the portal");
}

INSTANTIATE_TEST_SUITE_P(Backends, SunStraddling, ::testing::ValuesIn(backends()));

// The disc wholly behind a portal (its centre 0.3° behind, the disc 0.265°): no light, no error.
TEST(SunStraddlingScene, WhollyBehindIsDark) {
  const double e = -0.3 * kDeg;
  const dvec3 d = std::cos(e) * dvec3(0, -0.5, -std::sqrt(0.75)) + std::sin(e) * dvec3(-1, 0, 0);
  Scene s = grazing_window(d, true);
  validate(s);
  EXPECT_EQ(s.luminaires[0].flux_lm, 0.0);
}

}  // namespace
}  // namespace lightsolver::test
