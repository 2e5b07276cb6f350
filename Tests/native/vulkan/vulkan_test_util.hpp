#pragma once
// Shared by the Vulkan tests: a fixture that fails a test on any validation-layer message, and a
// helper that runs one test kernel over host-visible buffers.
#include <gtest/gtest.h>

#include <cstdlib>
#include <span>
#include <vector>

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

}  // namespace lightsolver::test
