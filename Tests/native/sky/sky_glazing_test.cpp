// Glazing on daylight openings (Shaders/shared/glazing.h, daylight/sky_glazing.hpp; the sky's
// portals and the sun's opening): the angular model against an independent Fresnel computation;
// a glazed roof opening, a glazed vertical window under the traditional overcast sky (without and
// with ground) and τv 0.01, each traced on every backend against a quadrature written here; a sky
// and a sun 10^5 times brighter than a small lamp, each group's part against its closed form;
// the scene keys and their errors.
#include "daylight/sky_glazing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "lightsolver/angles.hpp"
#include "sky_rooms.hpp"

namespace lightsolver::test {
namespace {

constexpr double kIor = 1.52;

// Fresnel reflectances of an air/glass interface in the trigonometric form (Born & Wolf), not
// the algebraic one glazing.h uses: Rs = sin²(θi − θt)/sin²(θi + θt), Rp = tan²/tan².
void fresnel_trig(double cos_i, double& rs, double& rp) {
  const double ti = std::acos(cos_i), tt = std::asin(std::sin(ti) / kIor);
  if (ti == 0.0) {
    rs = rp = std::pow((kIor - 1) / (kIor + 1), 2);
    return;
  }
  rs = std::pow(std::sin(ti - tt) / std::sin(ti + tt), 2);
  rp = std::pow(std::tan(ti - tt) / std::tan(ti + tt), 2);
}

// One clear pane per polarisation (scatter.h's thin_slab with τ = 1): T = (1−R)²/(1−R²),
// R' = R + (1−R)²R/(1−R²); two panes with inter-reflection: T² / (1 − R'²). Averaged over s, p.
double panes_by_composition(double cos_i, int panes) {
  double rs, rp;
  fresnel_trig(cos_i, rs, rp);
  double sum = 0.0;
  for (double r : {rs, rp}) {
    const double t = (1 - r) * (1 - r) / (1 - r * r), rr = r + (1 - r) * (1 - r) * r / (1 - r * r);
    sum += panes == 1 ? t : t * t / (1 - rr * rr);
  }
  return 0.5 * sum;
}

TEST(GlazingModel, MatchesFresnelPanesAndIsNormalisedToTauV) {
  for (int panes : {1, 2}) {
    const daylight::Glazing g{0.7, static_cast<unsigned>(panes), 1.0, 1.0};
    EXPECT_NEAR(g.tau(1.0), 0.7, 1e-15);
    const double t0 = panes_by_composition(1.0, panes);
    double last = 1.0;
    for (double c = 1.0; c > 0.01; c -= 0.01) {
      EXPECT_NEAR(g.tau(c), 0.7 * panes_by_composition(c, panes) / t0, 1e-12) << c;
      EXPECT_LE(g.tau(c), last + 1e-15);  // never more light at a steeper angle
      last = g.tau(c);
    }
    EXPECT_EQ(g.tau(0.0), 0.0);
    std::printf("[ glazing  ] %d pane(s): clear T(0) %.5f; tau(60 deg)/tau(0) %.4f\n", panes, t0,
                g.tau(0.5) / 0.7);
  }
  // The float text the GPU runs agrees with the double one to float precision.
  for (double c : {1.0, 0.8, 0.5, 0.2, 0.05}) {
    EXPECT_NEAR(shared::glazing_transmittance<float>(float(c), 0.9f, 2u),
                shared::glazing_transmittance<double>(c, 0.9, 2u), 2e-6);
  }
}

// ∫∫ f(x, y) over [x0, x1] x [y0, y1], composite Gauss-Legendre (8 panels x 8 points each way):
// the integrands below are smooth on each rectangle they are given.
double gauss_2d(const std::function<double(double, double)>& f, double x0, double x1, double y0,
                double y1) {
  static constexpr double x8[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                   -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                   0.7966664774136267,  0.9602898564975363};
  static constexpr double w8[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                   0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                   0.2223810344533745, 0.1012285362903763};
  constexpr int kPanels = 8;
  const double hx = (x1 - x0) / kPanels, hy = (y1 - y0) / kPanels;
  double sum = 0.0;
  for (int a = 0; a < kPanels; ++a) {
    for (int b = 0; b < kPanels; ++b) {
      for (int i = 0; i < 8; ++i) {
        for (int j = 0; j < 8; ++j) {
          const double x = x0 + hx * (a + 0.5 + 0.5 * x8[i]), y = y0 + hy * (b + 0.5 + 0.5 * x8[j]);
          sum += w8[i] * w8[j] * f(x, y);
        }
      }
    }
  }
  return sum * 0.25 * hx * hy;
}

// Illuminance at p on a plane of normal n_p from the sky seen through the glazed opening
// corner + s e1 + t e2 (n_out its normal toward the sky): f ∫ L(ω) τ(ω·n_out)(ω·n_out)(ω·n_p)/r²
// dA, ω = (q − p)/r. `split_z`: the opening is cut at p's height, where L jumps from ground to sky.
double through_opening(dvec3 p, dvec3 n_p, dvec3 corner, dvec3 e1, dvec3 e2, dvec3 n_out,
                       const daylight::Glazing& g, const std::function<double(dvec3)>& L,
                       bool split_z) {
  const double f = g.frame_factor * g.maintenance_factor;
  auto integrand = [&](double s, double t) {
    const dvec3 q = corner + s * e1 + t * e2, v = q - p;
    const double r = glm::length(v);
    const dvec3 w = v / r;
    const double co = glm::dot(w, n_out), cp = glm::dot(w, n_p);
    if (co <= 0 || cp <= 0) return 0.0;
    return L(w) * g.tau(co) * co * cp / (r * r);
  };
  const double area = glm::length(glm::cross(e1, e2));
  // e1 along z when split_z (the vertical window: edge1 = (0, 0, h)).
  double s_cut = split_z ? (p.z - corner.z) / e1.z : -1.0;
  double sum;
  if (s_cut > 0.0 && s_cut < 1.0) {
    sum = gauss_2d(integrand, 0, s_cut, 0, 1) + gauss_2d(integrand, s_cut, 1, 0, 1);
  } else {
    sum = gauss_2d(integrand, 0, 1, 0, 1);
  }
  return f * area * sum;
}

// Mean of `e(p)` over the probe corner + a u + b v, midpoint rule n x n (E is smooth in p).
double probe_mean(dvec3 corner, dvec3 u, dvec3 v, int n, const std::function<double(dvec3)>& e) {
  double sum = 0.0;
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) sum += e(corner + (a + 0.5) / n * u + (b + 0.5) / n * v);
  }
  return sum / (n * n);
}

