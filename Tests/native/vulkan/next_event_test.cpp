// PreparedGroup::next_event on the Vulkan backend (trace.comp's first_bounce push constant): a
// group whose direct light is by next-event estimation deposits nothing before its photons'
// first scattering, exactly as the Embree backend (continue_path, cross_grids' first_bounce).
// The flag is set after the backends were built, as the coordinator does, and changed between
// runs.
#include "embree/embree_backend.hpp"
#include "model/backend.hpp"
#include "model/groups.hpp"
#include "model/prepared_scene.hpp"
#include "native/core/scene_builders.hpp"
#include "vulkan_test_util.hpp"

namespace lightsolver::test {
namespace {

detail::TallyBlock trace(detail::Backend& b, const detail::PreparedScene& p, std::uint64_t n,
                         std::uint64_t seed) {
  detail::TallyBlock t(p.groups.size() * p.bins.size());
  b.trace(detail::group_ranges(p.groups, 0, n), seed, t);
  return t;
}

void expect_equal(const detail::TallyBlock& a, const detail::TallyBlock& b,
                  const std::string& what) {
  ASSERT_EQ(a.bins.size(), b.bins.size());
  for (std::size_t i = 0; i < a.bins.size(); ++i) {
    EXPECT_EQ(a.bins[i].sum, b.bins[i].sum) << what << ", bin " << i;
    EXPECT_EQ(a.bins[i].sum_sq, b.bins[i].sum_sq) << what << ", bin " << i;
  }
  EXPECT_EQ(a.ray_segments, b.ray_segments) << what;
}

std::uint64_t total(const detail::TallyBlock& t, std::size_t first, std::size_t count) {
  std::uint64_t s = 0;
  for (std::size_t i = first; i < first + count; ++i) s += t.bins[i].sum;
  return s;
}

// Two mirrors 4.2 m apart with 40 grids between them and a mirror floor that is a surface
// target; two point lights in two groups. Specular paths: the same seed gives the same paths
// on both backends, to the bit (as PathsTouchingManyBinsKeepExactPerPathCounts).
Scene mirror_slab() {
  Scene s = mirror_slab_with_grids();
  s.targets.push_back(surface("floor", 0));
  s.luminaires.push_back(named(point_light({0.1, 0.2, 2.05}, 1000), "a", "a"));
  s.luminaires.push_back(named(point_light({-1.3, 0.7, 1.55}, 500), "b", "b"));
  validate(s);
  return s;
}

using VulkanNextEventTest = VulkanTest;

TEST_F(VulkanNextEventTest, SameTalliesAsEmbreeToTheBit) {
  detail::PreparedScene p = detail::prepare(mirror_slab());
  ASSERT_EQ(p.groups.size(), 2u);
  const std::size_t bins = p.bins.size();
  const auto embree = detail::make_embree_backend(p);
  const auto vulkan = detail::make_vulkan_backend(p);
  constexpr std::uint64_t kPhotons = 20'000, kSeed = 5;
  const detail::TallyBlock off = trace(*vulkan, p, kPhotons, kSeed);
  expect_equal(trace(*embree, p, kPhotons, kSeed), off, "next_event off");
  p.groups[0].next_event = true;
  const detail::TallyBlock on = trace(*vulkan, p, kPhotons, kSeed);
  expect_equal(trace(*embree, p, kPhotons, kSeed), on, "group a by next-event estimation");
  // Group a lost its direct crossings and floor hits, and only those: every bin has at most
  // what it had, far less in all. Group b is untouched, bin for bin.
  for (std::size_t i = 0; i < bins; ++i) EXPECT_LE(on.bins[i].sum, off.bins[i].sum) << i;
  EXPECT_LT(total(on, 0, bins), total(off, 0, bins) * 9 / 10);
  EXPECT_GT(total(on, 0, bins), 0u);  // the reflected light stays
  for (std::size_t i = bins; i < 2 * bins; ++i) {
    EXPECT_EQ(on.bins[i].sum, off.bins[i].sum) << i;
    EXPECT_EQ(on.bins[i].sum_sq, off.bins[i].sum_sq) << i;
  }
  EXPECT_EQ(on.ray_segments, off.ray_segments);  // the same paths, fewer deposits
  p.groups[0].next_event = false;                // read again at each run
  expect_equal(trace(*vulkan, p, kPhotons, kSeed), off, "next_event off again");
}

// next_event "auto" gives some targets back to the photons (direct_by_photons, the mesh and grid
// records' flags, uploaded again when they change): there group a deposits its bounce-0 light
// again, so those bins hold exactly what they held without next-event estimation, the others
// what they held with it; both backends to the bit.
TEST_F(VulkanNextEventTest, TargetsGivenBackToThePhotonsDepositBounceZero) {
  detail::PreparedScene p = detail::prepare(mirror_slab());
  const std::size_t bins = p.bins.size();
  const auto embree = detail::make_embree_backend(p);
  const auto vulkan = detail::make_vulkan_backend(p);
  constexpr std::uint64_t kPhotons = 20'000, kSeed = 5;
  const detail::TallyBlock off = trace(*vulkan, p, kPhotons, kSeed);
  p.groups[0].next_event = true;
  const detail::TallyBlock on = trace(*vulkan, p, kPhotons, kSeed);
  std::vector<bool> given(bins, false);
  for (detail::PreparedMesh& m : p.meshes) {
    if (m.bin < 0) continue;
    m.direct_by_photons = true;
    given[std::size_t(m.bin)] = true;
  }
  ASSERT_GE(p.grids.size(), 4u);
  for (std::size_t k = 0; k < p.grids.size(); k += 2) {
    detail::PreparedGrid& g = p.grids[k];
    g.direct_by_photons = true;
    for (std::uint32_t b = g.bin; b <= g.bin + g.nu * g.nv; ++b) given[b] = true;
  }
  const detail::TallyBlock mixed = trace(*vulkan, p, kPhotons, kSeed);
  expect_equal(trace(*embree, p, kPhotons, kSeed), mixed, "targets given back");
  std::size_t differ = 0;  // bins where group a's direct light mattered
  for (std::size_t i = 0; i < bins; ++i) {
    const detail::TallyBlock& want = given[i] ? off : on;
    EXPECT_EQ(mixed.bins[i].sum, want.bins[i].sum) << i;
    EXPECT_EQ(mixed.bins[i].sum_sq, want.bins[i].sum_sq) << i;
    differ += given[i] && off.bins[i].sum != on.bins[i].sum;
  }
  EXPECT_GT(differ, 4u);
  for (std::size_t i = bins; i < 2 * bins; ++i) EXPECT_EQ(mixed.bins[i].sum, off.bins[i].sum) << i;
  for (detail::PreparedMesh& m : p.meshes) m.direct_by_photons = false;
  for (detail::PreparedGrid& g : p.grids) g.direct_by_photons = false;
  expect_equal(trace(*vulkan, p, kPhotons, kSeed), on, "every target by shadow rays again");
}

// A black room: all light is direct, so a group by next-event estimation deposits nothing at
// all, on grids and surface targets alike, while the other group's tallies stay as they were.
TEST_F(VulkanNextEventTest, DirectOnlyLightLeavesNothingForThePhotons) {
  Scene s = grouped_room();
  s.materials[0].reflectance = 0.0;
  validate(s);
  detail::PreparedScene p = detail::prepare(s);
  ASSERT_EQ(p.groups.size(), 2u);
  const std::size_t bins = p.bins.size();
  const auto embree = detail::make_embree_backend(p);
  const auto vulkan = detail::make_vulkan_backend(p);
  const detail::TallyBlock off = trace(*vulkan, p, 20'000, 3);
  p.groups[1].next_event = true;
  const detail::TallyBlock on = trace(*vulkan, p, 20'000, 3);
  expect_equal(trace(*embree, p, 20'000, 3), on, "black room, group right by next-event");
  EXPECT_GT(total(off, bins, bins), 1000u);  // the point lit grid and desk directly ...
  EXPECT_EQ(total(on, bins, bins), 0u);      // ... and now leaves that to next-event estimation
  for (std::size_t i = 0; i < bins; ++i) {
    EXPECT_EQ(on.bins[i].sum, off.bins[i].sum) << i;
    EXPECT_EQ(on.bins[i].sum_sq, off.bins[i].sum_sq) << i;
  }
}

// A grey room: diffuse paths coincide except where a last-bit difference in sin/cos/sqrt tips a
// decision (VulkanBackendTest.SameSeedTracesTheSamePaths), so per bin within 1e-3 + 2 hits.
TEST_F(VulkanNextEventTest, GreyRoomAgreesWithEmbree) {
  detail::PreparedScene p = detail::prepare(grouped_room());
  const auto embree = detail::make_embree_backend(p);
  const auto vulkan = detail::make_vulkan_backend(p);
  p.groups[0].next_event = true;
  const detail::TallyBlock e = trace(*embree, p, 40'000, 9), v = trace(*vulkan, p, 40'000, 9);
  ASSERT_EQ(e.bins.size(), v.bins.size());
  for (std::size_t i = 0; i < e.bins.size(); ++i) {
    const double he = double(e.bins[i].sum);
    EXPECT_NEAR(double(v.bins[i].sum), he, 1e-3 * he + 2) << "bin " << i;
  }
  EXPECT_NEAR(double(v.ray_segments), double(e.ray_segments), 1e-3 * double(e.ray_segments));
}

}  // namespace
}  // namespace lightsolver::test
