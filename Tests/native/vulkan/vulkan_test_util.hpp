#pragma once
// Shared by the Vulkan tests: a fixture that fails a test on any validation-layer message, and a
// helper that runs one test kernel over host-visible buffers.
#include <gtest/gtest.h>

#include <cstdlib>
#include <span>
#include <string>
#include <vector>

#include "native/core/scene_builders.hpp"

#include "vulkan/algorithm.hpp"
#include "vulkan/buffer.hpp"
#include "vulkan/context.hpp"
#include "vulkan/sequence.hpp"
#include "vulkan/vulkan_backend.hpp"

namespace lightsolver::test {

class VulkanTest : public ::testing::Test {
 protected:
  void SetUp() override { before_ = detail::vulkan_validation_message_count(); }
  void TearDown() override {
    EXPECT_EQ(detail::vulkan_validation_message_count(), before_)
        << "Vulkan validation layer reported problems (see stderr)";
  }

 private:
  std::size_t before_ = 0;
};

/// Dispatches `spirv` once with `threads` invocations (64 per group) and waits.
inline void run_kernel(const vkw::Context& ctx, std::span<const std::uint32_t> spirv,
                       const std::vector<const vkw::Buffer*>& buffers, const void* push,
                       std::uint32_t push_bytes, std::uint32_t threads) {
  const vkw::Algorithm kernel(ctx, spirv, buffers, push_bytes);
  vkw::Sequence seq(ctx);
  VkCommandBuffer cmd = seq.begin();
  kernel.record(cmd, (threads + 63) / 64, push);
  vkw::memory_barrier(cmd);
  seq.submit_and_wait("running a test kernel");
}

/// Two mirrors 4.2 m apart (floor and ceiling, 100 m wide) with 40 one-cell grids between them,
/// facing up and down in turn: specular paths that cross many bins and overflow the kernel's
/// register slots, the same to the bit on both backends for one seed. No light yet.
inline Scene mirror_slab_with_grids() {
  Scene s;
  add_material(s, "mirror", Material::Type::Mirror, 0.9);
  s.meshes.push_back(quad_mesh("floor", 0, {-50, -50, 0}, {100, 0, 0}, {0, 100, 0}));
  s.meshes.push_back(quad_mesh("ceiling", 0, {-50, -50, 4.2}, {0, 100, 0}, {100, 0, 0}));
  for (int k = 0; k < 40; ++k) {
    const double z = 0.1 * (k + 1);
    if (k % 2) {
      s.targets.push_back(
          grid("up" + std::to_string(k), {-5, -5, z}, {10, 0, 0}, {0, 10, 0}, 1, 1));
    } else {
      s.targets.push_back(
          grid("dn" + std::to_string(k), {-5, -5, z}, {0, 10, 0}, {10, 0, 0}, 1, 1));
    }
  }
  return s;
}

}  // namespace lightsolver::test
