// Movable meshes on the Vulkan backend (two-level tracing: a BVH per movable mesh, placed by an
// instance record that set_mesh_transform re-uploads): a moved mesh lights like a scene built
// there, and traces the same paths as Embree's instances for the same seed.
#include <glm/gtc/matrix_transform.hpp>

#include "lightsolver/simulation.hpp"
#include "lightsolver/solver.hpp"
#include "native/core/scene_builders.hpp"
#include "vulkan_test_util.hpp"

namespace lightsolver::test {
namespace {

void expect_same_hits(const Results& e, const Results& v, const std::string& what) {
  EXPECT_NEAR(double(v.ray_segments), double(e.ray_segments), 1e-3 * double(e.ray_segments))
      << what;
  for (std::size_t t = 0; t < e.targets.size(); ++t) {
    const double he = double(e.targets[t].estimate.hits);
    EXPECT_NEAR(double(v.targets[t].estimate.hits), he, 1e-3 * he + 2)
        << what << ": " << e.targets[t].name;
  }
}

const dvec3 kMove(3.0, 0.0, 0.0);  // under the spot

// Half a turn about the block's own vertical axis, after the move.
glm::dmat4 turned() {
  const dvec3 centre(1.5 + 3.0, 1.5, 0);
  return glm::translate(glm::dmat4(1.0), centre) *
         glm::rotate(glm::dmat4(1.0), glm::pi<double>(), dvec3(0, 0, 1)) *
         glm::translate(glm::dmat4(1.0), -centre) * glm::translate(glm::dmat4(1.0), kMove);
}

using VulkanMovableTest = VulkanTest;

// Tests/native/core/simulation_test.cpp MovedMeshMatchesASceneBuiltThere, on "vulkan".
TEST_F(VulkanMovableTest, MovedMeshMatchesASceneBuiltThere) {
  Simulation::Options opt;
  opt.backend = "vulkan";
  opt.movable_meshes = {"block"};
  Simulation sim(room_with_block(dvec3(0)), opt);
  SolveOptions o;
  o.photons = 100'000;
  o.backend = "vulkan";
  const Results before = sim.run(o);
  ASSERT_EQ(before.backend, "vulkan");
  sim.set_mesh_transform(1, glm::translate(glm::dmat4(1.0), kMove));
  const Results moved = sim.run(o);
  const Results fresh = solve(room_with_block(kMove), o);
  EXPECT_GT(moved.targets[0].estimate.mean, 3 * before.targets[0].estimate.mean);
  for (std::size_t t = 0; t < 2; ++t) {
    expect_same_within(moved.targets[t].estimate, fresh.targets[t].estimate, "target");
  }
  for (std::size_t c = 0; c < moved.targets[1].cells.size(); ++c) {
    expect_same_within(moved.targets[1].cells[c], fresh.targets[1].cells[c], "cell");
  }
  sim.set_mesh_transform(1, turned());
  expect_same_within(sim.run(o).targets[0].estimate, fresh.targets[0].estimate, "rotated");
}

// Same seed after each move (translation, then a 30-degree rotation): the instance transforms,
// world normals and hit points match embree_backend.cpp, so the hits agree like static scenes do.
TEST_F(VulkanMovableTest, SameSeedAsEmbreeAfterAMove) {
  Simulation::Options opt;
  opt.movable_meshes = {"block"};
  opt.backend = "embree";
  Simulation embree(room_with_block(dvec3(0)), opt);
  opt.backend = "vulkan";
  Simulation vulkan(room_with_block(dvec3(0)), opt);
  SolveOptions o;
  o.photons = 40'000;
  o.seed = 17;
  expect_same_hits(embree.run(o), vulkan.run(o), "in place");
  const dvec3 centre(1.5, 1.5, 0);  // a third of a turn: the block's faces change direction
  const glm::dmat4 rotated = glm::translate(glm::dmat4(1.0), centre + dvec3(2.2, 0.6, 0)) *
                             glm::rotate(glm::dmat4(1.0), glm::radians(30.0), dvec3(0, 0, 1)) *
                             glm::translate(glm::dmat4(1.0), -centre);
  for (const glm::dmat4& m : {glm::translate(glm::dmat4(1.0), kMove), rotated}) {
    embree.set_mesh_transform(1, m);
    vulkan.set_mesh_transform(1, m);
    expect_same_hits(embree.run(o), vulkan.run(o), "moved");
  }
}

TEST_F(VulkanMovableTest, RefusesToMoveAStaticMesh) {
  Simulation::Options opt;
  opt.backend = "vulkan";
  opt.movable_meshes = {"block"};
  Simulation sim(room_with_block(dvec3(0)), opt);
  EXPECT_THROW(sim.set_mesh_transform(0, glm::dmat4(1.0)), InputError);
}

}  // namespace
}  // namespace lightsolver::test
