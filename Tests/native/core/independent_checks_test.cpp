// Independent checks (issue 10, item 7): each compares one stage of the tracer with a reference
// computed here from first principles, so that a plausible mistake in that stage fails. The
// mutations each one catches are listed in docs/testing.md.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

class IndependentChecks : public ::testing::TestWithParam<std::string> {
 protected:
  Results run(Scene s, std::uint64_t photons, std::uint64_t seed = 3) {
    return run_on_backend(GetParam(), std::move(s), photons, seed);
  }
};

// Mean of f over the parallelogram corner + s e1 + t e2 (midpoint rule, n x n points).
double patch_mean(const std::function<double(dvec3)>& f, dvec3 c, dvec3 e1, dvec3 e2, int n = 60) {
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) sum += f(c + ((i + 0.5) / n) * e1 + ((j + 0.5) / n) * e2);
  }
  return sum / (n * n);
}

// Luminaire: a vertical beam of `lux` filling exactly the rectangle [x0,x1] x [y0,y1] at z = 0.
Luminaire vertical_beam(double x0, double x1, double y0, double y1, double lux) {
  Luminaire sun;
  sun.name = "beam";
  sun.type = Luminaire::Type::Directional;
  sun.direction = {0, 0, -1};
  sun.corner = {x0, y0, 3};
  sun.edge1 = {x1 - x0, 0, 0};
  sun.edge2 = {0, y1 - y0, 0};
  sun.illuminance_lx = lux;
  return sun;
}

// CIE 171:2006 test case 5.6 in spirit: a Lambertian patch of reflectance rho, uniformly lit
// with E_h, is a uniform diffuse emitter of exitance rho E_h; a probe elsewhere gets
// E = rho E_h F, F the configuration factor from the probe to the patch. Everything else is
// black (there is nothing else), so only the first diffuse bounce is seen. Probes straight above
// and far to the side weigh the emitted distribution at small and grazing angles: sampling the
// hemisphere uniformly instead of by cosine halves the first and inflates the second.
TEST_P(IndependentChecks, FirstDiffuseBounceMatchesFormFactors) {
  constexpr double rho = 0.6, e_h = 1000.0;
  Scene s;
  add_material(s, "grey", Material::Type::Diffuse, rho);
  s.meshes.push_back(quad_mesh("patch", 0, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}));  // front +z
  s.luminaires.push_back(vertical_beam(0, 1, 0, 1, e_h));
  // Parallel probe 1 m above the patch, facing down (front e1 x e2 = -z).
  const dvec3 pc(0.4, 0.4, 1.0), pe1(0, 0.2, 0), pe2(0.2, 0, 0);
  s.targets.push_back(grid("above", pc, pe1, pe2, 1, 1));
  // Vertical probe 0.5 m beside the patch, low down, facing it (front -x): grazing light.
  const dvec3 vc(1.5, 0.3, 0.02), ve1(0, 0, 0.2), ve2(0, 0.4, 0);
  s.targets.push_back(grid("beside", vc, ve1, ve2, 1, 1));
  // Fewer photons on lavapipe, where each costs more (with next-event estimation the probes'
  // light is all connected reflected light, N/4 paths, narrower than photons alone at any N).
  const Results r = run(s, GetParam().rfind("vulkan", 0) == 0 ? 1'000'000 : 4'000'000);
  const double m = rho * e_h;
  auto above = [&](dvec3 p) { return m * parallel_rect_factor(-p.x, 1 - p.x, -p.y, 1 - p.y, p.z); };
  expect_in_ci(r.targets[0].estimate, patch_mean(above, pc, pe1, pe2), 0.08, "probe above");
  // Point p on the plane x = p.x facing -x, at height p.z over the patch's plane. Rectangles in
  // z = 0 with an edge on the planes' intersection (x = p.x) and starting at the point's foot
  // are corner cases of lighting-facts.md; [0, 1] x [0, 1] is [0, p.x] minus [1, p.x] in x, and
  // the foot's two sides in y (signed lengths).
  auto beside = [&](dvec3 p) {
    auto corner = [&](double along_y, double depth) {  // rectangle [p.x - depth, p.x] x [.., ..]
      if (along_y == 0.0 || depth <= 0.0) return 0.0;
      return std::copysign(corner_factor_perpendicular(std::abs(along_y), depth, p.z), along_y);
    };
    auto strip = [&](double depth) { return corner(1 - p.y, depth) - corner(-p.y, depth); };
    return m * (strip(p.x) - strip(p.x - 1));  // x in [0, p.x] minus x in [1, p.x]
  };
  expect_in_ci(r.targets[1].estimate, patch_mean(beside, vc, ve1, ve2), 0.12, "probe beside");
}

