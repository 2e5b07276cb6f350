#pragma once
// One reusable command buffer and its fence (Kompute's "Sequence"): record, submit, wait.
// Each submission is waited for, so a batch never outlives its buffers and errors such as a lost
// device surface at the call that caused them.
#include <vulkan/vulkan.h>

#include <cstddef>

#include "vulkan/buffer.hpp"
#include "vulkan/context.hpp"

namespace lightsolver::vkw {

class Sequence {
 public:
  explicit Sequence(const Context& ctx);
  ~Sequence();
  Sequence(const Sequence&) = delete;
  Sequence& operator=(const Sequence&) = delete;

  /// Resets the command buffer and starts recording.
  VkCommandBuffer begin();
  /// Ends recording, submits and waits; throws std::runtime_error naming `what` on failure.
  void submit_and_wait(const char* what);

 private:
  const Context& ctx_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
};

/// Makes earlier compute/transfer writes visible to later compute, transfer, indirect-dispatch
/// and host access.
void memory_barrier(VkCommandBuffer cmd);

/// Copies `bytes` into `dst`: directly when it is mapped, otherwise through a staging buffer.
void upload(const Context& ctx, Buffer& dst, const void* data, std::size_t bytes);

}  // namespace lightsolver::vkw
