// Simulation: changes between runs (the optimizer's inner loop) give the same answers as
// scenes built with the change from the start.
#include "lightsolver/simulation.hpp"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "run_facts.hpp"
#include "scene_builders.hpp"

namespace lightsolver::test {
namespace {

TEST(Simulation, MovedMeshMatchesASceneBuiltThere) {
  Simulation::Options opt;
  opt.movable_meshes = {"block"};
  Simulation sim(room_with_block(dvec3(0)), opt);
  SolveOptions o;
  o.photons = 400'000;
  const Results before = sim.run(o);
  const dvec3 move(3.0, 0.0, 0.0);  // under the spot
  sim.set_mesh_transform(1, glm::translate(glm::dmat4(1.0), move));
  EXPECT_GT(sim.pending_update_seconds(), 0.0);
  const Results moved = sim.run(o);
  EXPECT_EQ(sim.pending_update_seconds(), 0.0);
  const Results fresh = solve(room_with_block(move), o);
  EXPECT_GT(moved.targets[0].estimate.mean, 3 * before.targets[0].estimate.mean);
  for (std::size_t t = 0; t < 2; ++t) {
    expect_same_within(moved.targets[t].estimate, fresh.targets[t].estimate, "target");
  }
  for (std::size_t c = 0; c < moved.targets[1].cells.size(); ++c) {
    expect_same_within(moved.targets[1].cells[c], fresh.targets[1].cells[c], "cell");
  }
  // Rotating it half a turn about its own vertical axis and back restores the first answer.
  const dvec3 centre(1.5 + 3.0, 1.5, 0);
  glm::dmat4 turn = glm::translate(glm::dmat4(1.0), centre) *
                    glm::rotate(glm::dmat4(1.0), glm::pi<double>(), dvec3(0, 0, 1)) *
                    glm::translate(glm::dmat4(1.0), -centre) *
                    glm::translate(glm::dmat4(1.0), move);
  sim.set_mesh_transform(1, turn);
  expect_same_within(sim.run(o).targets[0].estimate, fresh.targets[0].estimate, "rotated");
}

TEST(Simulation, MovedLuminaireIsBitIdenticalToAFreshScene) {
  Simulation sim(room_with_block(dvec3(0)));
  Luminaire moved = sim.scene().luminaires[0];
  moved.position = {1.5, 1.5, 2.9};
  moved.direction = {0, 0, -2};  // normalised by validation, as when loaded
  sim.set_luminaire(0, moved);
  Scene fresh = room_with_block(dvec3(0));
  fresh.luminaires[0].position = {1.5, 1.5, 2.9};
  SolveOptions o;
  o.photons = 200'000;
  Results a = sim.run(o), b = solve(fresh, o);
  // Both scenes are built in memory: no scene hash either way.
  EXPECT_EQ(results_to_json(without_run_facts(a)), results_to_json(without_run_facts(b)));
}

// Photon i is photon i: refining a kept run continues it, equal to one run of all the photons.
TEST(Simulation, RefineContinuesTheKeptPhotonsBitForBit) {
  Simulation sim(room_with_block(dvec3(0)));
  SolveOptions o;
  o.photons = 100'000;
  sim.run(o);
  EXPECT_EQ(sim.kept_photons(), 100'000u);
  o.photons = 250'000;
  std::uint64_t first_report = 0;
  Results resumed = sim.refine(o, [&](std::uint64_t done, std::uint64_t) {
    if (first_report == 0) first_report = done;
    return true;
  });
  EXPECT_GT(first_report, 100'000u);  // the first batch started where the kept photons end
  Results one = solve(room_with_block(dvec3(0)), o);
  EXPECT_EQ(results_to_json(without_run_facts(resumed)), results_to_json(without_run_facts(one)));
  // A change discards the kept photons: refine starts again at photon 0.
  Luminaire brighter = sim.scene().luminaires[0];
  brighter.flux_lm *= 2;
  sim.set_luminaire(0, brighter);
  EXPECT_EQ(sim.kept_photons(), 0u);
  Results again = sim.refine(o), fresh = sim.run(o);
  EXPECT_EQ(results_to_json(without_run_facts(again)), results_to_json(without_run_facts(fresh)));
  o.photons.reset();
  EXPECT_THROW(sim.refine(o), InputError);  // the total is required
}

TEST(Simulation, RejectsBadChangesAndKeepsItsState) {
  Simulation::Options opt;
  opt.movable_meshes = {"block"};
  Simulation sim(room_with_block(dvec3(0)), opt);
  EXPECT_THROW(sim.set_mesh_transform(0, glm::dmat4(1.0)), InputError);  // room not movable
  EXPECT_THROW(sim.set_mesh_transform(1, glm::scale(glm::dmat4(1.0), dvec3(2))), InputError);
  Luminaire bad = sim.scene().luminaires[0];
  bad.flux_lm = -1;
  EXPECT_THROW(sim.set_luminaire(0, bad), InputError);
  EXPECT_EQ(sim.scene().luminaires[0].flux_lm, 2000);
  EXPECT_THROW(sim.set_luminaire(5, bad), InputError);
  opt.movable_meshes = {"sofa"};
  EXPECT_THROW(Simulation(room_with_block(dvec3(0)), opt), InputError);
}

}  // namespace
}  // namespace lightsolver::test
