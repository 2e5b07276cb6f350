// Connected reflected light at grids (estimate/reflection_connection.hpp): a closed form of the
// first reflection with the r0 partition crossed (near crossings by photons, far ones by
// connections), the same box room as photons alone, honest intervals over 200 seeds, and the
// setting's errors, stops between its batches and during the photons, and goal runs.
#include "estimate/reflection_connection.hpp"

#include <gtest/gtest.h>

#include <atomic>

#include "embree/embree_backend.hpp"
#include "estimate/next_event.hpp"
#include "lightsolver/rescale.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

Results run_connected(Scene s, std::uint64_t photons, std::uint64_t seed, const std::string& mode,
                      double confidence = kCheckConfidence) {
  validate(s);
  SolveOptions o;
  o.backend = "embree";
  o.photons = photons;
  o.seed = seed;
  o.confidence = confidence;
  o.next_event = "on";
  o.connect_reflections = mode;
  return solve(s, o);
}

// A point source of `flux` at height H over an (effectively infinite) diffuse floor of
// reflectance rho, and grids facing DOWN at heights h: they count only the light the floor
// reflects (the direct light crosses them from behind), which leaves to infinity after one
// reflection. Floor 400 x 400 m: the light reflected beyond it is below 1e-9 of the total.
constexpr double kH = 2.0, kRho = 0.6, kFlux = 6000.0, kFloor = 200.0;
const dvec3 kSource(0.3, -0.2, kH);

Scene floor_scene(const std::vector<double>& heights) {
  Scene s;
  add_material(s, "floor", Material::Type::Diffuse, kRho);
  s.meshes.push_back(
      quad_mesh("floor", 0, {-kFloor, -kFloor, 0}, {2 * kFloor, 0, 0}, {0, 2 * kFloor, 0}));
  s.luminaires.push_back(point_light(kSource, kFlux));
  for (std::size_t i = 0; i < heights.size(); ++i) {
    // corner + e1 x e2 = -z: the front faces the floor. 2 x 2 m, 4 x 4 cells of 0.5 m.
    s.targets.push_back(
        grid("grid " + std::to_string(i), {-1, -1, heights[i]}, {0, 2, 0}, {2, 0, 0}, 4, 4));
  }
  return s;
}

// Irradiance at y (height h, facing down) from the floor lit by the source:
// E = rho I H / pi * integral of h^2 / (D^3 r^4) over the plane (D: source to x, r: x to y),
// in polar coordinates about y's foot with rho' = h tan(a): h^2 dA / r^4 = sin(a) cos(a) da dphi.
double reflected_lux(dvec3 y) {
  const double intensity = kFlux / (4.0 * std::numbers::pi);
  const int na = 400, nphi = 128;
  double sum = 0.0;
  for (int i = 0; i < na; ++i) {
    const double a = (i + 0.5) / na * 0.5 * std::numbers::pi;
    const double radial = y.z * std::tan(a);
    for (int j = 0; j < nphi; ++j) {
      const double phi = (j + 0.5) / nphi * 2.0 * std::numbers::pi;
      const dvec3 x(y.x + radial * std::cos(phi), y.y + radial * std::sin(phi), 0.0);
      const double D = glm::length(kSource - x);
      sum += std::sin(a) * std::cos(a) / (D * D * D);
    }
  }
  const double da_dphi = (0.5 * std::numbers::pi / na) * (2.0 * std::numbers::pi / nphi);
  return kRho * intensity * kH / std::numbers::pi * sum * da_dphi;
}

// A cell's mean: 3 x 3 Gauss-Legendre points.
double cell_lux(double x0, double y0, double size, double h) {
  const double g[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, w[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const dvec3 y(x0 + 0.5 * size * (1 + g[i]), y0 + 0.5 * size * (1 + g[j]), h);
      sum += w[i] * w[j] / 4.0 * reflected_lux(y);
    }
  }
  return sum;
}

// Grid cell k of the grids above: edge1 along y, edge2 along x (front down).
double exact_cell(std::size_t k, double h) {
  const double iu = double(k % 4), iv = double(k / 4);
  return cell_lux(-1.0 + 0.5 * iv, -1.0 + 0.5 * iu, 0.5, h);
}

