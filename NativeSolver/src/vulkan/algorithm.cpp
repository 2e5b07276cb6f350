#include "vulkan/algorithm.hpp"

#include "vulkan/vk_check.hpp"

namespace lightsolver::vkw {

Algorithm::Algorithm(const Context& ctx, std::span<const std::uint32_t> spirv,
                     const std::vector<const Buffer*>& buffers, std::uint32_t push_bytes,
                     const std::vector<SpecConstant>& spec)
    : device_(ctx.device()), push_bytes_(push_bytes) {
  try {
    create_layouts(buffers.size());
    create_pipeline(spirv, spec);
    write_descriptors(buffers);
  } catch (...) {
    release();
    throw;
  }
}

Algorithm::~Algorithm() { release(); }

void Algorithm::release() noexcept {
  if (pool_) vkDestroyDescriptorPool(device_, pool_, nullptr);  // frees set_ too
  if (pipeline_) vkDestroyPipeline(device_, pipeline_, nullptr);
  if (pipeline_layout_) vkDestroyPipelineLayout(device_, pipeline_layout_, nullptr);
  if (set_layout_) vkDestroyDescriptorSetLayout(device_, set_layout_, nullptr);
  pool_ = VK_NULL_HANDLE;
  pipeline_ = VK_NULL_HANDLE;
  pipeline_layout_ = VK_NULL_HANDLE;
  set_layout_ = VK_NULL_HANDLE;
}

void Algorithm::create_layouts(std::size_t bindings) {
  std::vector<VkDescriptorSetLayoutBinding> b(bindings);
  for (std::size_t i = 0; i < bindings; ++i) {
    b[i].binding = static_cast<std::uint32_t>(i);
    b[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    b[i].descriptorCount = 1;
    b[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
  }
  VkDescriptorSetLayoutCreateInfo set{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  set.bindingCount = static_cast<std::uint32_t>(bindings);
  set.pBindings = b.data();
  check(vkCreateDescriptorSetLayout(device_, &set, nullptr, &set_layout_),
        "creating a descriptor set layout");
  const VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes_};
  VkPipelineLayoutCreateInfo layout{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layout.setLayoutCount = 1;
  layout.pSetLayouts = &set_layout_;
  layout.pushConstantRangeCount = push_bytes_ > 0 ? 1 : 0;
  layout.pPushConstantRanges = &range;
  check(vkCreatePipelineLayout(device_, &layout, nullptr, &pipeline_layout_),
        "creating a pipeline layout");
}

void Algorithm::create_pipeline(std::span<const std::uint32_t> spirv,
                                const std::vector<SpecConstant>& spec) {
  VkShaderModuleCreateInfo module_info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  module_info.codeSize = spirv.size_bytes();
  module_info.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  check(vkCreateShaderModule(device_, &module_info, nullptr, &module), "creating a shader module");
  std::vector<VkSpecializationMapEntry> entries;
  std::vector<std::uint32_t> values;
  for (const SpecConstant& c : spec) {
    entries.push_back({c.id, static_cast<std::uint32_t>(4 * values.size()), 4});
    values.push_back(c.value);
  }
  const VkSpecializationInfo spec_info{static_cast<std::uint32_t>(entries.size()), entries.data(),
                                       4 * values.size(), values.data()};
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = spec.empty() ? nullptr : &spec_info;
  info.layout = pipeline_layout_;
  const VkResult r =
      vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline_);
  vkDestroyShaderModule(device_, module, nullptr);  // the pipeline keeps what it needs
  check(r, "compiling the compute pipeline");
}

void Algorithm::write_descriptors(const std::vector<const Buffer*>& buffers) {
  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                  static_cast<std::uint32_t>(buffers.size())};
  VkDescriptorPoolCreateInfo pool{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool.maxSets = 1;
  pool.poolSizeCount = 1;
  pool.pPoolSizes = &size;
  check(vkCreateDescriptorPool(device_, &pool, nullptr, &pool_), "creating a descriptor pool");
  VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  alloc.descriptorPool = pool_;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &set_layout_;
  check(vkAllocateDescriptorSets(device_, &alloc, &set_), "allocating a descriptor set");
  std::vector<VkDescriptorBufferInfo> infos;
  infos.reserve(buffers.size());
  std::vector<VkWriteDescriptorSet> writes;
  for (std::size_t i = 0; i < buffers.size(); ++i) {
    infos.push_back({buffers[i]->handle(), 0, VK_WHOLE_SIZE});
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = set_;
    w.dstBinding = static_cast<std::uint32_t>(i);
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w.pBufferInfo = &infos.back();
    writes.push_back(w);
  }
  vkUpdateDescriptorSets(device_, static_cast<std::uint32_t>(writes.size()), writes.data(), 0,
                         nullptr);
}

void Algorithm::bind(VkCommandBuffer cmd, const void* push) const {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_layout_, 0, 1, &set_, 0,
                          nullptr);
  if (push_bytes_ > 0) {
    vkCmdPushConstants(cmd, pipeline_layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes_, push);
  }
}

void Algorithm::record(VkCommandBuffer cmd, std::uint32_t groups, const void* push) const {
  bind(cmd, push);
  vkCmdDispatch(cmd, groups, 1, 1);
}

void Algorithm::record_indirect(VkCommandBuffer cmd, const Buffer& args, VkDeviceSize offset,
                                const void* push) const {
  bind(cmd, push);
  vkCmdDispatchIndirect(cmd, args.handle(), offset);
}

}  // namespace lightsolver::vkw