Luminaire glazed_portal_sky(Luminaire l, dvec3 corner, dvec3 e1, dvec3 e2,
                            const daylight::Glazing& g) {
  l.sky.portals.push_back(
      {corner, e1, e2,
       GlazingDefinition{g.transmittance, int(g.panes), g.frame_factor, g.maintenance_factor}});
  return l;
}

class GlazingTraced : public ::testing::TestWithParam<std::string> {
 protected:
  Results run(Scene s, std::uint64_t photons, std::uint64_t seed = 21) {
    return run_on_backend(GetParam(), std::move(s), photons, seed);
  }
};

// The roof opening of sky_luminaire_test.cpp, now double glazed (τv 0.7, frame 0.8, dirt 0.9):
// E = f L ∫ τ(θ) cos²θ / r² dA at each floor probe, and the flux f L A 2π ∫ τ(c) c dc.
TEST_P(GlazingTraced, GlazedRoofOpeningUnderTheUniformSky) {
  const daylight::Glazing g{0.7, 2, 0.8, 0.9};
  Scene s;
  add_material(s, "black", Material::Type::Diffuse, 0.0);
  s.meshes.push_back(room_with_hole(0, {0, 0, 0}, {4, 4, 3}, true, {0.375, 0.625, 0.375, 0.625}));
  s.luminaires.push_back(
      glazed_portal_sky(sky("uniform", 1000.0), {1.5, 1.5, 3}, {0, 1, 0}, {1, 0, 0}, g));
  const std::vector<dvec3> probes = {{1.8, 1.8, 0}, {0.4, 0.9, 0}, {3.0, 2.5, 0}};
  for (std::size_t i = 0; i < probes.size(); ++i) {
    s.targets.push_back(grid("p" + std::to_string(i), probes[i], {0.4, 0, 0}, {0, 0.4, 0}, 1, 1));
  }
  const Results r = run(s, 8'000'000);
  double flux = 0.0;  // midpoint rule in c = cos θ, 20000 steps: 10^-9
  for (int k = 0; k < 20000; ++k) {
    const double c = (k + 0.5) / 20000;
    flux += g.tau(c) * c / 20000;
  }
  flux *= 0.72 * 1000.0 * 2 * kPi;
  EXPECT_NEAR(r.luminaires[0].emitted_flux_lm, flux, 1e-5 * flux);
  auto uniform = [](dvec3) { return 1000.0; };
  for (std::size_t i = 0; i < probes.size(); ++i) {
    const double exact = probe_mean(probes[i], {0.4, 0, 0}, {0, 0.4, 0}, 12, [&](dvec3 p) {
      return through_opening(p, {0, 0, 1}, {1.5, 1.5, 3}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}, g,
                             uniform, false);
    });
    report(r.targets[i].estimate, exact, "glazed roof opening, probe " + std::to_string(i));
    expect_in_ci(r.targets[i].estimate, exact, 0.06, "probe " + std::to_string(i));
  }
}

