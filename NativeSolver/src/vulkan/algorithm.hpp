#pragma once
// A compute pipeline bound to its buffers (Kompute's "Algorithm"): shader module, descriptor set
// with one storage buffer per binding, push constants and specialisation constants.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <vector>

#include "vulkan/buffer.hpp"
#include "vulkan/context.hpp"

namespace lightsolver::vkw {

/// A 32-bit specialisation constant (bools are VkBool32).
struct SpecConstant {
  std::uint32_t id;
  std::uint32_t value;
};

class Algorithm {
 public:
  /// buffers[i] is bound to set 0, binding i. `push_bytes` is the push-constant block size.
  Algorithm(const Context& ctx, std::span<const std::uint32_t> spirv,
            const std::vector<const Buffer*>& buffers, std::uint32_t push_bytes,
            const std::vector<SpecConstant>& spec = {});
  ~Algorithm();
  Algorithm(const Algorithm&) = delete;
  Algorithm& operator=(const Algorithm&) = delete;

  /// Records bind + push constants + vkCmdDispatch(groups, 1, 1).
  void record(VkCommandBuffer cmd, std::uint32_t groups, const void* push) const;
  /// Records bind + push constants + vkCmdDispatchIndirect reading the group counts from `args`
  /// at `offset` (a VkDispatchIndirectCommand written by an earlier dispatch).
  void record_indirect(VkCommandBuffer cmd, const Buffer& args, VkDeviceSize offset,
                       const void* push) const;

 private:
  void bind(VkCommandBuffer cmd, const void* push) const;
  void create_layouts(std::size_t bindings);
  void create_pipeline(std::span<const std::uint32_t> spirv, const std::vector<SpecConstant>& spec);
  void write_descriptors(const std::vector<const Buffer*>& buffers);
  void release() noexcept;

  VkDevice device_;
  std::uint32_t push_bytes_;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkPipelineLayout pipeline_layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
};

}  // namespace lightsolver::vkw
