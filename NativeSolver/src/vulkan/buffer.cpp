#include "vulkan/buffer.hpp"

#include <utility>

#include "vulkan/vk_check.hpp"

namespace lightsolver::vkw {
namespace {

std::uint32_t pick_memory(const Context& ctx, std::uint32_t bits, MemoryKind kind) {
  constexpr VkMemoryPropertyFlags host =
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  switch (kind) {
    case MemoryKind::Device:
      return ctx.memory_type(bits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0);
    case MemoryKind::Upload:
      return ctx.memory_type(bits, host, host);
    case MemoryKind::Readback:
      return ctx.memory_type(bits, host | VK_MEMORY_PROPERTY_HOST_CACHED_BIT, host);
  }
  return 0;
}

}  // namespace

Buffer::Buffer(const Context& ctx, VkDeviceSize bytes, MemoryKind kind, std::string name)
    : device_(ctx.device()), size_(bytes), name_(std::move(name)) {
  try {
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = bytes;
    info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                 VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    check(vkCreateBuffer(device_, &info, nullptr, &buffer_), ("creating buffer " + name_).c_str());
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device_, buffer_, &req);
    const std::uint32_t type = pick_memory(ctx, req.memoryTypeBits, kind);
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = type;
    const std::string what =
        "allocating " + std::to_string(req.size >> 20) + " MiB for buffer " + name_;
    check(vkAllocateMemory(device_, &alloc, nullptr, &memory_), what.c_str());
    check(vkBindBufferMemory(device_, buffer_, memory_, 0), ("binding buffer " + name_).c_str());
    constexpr VkMemoryPropertyFlags coherent =
        VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    if ((ctx.memory_flags(type) & coherent) == coherent) {  // no flushes needed
      check(vkMapMemory(device_, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_),
            ("mapping buffer " + name_).c_str());
    }
  } catch (...) {
    release();
    throw;
  }
}

Buffer::Buffer(Buffer&& o) noexcept
    : device_(o.device_),
      buffer_(std::exchange(o.buffer_, VK_NULL_HANDLE)),
      memory_(std::exchange(o.memory_, VK_NULL_HANDLE)),
      size_(o.size_),
      mapped_(std::exchange(o.mapped_, nullptr)),
      name_(std::move(o.name_)) {}

Buffer& Buffer::operator=(Buffer&& o) noexcept {
  if (this != &o) {
    release();
    device_ = o.device_;
    buffer_ = std::exchange(o.buffer_, VK_NULL_HANDLE);
    memory_ = std::exchange(o.memory_, VK_NULL_HANDLE);
    size_ = o.size_;
    mapped_ = std::exchange(o.mapped_, nullptr);
    name_ = std::move(o.name_);
  }
  return *this;
}

Buffer::~Buffer() { release(); }

void Buffer::release() noexcept {
  if (mapped_) vkUnmapMemory(device_, memory_);
  if (buffer_) vkDestroyBuffer(device_, buffer_, nullptr);
  if (memory_) vkFreeMemory(device_, memory_, nullptr);
  mapped_ = nullptr;
  buffer_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
}

}  // namespace lightsolver::vkw
