// Luminaire groups with next-event estimation (docs/statistics.md, "Next-event estimation",
// "Recombining"): each group's direct parts travel in its contributions (`photon_light`,
// `direct`), so `rescale` rebuilds every estimate as the run built it: a factor 1 gives the run
// bit for bit, a factor f the run traced at the dimmed fluxes with the same photons (the direct
// means times f, their variances times f^2), results without direct parts rescale as before,
// and inconsistent direct parts are refused naming the field.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "lightsolver/rescale.hpp"
#include "lightsolver/simulation.hpp"
#include "lightsolver/solver.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

// A run with contributions whose photon shares do not follow the fluxes: dimming a group keeps
// every group's photons, so every tally and every shadow-ray point is as traced.
Results traced(const Scene& s, const std::string& next_event) {
  Simulation sim(s, {.backend = "embree", .threads = 2});
  sim.fix_photon_shares({1.0, 1.0});
  SolveOptions o;
  o.photons = 100'000;
  o.seed = 7;
  o.contributions = true;
  o.next_event = next_event;
  return sim.run(o);
}

Scene dimmed(Scene s, double left, double right) {
  for (Luminaire& l : s.luminaires) l.flux_lm *= l.group == "left" ? left : right;
  return s;
}

// The grouped room with requirements on its work plane (verdicts and grid intervals too).
Scene judged_room() {
  Scene s = grouped_room();
  s.targets[1].requirements.em_lux = 150.0;
  s.targets[1].requirements.u0 = 0.2;
  return s;
}

// Two groups of point lamps over a grid in empty space: no surface returns light, so a
// next-event group's photons deposit nothing and its part is its direct part alone.
Scene open_plane() {
  Scene s;
  s.luminaires.push_back(named(point_light({0.3, 0.5, 1.0}, 1000), "a", "left"));
  s.luminaires.push_back(named(point_light({1.2, 0.4, 0.6}, 400), "b", "right"));
  s.targets.push_back(grid("plane", {0, 0, 0}, {1.5, 0, 0}, {0, 1, 0}, 3, 2));
  validate(s);
  return s;
}

nlohmann::json targets(const std::string& json) { return nlohmann::json::parse(json)["targets"]; }

void expect_close(const Estimate& a, const Estimate& b, const std::string& what) {
  EXPECT_NEAR(a.mean, b.mean, 1e-12 * b.mean) << what;
  EXPECT_NEAR(a.ci_low, b.ci_low, 1e-12 * b.mean) << what;
  EXPECT_NEAR(a.ci_high, b.ci_high, 1e-12 * b.mean) << what;
  EXPECT_EQ(a.hits, b.hits) << what;
}

// Rescaled by (left, right) against the run traced at those fluxes with the same photons:
// targets, cells and each group's direct parts agree to rounding.
void expect_rescaled_is_traced(const Scene& s, const std::string& json, double left, double right) {
  const Results a = rescale_results(json, {{"left", left}, {"right", right}});
  const Results b = traced(dimmed(s, left, right), "on");
  const std::string at = " at " + std::to_string(left) + ", " + std::to_string(right);
  ASSERT_EQ(a.targets.size(), b.targets.size());
  for (std::size_t t = 0; t < b.targets.size(); ++t) {
    const TargetResult &x = a.targets[t], &y = b.targets[t];
    expect_close(x.estimate, y.estimate, y.name + at);
    for (std::size_t c = 0; c < y.cells.size(); ++c) {
      expect_close(x.cells[c], y.cells[c], y.name + " cell " + std::to_string(c) + at);
    }
    for (std::size_t g = 0; g < y.contributions.size(); ++g) {
      const Contribution &p = x.contributions[g], &q = y.contributions[g];
      EXPECT_EQ(p.photon_light, q.photon_light);
      ASSERT_EQ(p.direct.size(), q.direct.size());
      for (std::size_t k = 0; k < q.direct.size(); ++k) {
        EXPECT_NEAR(p.direct[k].lux, q.direct[k].lux, 1e-12 * q.direct[k].lux) << y.name << at;
        EXPECT_NEAR(p.direct[k].variance_lx2, q.direct[k].variance_lx2,
                    1e-12 * q.direct[k].variance_lx2)
            << y.name << at;
        EXPECT_EQ(p.direct[k].lit, q.direct[k].lit);
      }
    }
  }
  EXPECT_EQ(a.verdict, b.verdict) << at;
}

TEST(GroupsNextEvent, ContributionsCarryEachGroupsDirectParts) {
  const Results r = traced(judged_room(), "on");
  for (const TargetResult& t : r.targets) {
    ASSERT_EQ(t.contributions.size(), 2u);
    double parts = 0.0;
    for (const Contribution& c : t.contributions) {
      EXPECT_EQ(c.photon_light, Contribution::PhotonLight::Reflected) << t.name;
      ASSERT_EQ(c.direct.size(), c.tallies.size()) << t.name;  // whole target, then cells
      parts += c.estimate.mean;
    }
    EXPECT_NEAR(parts, t.estimate.mean, 1e-12 * t.estimate.mean) << t.name;
    // Under the spots most of the desk's light is direct: a rescale that dropped the direct
    // parts would miss it.
    EXPECT_GT(t.contributions[0].direct[0].lux, 0.3 * t.contributions[0].estimate.mean);
  }
  const auto doc = nlohmann::json::parse(results_to_json(r));
  const auto& part = doc["targets"][1]["contributions"]["left"];
  EXPECT_EQ(part["photon_light"], "reflected");
  EXPECT_EQ(part["direct"]["lit"], r.targets[1].contributions[0].direct[0].lit);
  EXPECT_TRUE(part["cells"][0].contains("direct"));
  // The photons alone: no direct parts, the layout as before next-event estimation.
  const auto off = nlohmann::json::parse(results_to_json(traced(judged_room(), "off")));
  EXPECT_FALSE(off["targets"][1]["contributions"]["left"].contains("photon_light"));
  EXPECT_FALSE(off["targets"][1]["contributions"]["left"].contains("direct"));
  EXPECT_FALSE(off["targets"][1]["contributions"]["left"]["cells"][0].contains("direct"));
}