// τv 0.01 (single pane): finite, inside its interval, and as narrow as clear glass's (the
// transmitted light is what is drawn: no photon is spent on light the glass absorbs).
TEST_P(GlazingTraced, TransmittanceOfOnePercent) {
  const daylight::Glazing g{0.01, 1, 1.0, 1.0};
  Scene s;
  add_material(s, "black", Material::Type::Diffuse, 0.0);
  s.meshes.push_back(room_with_hole(0, {0, 0, 0}, {4, 4, 3}, true, {0.375, 0.625, 0.375, 0.625}));
  s.luminaires.push_back(
      glazed_portal_sky(sky("uniform", 1000.0), {1.5, 1.5, 3}, {0, 1, 0}, {1, 0, 0}, g));
  s.targets.push_back(grid("p", {1.8, 1.8, 0}, {0.4, 0, 0}, {0, 0.4, 0}, 1, 1));
  const Results r = run(s, 4'000'000);
  const double exact = probe_mean({1.8, 1.8, 0}, {0.4, 0, 0}, {0, 0.4, 0}, 12, [&](dvec3 p) {
    return through_opening(
        p, {0, 0, 1}, {1.5, 1.5, 3}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}, g,
        [](dvec3) { return 1000.0; }, false);
  });
  EXPECT_TRUE(std::isfinite(r.targets[0].estimate.mean));
  report(r.targets[0].estimate, exact, "tau_v 0.01");
  expect_in_ci(r.targets[0].estimate, exact, 0.05, "τv 0.01");
}

// A 1.5 x 1.2 m double-glazed window (τv 0.75, frame 0.85) in the wall y = 0 of a black
// 3 x 3 x 2.5 m room under the traditional overcast sky (L_z 4000): a probe on the floor and a
// vertical probe facing the window, first with a black ground, then with ρ_g 0.3 (the ground's
// uniform luminance ρ_g · 7 L_z / 9, the overcast sky's horizontal illuminance over π), seen by
// the vertical probe through the window's lower part.
TEST_P(GlazingTraced, VerticalWindowUnderTheOvercastSky) {
  const daylight::Glazing g{0.75, 2, 0.85, 1.0};
  const double lz = 4000.0;
  const dvec3 corner(0.75, 0, 0.8), e1(0, 0, 1.2), e2(1.5, 0, 0), out(0, -1, 0);
  for (double rho : {0.0, 0.3}) {
    Scene s;
    add_material(s, "black", Material::Type::Diffuse, 0.0);
    s.meshes.push_back(room_with_hole(0, {0, 0, 0}, {3, 3, 2.5}, false, {0.32, 0.8, 0.25, 0.75}));
    s.luminaires.push_back(glazed_portal_sky(sky("cie_overcast", lz, rho), corner, e1, e2, g));
    s.targets.push_back(grid("floor", {1.3, 0.6, 0}, {0.4, 0, 0}, {0, 0.4, 0}, 1, 1));
    s.targets.push_back(grid("facing", {1.3, 1.0, 1.0}, {0.4, 0, 0}, {0, 0, 0.4}, 1, 1));
    const Results r = run(s, 6'000'000, 23);
    const double lg = rho * 7.0 * lz / 9.0;
    auto L = [&](dvec3 w) { return w.z > 0 ? lz * (1 + 2 * w.z) / 3 : lg; };
    const double floor = probe_mean({1.3, 0.6, 0}, {0.4, 0, 0}, {0, 0.4, 0}, 12, [&](dvec3 p) {
      return through_opening(p, {0, 0, 1}, corner, e1, e2, out, g, L, false);
    });
    const double facing = probe_mean({1.3, 1.0, 1.0}, {0.4, 0, 0}, {0, 0, 0.4}, 12, [&](dvec3 p) {
      return through_opening(p, {0, -1, 0}, corner, e1, e2, out, g, L, true);
    });
    const std::string tag = " (ground " + std::to_string(rho).substr(0, 3) + ")";
    report(r.targets[0].estimate, floor, "overcast window, floor" + tag);
    report(r.targets[1].estimate, facing, "overcast window, facing" + tag);
    expect_in_ci(r.targets[0].estimate, floor, 0.06, "floor" + tag);
    expect_in_ci(r.targets[1].estimate, facing, 0.04, "facing" + tag);
  }
}