// At h = 0.5 m three quarters of a cell's reflected light comes from closer than r0 (two cells,
// 1 m): the photons' capped crossings; at 1.5 m all of it from farther: connections. Either
// strategy missing, or both counting the same pairs, moves the cells by 25 % or more (0.5 m).
TEST(ReflectionConnection, FirstReflectionOverAFloorMatchesTheClosedForm) {
  const std::vector<double> heights{0.5, 1.5};
  const Results r = run_connected(floor_scene(heights), 1'000'000, 7, "on");
  for (std::size_t t = 0; t < heights.size(); ++t) {
    ASSERT_EQ(r.targets[t].cells.size(), 16u);
    const std::string where = "grid at " + std::to_string(heights[t]) + " m";
    double whole = 0.0;
    for (std::size_t k = 0; k < 16; ++k) {
      const double exact = exact_cell(k, heights[t]);
      whole += exact / 16.0;
      // Near pairs are photon crossings: a cell's 5-sigma interval is wide at 0.5 m.
      expect_in_ci(r.targets[t].cells[k], exact, t == 0 ? 0.3 : 0.1,
                   where + ", cell " + std::to_string(k));
    }
    expect_in_ci(r.targets[t].estimate, whole, 0.06, where + ", whole grid");
  }
  const auto& effects = r.effects.simulated;
  EXPECT_NE(std::find(effects.begin(), effects.end(), "reflection_connection"), effects.end());
}

// The same floor with the part off (photons count every reflected crossing): the closed form
// holds there too, so the test above checks the connection and not a shared error.
TEST(ReflectionConnection, PhotonsAloneMatchTheSameClosedForm) {
  const Results r = run_connected(floor_scene({0.5}), 1'000'000, 7, "off");
  double whole = 0.0;
  for (std::size_t k = 0; k < 16; ++k) {
    const double exact = exact_cell(k, 0.5);
    whole += exact / 16.0;
    expect_in_ci(r.targets[0].cells[k], exact, 0.3, "cell " + std::to_string(k));
  }
  expect_in_ci(r.targets[0].estimate, whole, 0.08, "whole grid");
}