TEST(GroupsNextEvent, FactorOneGivesTheRunBitForBit) {
  for (const Scene& s : {judged_room(), open_plane()}) {
    const std::string json = results_to_json(traced(s, "on"));
    EXPECT_EQ(targets(rescale_results_json(json, {})), targets(json));
    const auto ones =
        nlohmann::json::parse(rescale_results_json(json, {{"left", 1.0}, {"right", 1.0}}));
    EXPECT_EQ(ones["targets"], targets(json));
    EXPECT_EQ(ones["effects"], nlohmann::json::parse(json)["effects"]);  // the trace's
  }
  // Nothing reflects in the open plane: the parts are the direct parts alone.
  const Results open = traced(open_plane(), "on");
  for (const Contribution& c : open.targets[0].contributions) {
    EXPECT_EQ(c.photon_light, Contribution::PhotonLight::None);
    EXPECT_EQ(c.estimate.mean, c.direct[0].lux);
  }
}

TEST(GroupsNextEvent, DimmedEqualsARunTracedAtTheDimmedFluxes) {
  for (const Scene& s : {judged_room(), open_plane()}) {
    const std::string json = results_to_json(traced(s, "on"));
    expect_rescaled_is_traced(s, json, 0.5, 4.0);
    expect_rescaled_is_traced(s, json, 0.3, 0.7);
    // A rescaled result rescales again (its direct parts dimmed): in two steps as in one.
    const std::string once = rescale_results_json(json, {{"left", 0.5}, {"right", 4.0}});
    const std::string half = rescale_results_json(json, {{"left", 0.5}});
    EXPECT_EQ(targets(rescale_results_json(half, {{"right", 4.0}})), targets(once));
  }
}

// A group switched off leaves exactly the other group's part, direct part included.
TEST(GroupsNextEvent, AGroupAtZeroLeavesTheOthersPart) {
  const Results r = traced(judged_room(), "on");
  const Results off = rescale_results(results_to_json(r), {{"right", 0.0}});
  for (std::size_t t = 0; t < r.targets.size(); ++t) {
    const Estimate &e = off.targets[t].estimate, &left = r.targets[t].contributions[0].estimate;
    EXPECT_EQ(e.mean, left.mean);
    EXPECT_EQ(e.ci_low, left.ci_low);
    EXPECT_EQ(e.ci_high, left.ci_high);
    for (const DirectLight& d : off.targets[t].contributions[1].direct) EXPECT_EQ(d.lux, 0.0);
  }
}

// Results of runs without next-event estimation (as every file written before it) rescale as
// they always did: from the tallies alone, bit for bit at factor 1.
TEST(GroupsNextEvent, ResultsWithoutDirectPartsRescaleAsBefore) {
  const std::string json = results_to_json(traced(judged_room(), "off"));
  EXPECT_EQ(targets(rescale_results_json(json, {})), targets(json));
  const Results a = rescale_results(json, {{"left", 0.5}, {"right", 4.0}});
  const Results b = traced(dimmed(judged_room(), 0.5, 4.0), "off");
  for (std::size_t t = 0; t < b.targets.size(); ++t) {
    expect_close(a.targets[t].estimate, b.targets[t].estimate, b.targets[t].name);
  }
}

TEST(GroupsNextEvent, InconsistentDirectPartsAreRefusedNamingTheField) {
  const auto doc = nlohmann::json::parse(results_to_json(traced(judged_room(), "on")));
  auto message = [](const nlohmann::json& d) {
    return input_error_of([&] { rescale_results(d.dump(), {{"left", 0.5}}, "r.json"); });
  };
  auto edited = [&](auto change) {
    nlohmann::json d = doc;
    change(d["targets"][1]["contributions"]["left"]);
    return message(d);
  };
  const auto has = [](const std::string& m, const std::string& part) {
    return m.find(part) != std::string::npos;
  };
  std::string m = edited([](nlohmann::json& c) { c.erase("direct"); });  // its cells keep theirs
  EXPECT_TRUE(has(m, "targets[1].contributions.left") && has(m, "direct")) << m;
  m = edited([](nlohmann::json& c) { c["cells"][2].erase("direct"); });
  EXPECT_TRUE(has(m, "cells")) << m;
  m = edited([](nlohmann::json& c) { c["photon_light"] = "some"; });
  EXPECT_TRUE(has(m, "photon_light") && has(m, "\"reflected\" or \"none\"")) << m;
  m = edited([](nlohmann::json& c) { c.erase("photon_light"); });  // direct without it
  EXPECT_TRUE(has(m, "photon_light")) << m;
  m = edited([](nlohmann::json& c) { c["photon_light"] = "none"; });  // differs from target 0
  EXPECT_TRUE(has(m, "targets[1].contributions.left.photon_light")) << m;
  m = edited([](nlohmann::json& c) { c["direct"]["variance_lx2"] = -1.0; });
  EXPECT_TRUE(has(m, "variance_lx2")) << m;
  EXPECT_EQ(message(doc), "no error");
}

}  // namespace
}  // namespace lightsolver::test
