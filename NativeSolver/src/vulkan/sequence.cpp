#include "vulkan/sequence.hpp"

#include <cstring>
#include <string>

#include "vulkan/vk_check.hpp"

namespace lightsolver::vkw {
namespace {

// Generous: a batch is sized to take well under a second; this only catches a hung device.
constexpr std::uint64_t kFenceTimeoutNs = 600'000'000'000ull;

}  // namespace

Sequence::Sequence(const Context& ctx) : ctx_(ctx) {
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = ctx.command_pool();
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  check(vkAllocateCommandBuffers(ctx.device(), &alloc, &cmd_), "allocating a command buffer");
  VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  const VkResult r = vkCreateFence(ctx.device(), &fence, nullptr, &fence_);
  if (r != VK_SUCCESS) {
    vkFreeCommandBuffers(ctx.device(), ctx.command_pool(), 1, &cmd_);
    fail(r, "creating a fence");
  }
}

Sequence::~Sequence() {
  vkDestroyFence(ctx_.device(), fence_, nullptr);
  vkFreeCommandBuffers(ctx_.device(), ctx_.command_pool(), 1, &cmd_);
}

VkCommandBuffer Sequence::begin() {
  check(vkResetCommandBuffer(cmd_, 0), "resetting a command buffer");
  VkCommandBufferBeginInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  info.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(cmd_, &info), "recording commands");
  return cmd_;
}

void Sequence::submit_and_wait(const char* what) {
  check(vkEndCommandBuffer(cmd_), "recording commands");
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd_;
  check(vkQueueSubmit(ctx_.queue(), 1, &submit, fence_), what);
  check(vkWaitForFences(ctx_.device(), 1, &fence_, VK_TRUE, kFenceTimeoutNs), what);
  check(vkResetFences(ctx_.device(), 1, &fence_), what);
}

void memory_barrier(VkCommandBuffer cmd) {
  VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  b.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  b.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                    VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT |
                    VK_ACCESS_HOST_READ_BIT | VK_ACCESS_INDIRECT_COMMAND_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT |
                           VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
                       0, 1, &b, 0, nullptr, 0, nullptr);
}

void upload(const Context& ctx, Buffer& dst, const void* data, std::size_t bytes) {
  if (bytes == 0) return;
  if (dst.mapped()) {
    std::memcpy(dst.mapped(), data, bytes);
    return;
  }
  Buffer staging(ctx, bytes, MemoryKind::Upload, dst.name() + " (staging)");
  std::memcpy(staging.mapped(), data, bytes);
  Sequence seq(ctx);
  VkCommandBuffer cmd = seq.begin();
  const VkBufferCopy region{0, 0, bytes};
  vkCmdCopyBuffer(cmd, staging.handle(), dst.handle(), 1, &region);
  memory_barrier(cmd);
  seq.submit_and_wait(("uploading buffer " + dst.name()).c_str());
}

}  // namespace lightsolver::vkw
