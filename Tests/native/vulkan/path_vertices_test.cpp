// Backend::path_vertices on the Vulkan backend (Shaders/path_vertices.comp) against the Embree
// backend's, vertex for vertex for one seed, and a run that connects reflected light to grids
// on Vulkan against the same run on Embree.
#include <algorithm>
#include <cmath>

#include "embree/embree_backend.hpp"
#include "model/backend.hpp"
#include "model/prepared_scene.hpp"
#include "native/core/scene_builders.hpp"
#include "vulkan_test_util.hpp"

namespace lightsolver::test {
namespace {

using detail::PathVertex;

// Each path's vertices: [starts[p], starts[p + 1]).
std::vector<std::size_t> starts(const std::vector<PathVertex>& v, std::uint64_t paths) {
  std::vector<std::size_t> s(paths + 1, 0);
  for (const PathVertex& x : v) ++s[x.path + 1];
  for (std::uint64_t p = 0; p < paths; ++p) s[p + 1] += s[p];
  return s;
}

// Compares the two backends' vertices path by path. Both draw the same Philox numbers and
// share the emission and sampling code, but intersect with their own float arithmetic (Embree's
// and bvh.glsl's): hit points agree to float rounding, within kTolerance after bounces that
// magnify it (a hit point's error moves the next: grazing hits near the room's corners
// stretch it), and a hit within rounding of a triangle's edge may end a path on one backend and
// go on on the other. So: vertex lists in photon order, as many vertices per path (absorption
// is by the shared random numbers alone), the first `prefix` of each within kTolerance with the
// same normals and reflectances, and at most 1 in 1000 paths differing. Returns the vertices
// compared.
std::size_t expect_same_paths(const std::vector<PathVertex>& e, const std::vector<PathVertex>& v,
                              std::uint64_t paths, std::size_t prefix) {
  constexpr float kTolerance = 1e-3f;  // metres
  EXPECT_TRUE(std::is_sorted(v.begin(), v.end(),
                             [](const auto& a, const auto& b) { return a.path < b.path; }));
  const auto se = starts(e, paths), sv = starts(v, paths);
  std::uint64_t differing = 0;
  std::size_t compared = 0;
  for (std::uint64_t p = 0; p < paths; ++p) {
    const std::size_t ne = se[p + 1] - se[p], nv = sv[p + 1] - sv[p];
    bool same = ne == nv;
    for (std::size_t k = 0; same && k < std::min(ne, prefix); ++k) {
      const PathVertex &a = e[se[p] + k], &b = v[sv[p] + k];
      same = glm::length(a.origin - b.origin) < kTolerance && a.normal == b.normal &&
             a.reflectance == b.reflectance;
      compared += same;
    }
    differing += !same;
  }
  EXPECT_LE(differing * 1000, paths) << differing << " of " << paths << " paths differ";
  return compared;
}

using VulkanPathVerticesTest = VulkanTest;

TEST_F(VulkanPathVerticesTest, SameVerticesAsEmbreeInTheBoxRoom) {
  // The table is black (reflectance 0): a path ends there without a vertex on both backends.
  const detail::PreparedScene p = detail::prepare(box_room(4, true));
  const auto embree = detail::make_embree_backend(p);
  const auto vulkan = detail::make_vulkan_backend(p);
  ASSERT_TRUE(vulkan->traces_path_vertices());
  // More paths than one submission (16384), from an offset, in a stream of its own.
  constexpr std::uint64_t kFirst = 1000, kPaths = 20'000, kSeed = 7;
  constexpr std::uint32_t kStream = 0x40000000u;
  std::vector<PathVertex> e, v;
  embree->path_vertices(0, kFirst, kPaths, kSeed, kStream, e);
  vulkan->path_vertices(0, kFirst, kPaths, kSeed, kStream, v);
  ASSERT_GT(e.size(), kPaths / 2);  // reflectance 0.5: about one vertex per path
  EXPECT_GT(expect_same_paths(e, v, kPaths, kPaths), e.size() * 99 / 100);
  // Appended after what `out` held, paths numbered from the request's first photon again.
  std::vector<PathVertex> again(3);
  vulkan->path_vertices(0, kFirst, 10, kSeed, kStream, again);
  ASSERT_EQ(again.size(), 3 + starts(v, kPaths)[10]);
  for (std::size_t i = 3; i < again.size(); ++i) EXPECT_EQ(again[i].path, v[i - 3].path);
}

TEST_F(VulkanPathVerticesTest, LongPathsOverflowingTheBufferAreTracedInParts) {
  // Reflectance 0.95: about 19 vertices per path, more than the 8 a submission holds on
  // average, so chunks are split; the answer must not change.
  Scene s = box_room(4);
  s.materials[0].reflectance = 0.95;
  const detail::PreparedScene p = detail::prepare(s);
  const auto embree = detail::make_embree_backend(p);
  const auto vulkan = detail::make_vulkan_backend(p);
  constexpr std::uint64_t kPaths = 20'000, kSeed = 3;
  std::vector<PathVertex> e, v;
  embree->path_vertices(0, 0, kPaths, kSeed, 1, e);
  vulkan->path_vertices(0, 0, kPaths, kSeed, 1, v);
  ASSERT_GT(e.size(), 10 * kPaths);
  // Long paths carry rounding further (1 in 13 drifts past 1 mm by its 64th vertex): their
  // first 8 vertices are compared, and all counts.
  const auto se = starts(e, kPaths);
  std::size_t comparable = 0;
  for (std::uint64_t p = 0; p < kPaths; ++p)
    comparable += std::min<std::size_t>(se[p + 1] - se[p], 8);
  EXPECT_GT(expect_same_paths(e, v, kPaths, 8), comparable * 99 / 100);
}

TEST_F(VulkanPathVerticesTest, PathsOfThousandsOfBouncesMatchAcrossTheLoopLimit) {
  // Reflectance 0.9995: about 1000 vertices per path (capped at 3500), which on lavapipe
  // (Mesa 22.3) runs into its loop limit (trace.comp) for most paths: they are traced again
  // alone, and what they gave in the first pass is dropped (without that, 330 of these 400
  // paths differed), so the vertex counts still match Embree's path for path. Much longer
  // paths are cut even alone (PathsCutEvenAlone... below).
  Scene s = box_room(4);
  s.materials[0].reflectance = 0.9995;
  s.settings.max_bounces = 3500;
  const detail::PreparedScene p = detail::prepare(s);
  const auto embree = detail::make_embree_backend(p);
  const auto vulkan = detail::make_vulkan_backend(p);
  constexpr std::uint64_t kPaths = 400, kSeed = 9;
  std::vector<PathVertex> e, v;
  embree->path_vertices(0, 0, kPaths, kSeed, 2, e);
  vulkan->path_vertices(0, 0, kPaths, kSeed, 2, v);
  ASSERT_GT(e.size(), 300 * kPaths);  // more than one submission holds: split as well
  const auto se = starts(e, kPaths);
  std::size_t comparable = 0;
  for (std::uint64_t p = 0; p < kPaths; ++p) {
    comparable += std::min<std::size_t>(se[p + 1] - se[p], 8);
  }
  EXPECT_GT(expect_same_paths(e, v, kPaths, 8), comparable * 99 / 100);
}

Results run_connected(const std::string& backend, std::uint64_t seed) {
  Scene s = box_room(8);
  validate(s);
  SolveOptions o;
  o.backend = backend;
  o.photons = 100'000;
  o.seed = seed;
  o.confidence = 0.95;
  o.next_event = "on";
  o.connect_reflections = "on";
  return solve(s, o);
}

// The connection needs path_vertices: on Vulkan it now runs (intervals as narrow as Embree's,
// which photons alone would not give: reflection_connection_test.cpp finds them 30% wider and
// more), and with the same seed the two backends agree cell by cell.
TEST_F(VulkanPathVerticesTest, ConnectedRunAgreesWithEmbree) {
  const Results e = run_connected("embree", 11);
  const Results v = run_connected("vulkan", 11);
  ASSERT_EQ(v.targets[0].cells.size(), 64u);
  const auto [width_v, width_e] = expect_cells_agree(v, e);
  EXPECT_LT(width_v, 1.1 * width_e);
  EXPECT_GT(width_v, 0.9 * width_e);
  expect_same_within(v.targets[0].estimate, e.targets[0].estimate, "whole grid");
  for (std::size_t k = 0; k < 64; ++k) {
    const Estimate& c = v.targets[0].cells[k];
    EXPECT_TRUE(std::isfinite(c.mean) && c.ci_low <= c.mean && c.mean <= c.ci_high) << k;
  }
}

// The box room at reflectance 0.9995 with max_bounces 6000: about 2000 vertices per path, and
// on lavapipe (Mesa 22.3) a path of that length runs past its loop limit even traced alone.
Scene nearly_white_box() {
  Scene s = box_room(4);
  s.materials[0].reflectance = 0.9995;
  s.settings.max_bounces = 6000;
  validate(s);
  return s;
}

// Whether the device (Backend::device(), a run's provenance) has lavapipe's loop limit.
bool loop_limited(const std::string& device) {
  return device.find("llvmpipe") != std::string::npos;
}

// Such paths cannot be traced on this device: the call says so with its own error type (which
// the connection's "auto" catches), never with vertices missing. A real GPU has no such limit.
TEST_F(VulkanPathVerticesTest, PathsCutEvenAloneThrowADeviceLimitError) {
  const detail::PreparedScene p = detail::prepare(nearly_white_box());
  const auto vulkan = detail::make_vulkan_backend(p);
  std::vector<PathVertex> v;
  if (!loop_limited(vulkan->device())) {
    vulkan->path_vertices(0, 0, 64, 4, 2, v);
    GTEST_SKIP() << "no loop limit on " << vulkan->device();
  }
  EXPECT_THROW(vulkan->path_vertices(0, 0, 64, 4, 2, v), detail::DeviceLimitError);
}

Results run_nearly_white(const std::string& connect) {
  SolveOptions o;
  o.backend = "vulkan";
  o.photons = 1000;  // the fewest connections (16 cells x 512 paths x 2 rays) are within auto's
  o.seed = 5;
  o.next_event = "on";
  o.connect_reflections = connect;
  return solve(nearly_white_box(), o);
}

// Where the loop limit cuts connection paths even alone, "auto" does without the connection
// (the photons carry every reflected crossing, as with "off") and its effects list says why;
// "on" stops with an error that names both ways out.
TEST_F(VulkanPathVerticesTest, AutoDoesWithoutTheConnectionWhereTheLoopLimitCutsItsPaths) {
  const Results r = run_nearly_white("auto");
  const auto skipped =
      std::find_if(r.effects.skipped.begin(), r.effects.skipped.end(),
                   [](const SkippedEffect& e) { return e.effect == "reflection_connection"; });
  for (const Estimate& c : r.targets[0].cells) {
    EXPECT_TRUE(std::isfinite(c.mean) && c.ci_low <= c.mean && c.mean <= c.ci_high);
  }
  if (!r.provenance || !loop_limited(r.provenance->device)) {
    EXPECT_EQ(skipped, r.effects.skipped.end()) << "connected on a device without a loop limit";
    GTEST_SKIP() << "no loop limit on this device";
  }
  ASSERT_NE(skipped, r.effects.skipped.end()) << "auto connected paths the device cut";
  EXPECT_NE(skipped->reason.find("auto: Vulkan backend:"), std::string::npos) << skipped->reason;
  EXPECT_NE(skipped->reason.find("even traced alone"), std::string::npos) << skipped->reason;
  try {
    run_nearly_white("on");
    ADD_FAILURE() << "\"on\" connected paths the device cut";
  } catch (const detail::DeviceLimitError& e) {
    EXPECT_NE(std::string(e.what()).find("--backend embree, or connect_reflections"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace lightsolver::test