// Closed form per cell on a non-square grid (7 x 3, lamp off-centre): each cell's exact mean
// illuminance (inverse square and cosine, integrated over the cell) inside its interval. A cell
// stride of nv instead of nu would put counts in the wrong cells (and several into one).
TEST_P(IndependentChecks, NonSquareGridCellsMatchTheClosedForm) {
  Scene s;
  const dvec3 lamp(0.9, 0.35, 1.2);
  s.luminaires.push_back(point_light(lamp, 3000.0));
  const dvec3 c(-0.4, -0.3, 0), e1(2.8, 0, 0), e2(0, 1.5, 0);
  constexpr unsigned nu = 7, nv = 3;
  s.targets.push_back(grid("floor", c, e1, e2, nu, nv));
  const Results r = run(s, GetParam() == "vulkan" ? 1'000'000 : 2'000'000);
  const TargetResult& t = r.targets[0];
  ASSERT_EQ(t.cells.size(), nu * nv);
  for (unsigned iv = 0; iv < nv; ++iv) {
    for (unsigned iu = 0; iu < nu; ++iu) {
      const dvec3 cc = c + (double(iu) / nu) * e1 + (double(iv) / nv) * e2;
      const double exact =
          point_source_patch_lux(lamp, 3000.0, cc, e1 / double(nu), e2 / double(nv));
      expect_in_ci(t.cells[iv * nu + iu], exact, 0.15,
                   "cell iu " + std::to_string(iu) + " iv " + std::to_string(iv));
    }
  }
}

// The distribution the glossy sampler is meant to produce, written independently of
// scatter.hpp: microfacet normals h drawn with density D(h) cos(theta_h) (GGX, alpha =
// roughness^2, Walter et al. 2007 eq. 33), the photon mirrored about h; h facing away from the
// photon or an outgoing direction below the surface absorbs it (no renormalisation). The density
// of the outgoing direction o for incoming direction i (towards the surface's outside) is then
// D(h) cos(theta_h) / (4 |o . h|), h = normalize(i + o) (Walter eq. 14), times the specular
// albedo.
double ggx_d(double cos_h, double alpha) {
  const double a2 = alpha * alpha, c2 = cos_h * cos_h;
  const double denom = c2 * (a2 - 1.0) + 1.0;
  return a2 / (std::numbers::pi * denom * denom);
}

double glossy_pdf(dvec3 i, dvec3 o, double alpha) {
  if (o.z <= 0.0) return 0.0;
  const dvec3 h = glm::normalize(i + o);
  return ggx_d(h.z, alpha) * h.z / (4.0 * glm::dot(o, h));
}