// A glazed roof opening passing a uniform sky (L 3000) and a sun (10^5 lx, 20° from the zenith)
// through the same glass, beside a 0.4 lm point lamp: 10^5 times less light, each in its own group.
// Each group's part: the lamp's I Ω / A, the sun's E cos θ τ(θ) f where its beam lands, the
// sky's quadrature.
TEST_P(GlazingTraced, SunAndSkyBesideALampTenToTheFiveTimesDimmerEachResolved) {
  const daylight::Glazing g{0.6, 2, 0.9, 0.95};
  Scene s;
  add_material(s, "black", Material::Type::Diffuse, 0.0);
  s.meshes.push_back(room_with_hole(0, {0, 0, 0}, {4, 4, 3}, true, {0.375, 0.625, 0.375, 0.625}));
  s.luminaires.push_back(
      named(glazed_portal_sky(sky("uniform", 3000.0), {1.5, 1.5, 3}, {0, 1, 0}, {1, 0, 0}, g),
            "sky", "daylight"));
  Luminaire sun;
  sun.type = Luminaire::Type::Sun;
  sun.illuminance_lx = 1e5;
  const double th = 20.0 * kPi / 180.0;
  sun.direction = dvec3(std::sin(th), 0, -std::cos(th));
  sun.corner = {1.5, 1.5, 3};
  sun.edge1 = {0, 1, 0};
  sun.edge2 = {1, 0, 0};
  sun.glazing = GlazingDefinition{0.6, 2, 0.9, 0.95};
  s.luminaires.push_back(named(sun, "sun", "sun"));
  s.luminaires.push_back(named(point_light({0.8, 0.8, 1.5}, 0.4), "lamp", "lamp"));
  s.targets.push_back(grid("under lamp", {0.6, 0.6, 1.0}, {0.4, 0, 0}, {0, 0.4, 0}, 1, 1));
  s.targets.push_back(grid("in the beam", {2.9, 1.8, 0}, {0.4, 0, 0}, {0, 0.4, 0}, 1, 1));
  validate(s);
  SolveOptions o;
  o.photons = 9'000'000;
  o.seed = 25;
  o.confidence = kCheckConfidence;
  o.backend = GetParam();
  o.contributions = true;
  const Results r = solve(s, o);
  const double sun_flux = 1e5 * std::cos(th) * g.tau(std::cos(th)) * 0.9 * 0.95;
  EXPECT_NEAR(r.luminaires[1].emitted_flux_lm, sun_flux, 1e-9 * sun_flux);
  EXPECT_GT(r.luminaires[0].emitted_flux_lm + sun_flux, 1e5 * 0.4);
  auto part = [&](std::size_t target, const std::string& group) {
    for (const Contribution& c : r.targets[target].contributions) {
      if (c.group == group) return c.estimate;
    }
    ADD_FAILURE() << "no contribution of " << group;
    return Estimate{};
  };
  const double lamp =
      point_source_patch_lux({0.8, 0.8, 1.5}, 0.4, {0.6, 0.6, 1.0}, {0.4, 0, 0}, {0, 0.4, 0});
  report(part(0, "lamp"), lamp, "0.4 lm lamp beside sun and sky");
  expect_in_ci(part(0, "lamp"), lamp, 0.05, "lamp");
  const double beam = sun_flux;  // E cos θ τ f on the floor, the probe wholly in the beam
  report(part(1, "sun"), beam, "sun through the glazing");
  expect_in_ci(part(1, "sun"), beam, 0.03, "sun");
  const double sky_exact = probe_mean({2.9, 1.8, 0}, {0.4, 0, 0}, {0, 0.4, 0}, 12, [&](dvec3 p) {
    return through_opening(
        p, {0, 0, 1}, {1.5, 1.5, 3}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}, g,
        [](dvec3) { return 3000.0; }, false);
  });
  report(part(1, "daylight"), sky_exact, "sky beside the sun and the lamp");
  expect_in_ci(part(1, "daylight"), sky_exact, 0.1, "sky");
}

