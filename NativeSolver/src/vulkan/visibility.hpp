#pragma once
// Shadow rays on the device (Shaders/visibility.comp): Backend::visible for the Vulkan backend,
// in chunks of a fixed size, with lavapipe's loop limit handled as in trace.comp.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "model/backend.hpp"
#include "vulkan/algorithm.hpp"
#include "vulkan/buffer.hpp"
#include "vulkan/context.hpp"
#include "vulkan/loop_limit.hpp"
#include "vulkan/sequence.hpp"

namespace lightsolver::detail {

/// Shadow rays per submission: 8 MiB of rays, 4096 workgroups of 64.
inline constexpr std::uint32_t kShadowRaysPerSubmit = 1u << 18;

class ShadowRayTracer {
 public:
  /// `scene` holds the backend's buffers, indexed by gpu::Binding: the geometry and the
  /// instances are read there. They must stay as they are while this object lives (the backend
  /// drops it whenever it replaces one of them).
  ShadowRayTracer(const vkw::Context& ctx, const std::vector<vkw::Buffer>& scene,
                  bool has_instances);

  /// Backend::visible with `instance_count` movable meshes. Throws DeviceLimitError when the
  /// device's loop limit leaves a ray undecided even traced alone (lavapipe, pathological
  /// scenes only), so no answer is ever a guess.
  void visible(vkw::Sequence& seq, std::span<const ShadowRay> rays, std::uint32_t instance_count,
               std::vector<std::uint8_t>& out);

 private:
  const vkw::Context& ctx_;
  vkw::Buffer rays_;     // host-visible: written by the CPU, read by the shader in place
  vkw::Buffer visible_;  // host-visible: written by the shader, read by the CPU in place
  vkw::Buffer retry_;    // the retry pass's dispatch command and queue
  std::optional<vkw::Algorithm> kernel_;
};

}  // namespace lightsolver::detail