// The box room (several reflections, walls just above the plane): every cell agrees
// with photons alone within five combined sigma, and the intervals are narrower.
TEST(ReflectionConnection, AgreesWithPhotonsAloneInTheBoxRoom) {
  const Scene s = box_room(8);
  const Results on = run_connected(s, 200'000, 11, "on", 0.95);
  const Results off = run_connected(s, 200'000, 12, "off", 0.95);
  ASSERT_EQ(on.targets[0].cells.size(), 64u);
  const auto [width_on, width_off] = expect_cells_agree(on, off);
  EXPECT_LT(width_on, 0.7 * width_off);
  expect_same_within(on.targets[0].estimate, off.targets[0].estimate, "whole grid");
}

// The part is linear in the group's flux and travels in the direct parts: rescaling a result
// by 0.5 gives the run traced at half the flux, cell for cell.
TEST(ReflectionConnection, RescaleMatchesARunAtTheDimmedFlux) {
  Scene s = floor_scene({0.5, 1.5});
  s.settings.contributions = true;
  const Results full = run_connected(s, 50'000, 4, "on", 0.95);
  s.luminaires[0].flux_lm *= 0.5;
  const Results traced = run_connected(s, 50'000, 4, "on", 0.95);
  const Results half =
      rescale_results(results_to_json(full), {{s.luminaires[0].group_name(), 0.5}});
  for (std::size_t t = 0; t < 2; ++t) {
    for (std::size_t k = 0; k < 16; ++k) {
      const Estimate &a = half.targets[t].cells[k], &b = traced.targets[t].cells[k];
      EXPECT_NEAR(a.mean, b.mean, 1e-12 * b.mean) << t << " " << k;
      EXPECT_NEAR(a.ci_high - a.ci_low, b.ci_high - b.ci_low, 1e-12 * b.mean) << t << " " << k;
    }
  }
}

// Per-cell 95 % intervals over 200 seeds on the floor (h = 0.5 m: both strategies) cover the
// closed form within binomial limits (4 sigma of 3200 intervals).
TEST(ReflectionConnection, PerCellCoverageOver200Seeds) {
  const Scene s = floor_scene({0.5});
  std::vector<double> exact(16);
  for (std::size_t k = 0; k < 16; ++k) exact[k] = exact_cell(k, 0.5);
  int covered = 0, total = 0;
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    const Results r = run_connected(s, 20'000, seed, "on", 0.95);
    for (std::size_t k = 0; k < 16; ++k) {
      const Estimate& e = r.targets[0].cells[k];
      covered += e.ci_low <= exact[k] && exact[k] <= e.ci_high;
      ++total;
    }
  }
  const double p = double(covered) / total, sd = std::sqrt(0.95 * 0.05 / total);
  EXPECT_GT(p, 0.95 - 4 * sd) << covered << " of " << total;
  EXPECT_LT(p, 0.95 + 4 * sd) << covered << " of " << total;
}

// Bad values name the setting; `on` where it cannot run says why.
TEST(ReflectionConnection, BadSettingsAreInputErrorsNamingTheField) {
  const Scene s = floor_scene({0.5});
  auto message = [&](Scene scene, const std::string& mode, const std::string& next_event) {
    try {
      validate(scene);
      SolveOptions o;
      o.backend = "embree";
      o.photons = 1000;
      o.next_event = next_event;
      o.connect_reflections = mode;
      solve(scene, o);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(s, "sometimes", "on").find("connect_reflections"), std::string::npos);
  const std::string no_nee = message(s, "on", "off");
  EXPECT_NE(no_nee.find("connect_reflections"), std::string::npos) << no_nee;
  EXPECT_NE(no_nee.find("next_event"), std::string::npos) << no_nee;
  Scene mirror = s;
  add_material(mirror, "mirror", Material::Type::Mirror, 0.9);
  mirror.meshes.push_back(quad_mesh("mirror", 1, {5, 5, 0.01}, {1, 0, 0}, {0, 1, 0}));
  const std::string glossy = message(mirror, "on", "on");
  EXPECT_NE(glossy.find("connect_reflections"), std::string::npos) << glossy;
  EXPECT_NE(glossy.find("mirror"), std::string::npos) << glossy;
  // auto leaves it off there and says why; the scene settings' value is checked too.
  validate(mirror);
  SolveOptions o;
  o.backend = "embree";
  o.photons = 1000;
  o.next_event = "on";
  o.connect_reflections = "auto";
  const Results r = solve(mirror, o);
  const auto& skipped = r.effects.skipped;
  EXPECT_TRUE(std::any_of(skipped.begin(), skipped.end(), [](const auto& e) {
    return e.effect == "reflection_connection" && e.reason.find("mirror") != std::string::npos;
  }));
  Scene bad = s;
  bad.settings.connect_reflections = "yes";
  EXPECT_THROW(
      {
        try {
          validate(bad);
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("connect_reflections"), std::string::npos);
          throw;
        }
      },
      InputError);
}

std::string connection_reason(const Results& r) {
  for (const auto& e : r.effects.skipped) {
    if (e.effect == "reflection_connection") return e.reason;
  }
  return "simulated";
}

// auto leaves it to the photons, saying why, where its fewest paths would cost far more than
// the run's photons; a run with an accuracy goal connects (its paths refined before the photons).
TEST(ReflectionConnection, AutoLeavesTinyRunsToPhotonsAndConnectsAccuracyRuns) {
  Scene s = floor_scene({0.5});
  validate(s);
  const auto reason = [](const Results& r) {
    for (const auto& e : r.effects.skipped) {
      if (e.effect == "reflection_connection") return e.reason;
    }
    return std::string("simulated");
  };
  SolveOptions o;
  o.backend = "embree";
  o.next_event = "on";
  o.connect_reflections = "auto";
  o.photons = 200;  // 2 x 512 paths x 16 cells: 16384 rays, more than 24 per photon
  EXPECT_NE(reason(solve(s, o)).find("per photon"), std::string::npos);
  o.photons = 20'000;
  EXPECT_EQ(reason(solve(s, o)), "simulated");
  o.photons.reset();
  o.target_accuracy = 0.5;
  EXPECT_EQ(reason(solve(s, o)), "simulated");
}

// auto judges from its first paths whether the connection pays: in a room of reflectance 0.01
// the connected light is far under kConnectMinShare of the direct light, so the photons keep it
// (`on` still connects); at 0.5 it pays.
TEST(ReflectionConnection, AutoLeavesNegligibleReflectedLightToPhotons) {
  Scene dark = box_room(8);
  dark.materials[0].reflectance = 0.01;
  const Results off = run_connected(dark, 100'000, 3, "auto");
  EXPECT_NE(connection_reason(off).find("of their direct light"), std::string::npos)
      << connection_reason(off);
  EXPECT_EQ(connection_reason(run_connected(dark, 100'000, 3, "on")), "simulated");
  EXPECT_EQ(connection_reason(run_connected(box_room(8), 100'000, 3, "auto")), "simulated");
}

// add_connected_reflection asks its stop between batches of about 2^18 shadow rays: stopped, it
// leaves the parts as they were; never stopped, it gives the parts of a run without a stop.
TEST(ReflectionConnection, AStoppedConnectionLeavesThePartsAsTheyWere) {
  Scene s = floor_scene({0.5, 1.5});
  validate(s);
  detail::PreparedScene p = detail::prepare(s);
  const auto backend = detail::make_embree_backend(p);
  detail::plan_next_event(p, *backend, "on");
  detail::plan_connection(p, *backend, "on", false, 1'000'000);
  // 32 cells: 4096 paths (2^18 rays at two vertices a path) a batch, four batches.
  const std::uint64_t paths = 16384;
  const std::vector<detail::DirectPart> before(p.groups.size() * p.bins.size(),
                                               detail::DirectPart{1.0, 2.0, 3});
  int asked = 0;
  std::vector<detail::DirectPart> stopped = before;
  EXPECT_FALSE(detail::add_connected_reflection(p, *backend, 5, paths, stopped,
                                                [&] { return ++asked == 3; }));
  EXPECT_EQ(asked, 3);
  for (std::size_t i = 0; i < before.size(); ++i) {
    EXPECT_EQ(stopped[i].lux, 1.0);
    EXPECT_EQ(stopped[i].variance, 2.0);
    EXPECT_EQ(stopped[i].lit, 3u);
  }
  asked = 0;
  std::vector<detail::DirectPart> asking = before, plain = before;
  EXPECT_TRUE(detail::add_connected_reflection(p, *backend, 5, paths, asking, [&] {
    ++asked;
    return false;
  }));
  EXPECT_EQ(asked, 4);
  EXPECT_TRUE(detail::add_connected_reflection(p, *backend, 5, paths, plain));
  double added = 0.0;
  for (std::size_t i = 0; i < before.size(); ++i) {
    EXPECT_EQ(asking[i].lux, plain[i].lux);
    EXPECT_EQ(asking[i].variance, plain[i].variance);
    added += plain[i].lux - 1.0;
  }
  EXPECT_GT(added, 0.0);
}

// A run stopped during its photons keeps the fewest paths' connection, traced before them, and
// says so: the grid at 1.5 m (all of its light connected, none direct) has the cells of a plain
// run that plans the fewest paths, and every cell is honest against the closed form.
TEST(ReflectionConnection, AStopDuringThePhotonsKeepsTheFewestPathsConnection) {
  Scene s = floor_scene({0.5, 1.5});
  validate(s);
  SolveOptions o;
  o.backend = "embree";
  o.photons = 100'000'000;  // plans about 10^7 paths
  o.seed = 9;
  o.next_event = "on";
  o.connect_reflections = "on";
  const Results stopped = solve(s, o, [](std::uint64_t, std::uint64_t) { return false; });
  EXPECT_TRUE(stopped.partial);
  EXPECT_EQ(stopped.stop_reason, kStopCancelled);
  EXPECT_TRUE(std::any_of(stopped.warnings.begin(), stopped.warnings.end(), [](const auto& w) {
    return w.find("reflected light was connected as planned") != std::string::npos;
  })) << "no warning";
  EXPECT_EQ(connection_reason(stopped), "simulated");
  o.photons = 4'000;  // plans the fewest paths, 512
  const Results fewest = solve(s, o);
  EXPECT_TRUE(std::none_of(fewest.warnings.begin(), fewest.warnings.end(), [](const auto& w) {
    return w.find("as planned") != std::string::npos;
  }));
  for (std::size_t k = 0; k < 16; ++k) {
    // The means only: the photons' empty tallies still widen the intervals by their count.
    EXPECT_EQ(stopped.targets[1].cells[k].mean, fewest.targets[1].cells[k].mean) << k;
  }
  for (std::size_t t = 0; t < 2; ++t) {
    for (std::size_t k = 0; k < 16; ++k) {
      const Estimate& e = stopped.targets[t].cells[k];
      const double exact = exact_cell(k, t == 0 ? 0.5 : 1.5);
      EXPECT_TRUE(std::isfinite(e.ci_low) && std::isfinite(e.ci_high));
      EXPECT_TRUE(e.ci_low <= e.mean && e.mean <= e.ci_high);
      EXPECT_GT(e.sigma, 0.0);
      EXPECT_LT(std::abs(e.mean - exact), 5.0 * e.sigma) << t << " " << k;
    }
  }
}

// Stopped before anything (the cancel flag set before the run): no direct parts, so no
// connection, with the reason, and every interval contains its estimate.
TEST(ReflectionConnection, AStopBeforeAnythingConnectsNothingAndSaysWhy) {
  Scene s = floor_scene({0.5});
  validate(s);
  std::atomic<bool> cancel{true};
  SolveOptions o;
  o.backend = "embree";
  o.photons = 1'000'000;
  o.next_event = "on";
  o.connect_reflections = "auto";
  o.cancel = &cancel;
  const Results r = solve(s, o);
  EXPECT_TRUE(r.partial);
  EXPECT_NE(connection_reason(r).find("next-event"), std::string::npos) << connection_reason(r);
  for (const Estimate& e : r.targets[0].cells) {
    EXPECT_TRUE(std::isfinite(e.ci_low) && std::isfinite(e.ci_high));
    EXPECT_TRUE(e.ci_low <= e.mean && e.mean <= e.ci_high);
  }
}

// A goal run connects: it reaches its goal, the grid at 1.5 m (connected light only) has every
// cell's connected part within half the goal (the paths refined before the photons), and the 95 %
// intervals of 20 seeds x 32 cells cover the closed form within binomial limits (4 sigma).
TEST(ReflectionConnection, AGoalRunReachesItsGoalWithHonestIntervals) {
  const std::vector<double> heights{0.5, 1.5};
  Scene s = floor_scene(heights);
  validate(s);
  std::vector<double> exact;
  for (double h : heights) {
    for (std::size_t k = 0; k < 16; ++k) exact.push_back(exact_cell(k, h));
  }
  int covered = 0, total = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    SolveOptions o;
    o.backend = "embree";
    o.seed = seed;
    o.confidence = 0.95;
    o.target_accuracy = 0.1;
    o.next_event = "on";
    o.connect_reflections = "auto";
    o.contributions = true;
    const Results r = solve(s, o);
    ASSERT_EQ(connection_reason(r), "simulated");
    ASSERT_EQ(r.targets[1].contributions.size(), 1u);
    const auto& connected = r.targets[1].contributions[0].direct;  // whole grid, then cells
    ASSERT_EQ(connected.size(), 17u);
    for (std::size_t k = 1; k < 17; ++k) {
      EXPECT_GT(connected[k].lux, 0.0);
      EXPECT_LE(1.96 * std::sqrt(connected[k].variance_lx2), 0.05 * connected[k].lux) << k;
    }
    EXPECT_EQ(r.stop_reason, kStopAccuracy) << seed;
    for (std::size_t t = 0; t < 2; ++t) {
      const Estimate& whole = r.targets[t].estimate;
      EXPECT_LE(0.5 * (whole.ci_high - whole.ci_low), 0.1 * whole.mean) << seed << " " << t;
      for (std::size_t k = 0; k < 16; ++k) {
        const Estimate& e = r.targets[t].cells[k];
        covered += e.ci_low <= exact[16 * t + k] && exact[16 * t + k] <= e.ci_high;
        ++total;
      }
    }
  }
  const double p = double(covered) / total, sd = std::sqrt(0.95 * 0.05 / total);
  EXPECT_GT(p, 0.95 - 4 * sd) << covered << " of " << total;
  EXPECT_LT(p, 0.95 + 4 * sd) << covered << " of " << total;
}

}  // namespace
}  // namespace lightsolver::test
