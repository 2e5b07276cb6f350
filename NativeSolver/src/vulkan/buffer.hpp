#pragma once
// A storage buffer with its own memory allocation (one per buffer: this backend needs about ten
// long-lived buffers, far below maxMemoryAllocationCount). Host-visible memory stays mapped.
#include <vulkan/vulkan.h>

#include <cstddef>
#include <string>

#include "vulkan/context.hpp"

namespace lightsolver::vkw {

enum class MemoryKind {
  Device,    ///< fastest for the device; mapped too where the device shares host memory
  Upload,    ///< host-visible, coherent: staging for uploads
  Readback,  ///< host-visible, cached where possible: results read by the CPU
};

class Buffer {
 public:
  /// `name` appears in error messages. Usage: storage, transfer source and destination.
  Buffer(const Context& ctx, VkDeviceSize bytes, MemoryKind kind, std::string name);
  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  const std::string& name() const { return name_; }
  /// Host pointer to the whole buffer, or nullptr when the memory is not host-visible.
  void* mapped() const { return mapped_; }

 private:
  void release() noexcept;

  VkDevice device_ = VK_NULL_HANDLE;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  void* mapped_ = nullptr;
  std::string name_;
};

}  // namespace lightsolver::vkw