// A narrow directional beam onto a glossy patch (reflectance 0, specular 1, roughness 0.5), 35
// degrees off the normal; probes 2 m away in the specular direction, 15 and 40 degrees off it
// in the plane of incidence and one out of it. Reference: the density above integrated
// over the beam's footprint and each probe (midpoint rule, 8 x 8 x 8 x 8 points). Using alpha
// where alpha^2 belongs (or roughness for alpha) changes the lobe's peak by a factor of 4.
TEST_P(IndependentChecks, RoughGlossyLobeMatchesNumericalIntegration) {
  constexpr double alpha = 0.25, lux = 2000.0, dist = 2.0;
  const double th = 35.0 * std::numbers::pi / 180.0;
  const dvec3 beam(std::sin(th), 0, -std::cos(th)), in = -beam;
  Scene s;
  Material m;
  m.name = "glossy";
  m.type = Material::Type::Glossy;
  m.reflectance = 0.0;
  m.specular = 1.0;
  m.roughness = 0.5;
  s.materials.push_back(m);
  s.meshes.push_back(quad_mesh("patch", 0, {-2, -2, 0}, {4, 0, 0}, {0, 4, 0}));
  // A 0.1 x 0.1 m opening perpendicular to the beam, whose centre ray meets the origin.
  const dvec3 u(std::cos(th), 0, std::sin(th)), v(0, 1, 0);
  Luminaire sun;
  sun.name = "beam";
  sun.type = Luminaire::Type::Directional;
  sun.direction = beam;
  sun.corner = -1.5 * beam - 0.05 * u - 0.05 * v;
  sun.edge1 = 0.1 * v;
  sun.edge2 = 0.1 * u;  // edge1 x edge2 = v x u = the beam direction
  sun.illuminance_lx = lux;
  s.luminaires.push_back(sun);
  const double flux = lux * 0.01;
  auto spherical = [&](double polar_deg, double azimuth_deg) {
    const double p = polar_deg * std::numbers::pi / 180.0,
                 a = azimuth_deg * std::numbers::pi / 180.0;
    return dvec3(std::sin(p) * std::cos(a), std::sin(p) * std::sin(a), std::cos(p));
  };
  const std::vector<std::pair<std::string, dvec3>> dirs = {
      {"specular", spherical(35, 0)},
      {"15 deg off", spherical(50, 0)},
      {"40 deg off", spherical(5, 180)},
      {"out of plane", spherical(38, 28)},
  };
  constexpr double size = 0.1;
  for (const auto& [name, d] : dirs) {
    // Unit edges with a x b = a x (a x d) = -d: the probe's front faces the patch.
    const dvec3 a = glm::normalize(glm::cross(d, dvec3(0, 1, 0.3))), b = glm::cross(a, d);
    s.targets.push_back(grid(name, dist * d - 0.5 * size * (a + b), size * a, size * b, 1, 1));
  }
  const Results r = run(s, GetParam() == "vulkan" ? 2'000'000 : 4'000'000);
  for (std::size_t k = 0; k < dirs.size(); ++k) {
    const Target& t = s.targets[k];
    const dvec3 normal = glm::normalize(glm::cross(t.edge1, t.edge2));
    constexpr int n = 8;
    double sum = 0.0;  // flux fraction reaching the probe, times its area
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        // Footprint point: the opening point carried along the beam to z = 0.
        const dvec3 q = sun.corner + ((i + 0.5) / n) * sun.edge1 + ((j + 0.5) / n) * sun.edge2;
        const dvec3 x = q + (-q.z / beam.z) * beam;
        for (int k1 = 0; k1 < n; ++k1) {
          for (int k2 = 0; k2 < n; ++k2) {
            const dvec3 y = t.corner + ((k1 + 0.5) / n) * t.edge1 + ((k2 + 0.5) / n) * t.edge2;
            const dvec3 o = glm::normalize(y - x);
            const double r2 = glm::dot(y - x, y - x);
            sum += glossy_pdf(in, o, alpha) * std::max(0.0, -glm::dot(o, normal)) / r2;
          }
        }
      }
    }
    // E = flux * (mean over footprint and probe of pdf cos / r^2): the probe-area integral of
    // dOmega = cos dA / r^2, divided by the area again for the mean illuminance.
    const double exact = flux * sum / (n * n * n * n);
    expect_in_ci(r.targets[k].estimate, exact, 0.2, dirs[k].first);
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, IndependentChecks, ::testing::ValuesIn(backends_and_nee()),
                         [](const auto& info) {
                           std::string n = info.param;
                           for (char& ch : n) ch = std::isalnum(ch) ? ch : '_';
                           return n;
                         });

}  // namespace
}  // namespace lightsolver::test
