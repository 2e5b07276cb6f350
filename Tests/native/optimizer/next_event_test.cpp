// Next-event estimation in the optimizer's evaluations (docs/optimization.md, "Next-event
// estimation"): a group traced alone carries its direct parts (Simulation::trace_group), and
// combining every group's trace is run() bit for bit with next_event on, on every backend; a
// point source over a surface target gives the closed-form direct illuminance; a combined
// result scales the direct part with the group's flux; a search with and without next-event
// estimation (fixed seeds) finds the same best configuration, the one the closed form says, and
// the results say which setting the evaluations followed.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "lightsolver/backends.hpp"
#include "lightsolver/optimizer/scene_problem.hpp"
#include "lightsolver/simulation.hpp"

namespace lightsolver::optimizer {
namespace {

using nlohmann::json;

std::vector<std::string> backend_names() {
  std::vector<std::string> names;
  for (const BackendInfo& b : lightsolver::backends()) {
    if (b.name != kAutoBackend) names.push_back(b.name);
  }
  return names;
}

json square(const std::string& name, const std::string& material, double x0, double y0, double side,
            double z) {
  return {{"name", name},
          {"material", material},
          {"vertices",
           {{x0, y0, z}, {x0 + side, y0, z}, {x0 + side, y0 + side, z}, {x0, y0 + side, z}}},
          {"triangles", {{0, 1, 2}, {0, 2, 3}}}};
}

// A 4 x 4 m floor (reflectance `rho`), a 1 x 1 m desk top at 0.75 m over [1, 2]^2 (the surface
// target), lamp "a" (1000 lm, isotropic point) moved over a 4 x 4 grid of 1 m cells at 2.5 m and
// lamp "b" (500 lm) fixed in a corner: maximise the desk's mean illuminance.
json desk_room(double rho, const std::string& next_event) {
  return {{"format", "lightsolver.scene/1"},
          {"materials",
           {{"floor", {{"type", "diffuse"}, {"reflectance", rho}}},
            {"desk", {{"type", "diffuse"}, {"reflectance", 0.0}}}}},
          {"meshes", {square("floor", "floor", 0, 0, 4, 0), square("desk", "desk", 1, 1, 1, 0.75)}},
          {"luminaires",
           {{{"name", "a"}, {"type", "point"}, {"flux_lm", 1000}, {"position", {0.5, 0.5, 2.5}}},
            {{"name", "b"}, {"type", "point"}, {"flux_lm", 500}, {"position", {3.5, 3.5, 2.5}}}}},
          {"targets", {{{"name", "desk"}, {"type", "surface"}, {"mesh", "desk"}}}},
          {"settings", {{"next_event", next_event}}},
          {"optimization",
           {{"intention", {{"type", "maximize_mean_illuminance"}, {"target", "desk"}}},
            {"variables",
             {{{"type", "position"},
               {"luminaire", "a"},
               {"corner", {0, 0, 2.5}},
               {"edge1", {4, 0, 0}},
               {"edge2", {0, 4, 0}},
               {"cells", {4, 4}}}}},
            {"search",
             {{"seed", 3},
              {"confidence", 0.99},
              {"screening_photons", 4000},
              {"confirmation_photons", 40000},
              {"strategy", "refine_at_end"},
              {"max_iterations", 30}}}}}};
}

SceneProblem parse_desk(const json& s) { return problem_from_json(s.dump(), "desk.json", "."); }

// The mean illuminance of a w x w square centred under an isotropic point source of I cd at
// height h: I times the square's solid angle from the source over its area.
double square_under_point(double intensity_cd, double w, double h) {
  const double omega = 4.0 * std::asin(w * w / (w * w + 4.0 * h * h));
  return intensity_cd * omega / (w * w);
}

void expect_same(const Estimate& a, const Estimate& b, const std::string& where) {
  EXPECT_EQ(a.mean, b.mean) << where;
  EXPECT_EQ(a.ci_low, b.ci_low) << where;
  EXPECT_EQ(a.ci_high, b.ci_high) << where;
  EXPECT_EQ(a.sigma, b.sigma) << where;
  EXPECT_EQ(a.hits, b.hits) << where;
}

Results traced_apart(Simulation& sim, std::uint64_t photons, std::uint64_t seed,
                     std::vector<GroupTrace>& traces) {
  std::vector<double> flux;
  traces.clear();
  for (std::size_t g = 0; g < sim.groups().size(); ++g) {
    traces.push_back(sim.trace_group(g, photons, seed));
    flux.push_back(sim.groups()[g].flux_lm);
  }
  std::vector<const GroupTrace*> parts;
  for (const GroupTrace& t : traces) parts.push_back(&t);
  return sim.combine(parts, flux, 0.95);
}

bool simulated(const Results& r, const std::string& effect) {
  return std::find(r.effects.simulated.begin(), r.effects.simulated.end(), effect) !=
         r.effects.simulated.end();
}

class GroupTraceNextEvent : public ::testing::TestWithParam<std::string> {};

// Every group traced apart with next_event on and combined is run() with it, bit for bit (the
// photons skip their bounce-0 deposits, the direct parts are the run's own points).
TEST_P(GroupTraceNextEvent, CombinedTracesAreTheRunBitForBit) {
  Scene scene = parse_desk(desk_room(0.5, "on")).scene;
  Simulation sim(scene, Simulation::Options{GetParam(), 2, {}});
  ASSERT_EQ(sim.groups().size(), 2u);
  SolveOptions o;
  o.photons = 50'000;
  o.seed = 11;
  const Results run = sim.run(o);
  ASSERT_TRUE(simulated(run, "next_event_direct"));
  std::vector<GroupTrace> traces;
  const Results apart = traced_apart(sim, 50'000, 11, traces);
  for (const GroupTrace& t : traces) {
    EXPECT_EQ(t.direct.size(), t.bins.size());
    EXPECT_GT(t.shadow_rays, 0u);
    EXPECT_TRUE(t.next_event_off.empty());
  }
  EXPECT_TRUE(simulated(apart, "next_event_direct"));
  EXPECT_EQ(apart.next_event, "on");
  ASSERT_EQ(run.targets.size(), apart.targets.size());
  expect_same(run.targets[0].estimate, apart.targets[0].estimate, "desk");
  // And off: no direct parts, the reason in the effects list.
  scene.settings.next_event = "off";
  Simulation plain(scene, Simulation::Options{GetParam(), 2, {}});
  const Results photons_only = traced_apart(plain, 50'000, 11, traces);
  EXPECT_TRUE(traces[0].direct.empty());
  EXPECT_FALSE(simulated(photons_only, "next_event_direct"));
  o.next_event = "off";
  expect_same(plain.run(o).targets[0].estimate, photons_only.targets[0].estimate, "desk, off");
}

INSTANTIATE_TEST_SUITE_P(Backends, GroupTraceNextEvent, ::testing::ValuesIn(backend_names()));

// Nothing reflects (floor and desk black): the desk's light is lamp "a"'s direct light alone,
// whose mean over the desk has a closed form; the photons' part is exactly zero. Combined at
// half the flux, the direct part halves.
TEST(GroupTraceNextEvent, PointOverSurfaceTargetIsTheClosedForm) {
  json j = desk_room(0.0, "on");
  j["luminaires"][0]["position"] = {1.5, 1.5, 2.5};  // over the desk's centre
  j["luminaires"][1]["flux_lm"] = 0;
  Simulation sim(parse_desk(j).scene, Simulation::Options{"embree", 2, {}});
  const GroupTrace t = sim.trace_group(0, 20'000, 5);
  ASSERT_FALSE(t.direct.empty());
  EXPECT_FALSE(t.photons_reflect);
  const double exact = square_under_point(1000.0 / (4.0 * M_PI), 1.0, 2.5 - 0.75);
  for (double flux : {1000.0, 500.0}) {
    const Results r = sim.combine({&t, nullptr}, {flux, 0.0}, 0.95);
    const Estimate& e = r.targets[0].estimate;
    const double expected = exact * flux / 1000.0;
    EXPECT_NEAR(e.mean, expected, 4.0 * e.sigma + 1e-12 * expected) << flux;
    EXPECT_LE(e.ci_low, expected);
    EXPECT_GE(e.ci_high, expected);
    EXPECT_GT(e.sigma, 0.0);
    EXPECT_LT(e.sigma, 2e-3 * expected);  // stratified points over a smooth field
  }
}

// A trace continued from its first part (the staged refinement's first stage) is the trace
// from photon 0, bit for bit, with and without next-event estimation, also when the first part
// was given the whole run's direct parts; a prefix of another seed, a larger run or another
// next-event plan is refused.
TEST(GroupTraceNextEvent, ContinuedTraceIsTheWholeTraceBitForBit) {
  for (const std::string mode : {"off", "on"}) {
    Simulation sim(parse_desk(desk_room(0.5, mode)).scene, Simulation::Options{"embree", 2, {}});
    const GroupTrace whole = sim.trace_group(0, 80'000, 21);
    const GroupTrace first = sim.trace_group(0, 20'000, 21);
    const GroupTrace rest = sim.trace_group(0, 80'000, 21, nullptr, &first);
    ASSERT_EQ(whole.bins.size(), rest.bins.size());
    for (std::size_t b = 0; b < whole.bins.size(); ++b) {
      EXPECT_EQ(whole.bins[b].sum, rest.bins[b].sum) << mode;
      EXPECT_EQ(whole.bins[b].sum_sq, rest.bins[b].sum_sq) << mode;
    }
    EXPECT_EQ(whole.ray_segments, rest.ray_segments);
    EXPECT_EQ(whole.photons, rest.photons);
    ASSERT_EQ(whole.direct.size(), rest.direct.size());
    EXPECT_EQ(whole.direct.empty(), mode == "off");
    for (std::size_t b = 0; b < whole.direct.size(); ++b) {
      EXPECT_EQ(whole.direct[b].lux, rest.direct[b].lux);
      EXPECT_EQ(whole.direct[b].variance_lx2, rest.direct[b].variance_lx2);
    }
    EXPECT_THROW(sim.trace_group(0, 80'000, 22, nullptr, &first), std::invalid_argument);
    EXPECT_THROW(sim.trace_group(0, 10'000, 21, nullptr, &first), std::invalid_argument);
    // A first part with the whole run's direct parts (a staged refinement's stage): its
    // continuation keeps them, so it is still the whole trace bit for bit.
    const GroupTrace stage = sim.trace_group(0, 20'000, 21, nullptr, nullptr, 80'000);
    const GroupTrace continued = sim.trace_group(0, 80'000, 21, nullptr, &stage);
    EXPECT_EQ(stage.photons, first.photons);
    if (mode == "on") {
      EXPECT_LT(first.shadow_rays, whole.shadow_rays);  // sized apart otherwise
    }
    EXPECT_EQ(stage.shadow_rays, whole.shadow_rays);
    ASSERT_EQ(stage.direct.size(), whole.direct.size());
    for (std::size_t b = 0; b < whole.direct.size(); ++b) {
      EXPECT_EQ(stage.direct[b].lux, whole.direct[b].lux);
      EXPECT_EQ(continued.direct[b].variance_lx2, whole.direct[b].variance_lx2);
    }
    for (std::size_t b = 0; b < whole.bins.size(); ++b)
      EXPECT_EQ(whole.bins[b].sum, continued.bins[b].sum) << mode;
  }
  Scene on = parse_desk(desk_room(0.5, "on")).scene, off = on;
  off.settings.next_event = "off";
  Simulation with(on, Simulation::Options{"embree", 2, {}});
  Simulation without(off, Simulation::Options{"embree", 2, {}});
  const GroupTrace photons_only = without.trace_group(0, 20'000, 21);
  EXPECT_THROW(with.trace_group(0, 80'000, 21, nullptr, &photons_only), std::invalid_argument);
}

// The same search (seeds fixed) with and without next-event estimation: both keep the cell over
// the desk, which the closed form says is best by far (the next cells get 0.62 of its direct
// light); with it the intervals are narrower, so its ISOC is no larger; the results say which.
// N as given (match_widths false; the default scales N: MatchedWidthsTraceFewerPhotons... below).
TEST(OptimizerNextEvent, SearchKeepsTheClosedFormBestWithAndWithout) {
  std::size_t sizes[2] = {0, 0};
  for (const std::string mode : {"off", "on"}) {
    const SceneProblem p = parse_desk(desk_room(0.5, mode));
    RunOverrides o;
    o.threads = 2;
    o.backend = "embree";
    o.match_widths = false;
    const OptimizationResult r = run_problem(p, o);
    ASSERT_FALSE(r.isoc.empty()) << mode;
    EXPECT_EQ(r.isoc[0].cells, (Configuration{1, 1})) << mode;
    EXPECT_EQ(r.isoc[0].photons, 40'000u) << mode;
    ASSERT_TRUE(r.next_event);
    EXPECT_EQ(r.next_event->setting, mode);
    EXPECT_EQ(r.next_event->direct, mode == "on");
    EXPECT_EQ(r.next_event->reason.empty(), mode == "on") << r.next_event->reason;
    sizes[mode == "on"] = r.isoc.size();
    const json out = json::parse(problem_result_json(p, r));
    EXPECT_EQ(out["next_event"]["setting"], mode);
    EXPECT_EQ(out["provenance"]["options"]["next_event"], mode);
  }
  EXPECT_LE(sizes[1], sizes[0]);
  // The override wins over the scene's setting.
  const SceneProblem p = parse_desk(desk_room(0.5, "off"));
  RunOverrides o;
  o.threads = 2;
  o.backend = "embree";
  o.next_event = "on";
  o.iterations = 2;
  EXPECT_TRUE(run_problem(p, o).next_event->direct);
}

// The staged refinement in a scene search (docs/optimization.md §6): the first stage's traces
// are continued to N, so every member's N estimate is, bit for bit, the unstaged one's, and the
// ISOC is the same; the refinement traces no more photons than unstaged. With and without
// next-event estimation. The target is the floor, whose mean illuminance hardly depends on
// where the lamp is: a broad optimum, many members at n. N as given (match_widths false): the
// default would scale this small N down to 4 n, where stages have little to leave out.
TEST(OptimizerNextEvent, StagedRefinementContinuesTracesBitForBit) {
  for (const std::string mode : {"off", "on"}) {
    json j = desk_room(0.5, mode);
    j["targets"][0]["mesh"] = "floor";
    const SceneProblem p = parse_desk(j);
    RunOverrides o;
    o.threads = 2;
    o.backend = "embree";
    o.match_widths = false;
    o.screening_photons = 2000;  // a wide n-level ISOC: several members to stage
    o.refine_stage_photons = 0;
    const OptimizationResult plain = run_problem(p, o);
    o.refine_stage_photons.reset();  // the default: N / 4
    const OptimizationResult staged = run_problem(p, o);
    EXPECT_EQ(plain.counters.refine_stage, 0u);
    EXPECT_GT(staged.counters.refine_stage, 1u) << mode;
    EXPECT_EQ(staged.counters.refined + staged.counters.refine_dropped, plain.counters.refined);
    EXPECT_LE(staged.counters.photons_traced, plain.counters.photons_traced)
        << mode << ": stage traces " << staged.counters.refine_stage << ", left out "
        << staged.counters.refine_dropped << ", refined " << staged.counters.refined << " of "
        << plain.counters.refined;
    ASSERT_EQ(plain.isoc.size(), staged.isoc.size()) << mode;
    for (std::size_t i = 0; i < plain.isoc.size(); ++i) {
      EXPECT_EQ(plain.isoc[i].cells, staged.isoc[i].cells);
      EXPECT_EQ(plain.isoc[i].objective.mean, staged.isoc[i].objective.mean);
      EXPECT_EQ(plain.isoc[i].objective.sigma, staged.isoc[i].objective.sigma);
    }
  }
}

// Equal widths (docs/optimization.md §6): with next-event estimation N is scaled by the
// measured variance ratio (well below 1 over the desk, whose light is mostly direct), the
// provenance says by how much, the same best cell is found, and its interval is no wider than
// a photon-only search's at the unscaled N; where no direct part is traced nothing changes.
TEST(OptimizerNextEvent, MatchedWidthsTraceFewerPhotonsForTheSameIntervals) {
  const auto factor = [](const OptimizationResult& r) {
    for (const auto& [key, value] : r.provenance->options) {
      if (key == "width_factor") return std::get<double>(value);
    }
    return -1.0;  // not matched
  };
  const SceneProblem on = parse_desk(desk_room(0.5, "on")), off = parse_desk(desk_room(0.5, "off"));
  RunOverrides o;
  o.threads = 2;
  o.backend = "embree";
  o.match_widths = false;
  const OptimizationResult photons = run_problem(off, o);
  o.match_widths = true;
  const OptimizationResult matched = run_problem(on, o);
  const double f = factor(matched);
  EXPECT_GT(f, 0.0);
  EXPECT_LT(f, 0.8);
  EXPECT_EQ(factor(photons), -1.0);
  ASSERT_FALSE(matched.isoc.empty());
  ASSERT_FALSE(photons.isoc.empty());
  EXPECT_EQ(matched.isoc[0].cells, photons.isoc[0].cells);
  EXPECT_EQ(matched.isoc[0].photons, std::uint64_t(std::llround(40'000 * f)));
  const double width = matched.isoc[0].objective.ci_high - matched.isoc[0].objective.ci_low;
  const double photon_width = photons.isoc[0].objective.ci_high - photons.isoc[0].objective.ci_low;
  // Mostly direct light: the ratio is below 0.2, so N is scaled to the calibration's count,
  // max(N/8, 2 n) = 8000 photons (not extrapolated below it), and the interval is no wider.
  EXPECT_EQ(f, 0.2);
  EXPECT_LE(width, 1.25 * photon_width) << width << " vs " << photon_width;
  const OptimizationResult unchanged = run_problem(off, o);  // no direct part: factor 1
  EXPECT_EQ(factor(unchanged), 1.0);
  EXPECT_EQ(unchanged.isoc[0].photons, 40'000u);
}

// A next_event value outside auto/on/off is refused before the search, naming the setting.
TEST(OptimizerNextEvent, BadSettingsAreRefused) {
  json j = desk_room(0.5, "on");
  const SceneProblem p = parse_desk(j);
  RunOverrides o;
  o.backend = "embree";
  o.next_event = "sometimes";
  EXPECT_THROW(
      {
        try {
          run_problem(p, o);
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("next_event"), std::string::npos) << e.what();
          throw;
        }
      },
      InputError);
}

}  // namespace
}  // namespace lightsolver::optimizer
