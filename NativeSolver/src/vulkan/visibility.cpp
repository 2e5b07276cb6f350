#include "vulkan/visibility.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

#include "vulkan/gpu_layout.hpp"
#include "vulkan/shaders.hpp"

namespace lightsolver::detail {
namespace {

constexpr std::uint32_t kWorkgroupSize = 64;
static_assert(kShadowRaysPerSubmit / kWorkgroupSize <= 65535, "one ray per invocation");
static_assert(sizeof(ShadowRay) == 32, "visibility.comp reads 32-byte records");

// Written by the shader (Shaders/visibility.comp): 1 visible, 0 blocked, kCut undecided.
constexpr std::uint32_t kCut = 2;

// The retry queue: a VkDispatchIndirectCommand {x, 1, 1} (x counted up by the shader, one
// workgroup per ray, at most 65535), the queue's length, then one ray index per ray of a chunk.
constexpr std::uint32_t kRetryHeader[4] = {0, 1, 1, 0};
constexpr std::size_t kRetryBytes = sizeof(kRetryHeader) + kShadowRaysPerSubmit * 4;

}  // namespace

ShadowRayTracer::ShadowRayTracer(const vkw::Context& ctx, const std::vector<vkw::Buffer>& scene,
                                 bool has_instances)
    : ctx_(ctx),
      rays_(ctx, kShadowRaysPerSubmit * sizeof(ShadowRay), vkw::MemoryKind::Upload, "shadow rays"),
      visible_(ctx, kShadowRaysPerSubmit * sizeof(std::uint32_t), vkw::MemoryKind::Readback,
               "shadow-ray results"),
      retry_(ctx, kRetryBytes, vkw::MemoryKind::Device, "shadow-ray retry list") {
  vkw::upload(ctx_, retry_, kRetryHeader, sizeof(kRetryHeader));
  std::vector<const vkw::Buffer*> bindings;
  for (const vkw::Buffer& b : scene) bindings.push_back(&b);
  if (bindings.size() != gpu::kShadowRays) {
    throw std::logic_error("shadow rays: the scene has " + std::to_string(bindings.size()) +
                           " buffers, visibility.comp expects " + std::to_string(gpu::kShadowRays));
  }
  bindings.push_back(&rays_);
  bindings.push_back(&visible_);
  bindings.push_back(&retry_);
  const std::vector<vkw::SpecConstant> spec = {
      {gpu::kWorkgroupSize, kWorkgroupSize},
      {gpu::kHasInstances, has_instances ? 1u : 0u},
  };
  kernel_.emplace(ctx_, shaders::visibility(), bindings,
                  static_cast<std::uint32_t>(sizeof(gpu::VisibilityPush)), spec);
}

void ShadowRayTracer::visible(vkw::Sequence& seq, std::span<const ShadowRay> rays,
                              std::uint32_t instance_count, std::vector<std::uint8_t>& out) {
  out.assign(rays.size(), 0);
  auto* ray_slots = static_cast<ShadowRay*>(rays_.mapped());
  const auto* results = static_cast<const std::uint32_t*>(visible_.mapped());
  for (std::size_t first = 0; first < rays.size(); first += kShadowRaysPerSubmit) {
    const auto count = static_cast<std::uint32_t>(
        std::min<std::size_t>(kShadowRaysPerSubmit, rays.size() - first));
    std::memcpy(ray_slots, rays.data() + first, count * sizeof(ShadowRay));
    VkCommandBuffer cmd = seq.begin();
    vkCmdFillBuffer(cmd, retry_.handle(), 0, sizeof(std::uint32_t), 0);  // empty queue: x = 0
    vkCmdFillBuffer(cmd, retry_.handle(), 3 * sizeof(std::uint32_t), sizeof(std::uint32_t), 0);
    vkw::memory_barrier(cmd);
    gpu::VisibilityPush push{count, instance_count, 0, kProbeIterations, probe_hash(), {0, 0, 0}};
    kernel_->record(cmd, (count + kWorkgroupSize - 1) / kWorkgroupSize, &push);
    record_retry_pass(cmd, *kernel_, retry_, push);  // the rays the loop limit left undecided
    seq.submit_and_wait("tracing shadow rays");
    std::size_t cut = 0;
    for (std::uint32_t i = 0; i < count; ++i) {
      cut += results[i] == kCut;
      out[first + i] = results[i] == 1 ? 1 : 0;
    }
    if (cut > 0) {
      throw DeviceLimitError("Vulkan backend: " + std::to_string(cut) +
                             " shadow rays need more loop iterations than this device (" +
                             ctx_.device_name() +
                             ") allows even traced alone; use --backend embree");
    }
  }
}

}  // namespace lightsolver::detail