INSTANTIATE_TEST_SUITE_P(Backends, GlazingTraced, ::testing::ValuesIn(backends()));

std::string scene_with(const std::string& luminaire) {
  return R"({"format": "lightsolver.scene/1",
  "materials": {"white": {"type": "diffuse", "reflectance": 0.7}},
  "meshes": [{"name": "floor", "material": "white",
              "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "triangles": [[0,1,2],[0,2,3]]}],
  "luminaires": [)" +
         luminaire + R"(],
  "targets": [{"name": "floor", "type": "surface", "mesh": "floor"}]})";
}

std::string sky_with_glazing(const std::string& glazing) {
  return R"({"name": "sky", "type": "sky", "model": "uniform", "zenith_luminance_cd_m2": 1000,
    "portals": [{"corner": [0,0,3], "edge1": [0,1,0], "edge2": [1,0,0], "glazing": )" +
         glazing + "}]}";
}

std::string sun_with_glazing(const std::string& glazing) {
  return R"({"name": "sun", "type": "sun", "illuminance_lx": 100000, "direction": [0, 0, -1],
    "corner": [0,0,3], "edge1": [0,1,0], "edge2": [1,0,0], "glazing": )" +
         glazing + "}";
}

std::string glazing_error_of(const std::string& text) {
  try {
    Scene s = scene_from_json(text, "scene.json", ".");
    validate(s);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(GlazingScene, ReadsTheKeysOnPortalsAndTheSun) {
  Scene s = scene_from_json(
      scene_with(sky_with_glazing(R"({"transmittance": 0.7, "panes": 2, "frame_factor": 0.8,
                 "maintenance_factor": 0.9})") +
                 ", " + sun_with_glazing(R"({"transmittance": 0.7, "panes": 2,
                 "frame_factor": 0.8, "maintenance_factor": 0.9})")),
      "scene.json", ".");
  validate(s);
  const daylight::Glazing g{0.7, 2, 0.8, 0.9};
  double flux = 0.0;
  for (int k = 0; k < 20000; ++k) flux += g.tau((k + 0.5) / 20000) * (k + 0.5) / 20000 / 20000;
  EXPECT_NEAR(s.luminaires[0].flux_lm, 0.72 * 1000 * 2 * kPi * flux,
              1e-5 * s.luminaires[0].flux_lm);
  // The sun straight down through a horizontal opening: normal incidence, τv f.
  EXPECT_NEAR(s.luminaires[1].flux_lm, 1e5 * 0.7 * 0.72, 1e-9 * 1e5);
}

TEST(GlazingScene, BadValuesAreNamed) {
  const std::pair<std::string, std::string> cases[] = {
      {R"({"transmittance": 1.2})", "portals[0].glazing.transmittance: must be more than 0"},
      {R"({"transmittance": -0.1})", "portals[0].glazing.transmittance"},
      {R"({"transmittance": 0})", "portals[0].glazing.transmittance"},
      {R"({"transmittance": 0.7, "frame_factor": 0})", "portals[0].glazing.frame_factor"},
      {R"({"transmittance": 0.7, "maintenance_factor": 1.5})",
       "portals[0].glazing.maintenance_factor"},
      {R"({"transmittance": 0.7, "panes": 3})", "portals[0].glazing.panes: must be 1"},
      {R"({"transmittance": 0.7, "tint": 3})", "tint"},
      {R"({"panes": 2})", "transmittance"}};
  for (const auto& [glazing, expected] : cases) {
    const std::string e = glazing_error_of(scene_with(sky_with_glazing(glazing)));
    EXPECT_NE(e.find(expected), std::string::npos) << glazing << " -> " << e;
    EXPECT_NE(e.find("luminaires[0]"), std::string::npos) << e;
  }
  const std::string e = glazing_error_of(scene_with(sun_with_glazing(R"({"transmittance": 2})")));
  EXPECT_NE(e.find("luminaires[0].glazing.transmittance"), std::string::npos) << e;
}

}  // namespace
}  // namespace lightsolver::test
