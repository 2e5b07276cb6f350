#pragma once
// lavapipe's loop limit (docs/vulkan.md): Mesa's llvmpipe ends every loop of an invocation once
// it has run 65 535 iterations in all. The kernels that trace (trace.comp, path_vertices.comp,
// visibility.comp) probe whether the limit was reached, queue what it cut, and trace that again
// alone in its workgroup; these are the host's halves of that protocol, shared by their hosts.
#include <cstdint>

#include "vulkan/algorithm.hpp"
#include "vulkan/buffer.hpp"
#include "vulkan/sequence.hpp"

namespace lightsolver::detail {

/// Iterations of the loop-limit probe (the kernels' loop_limit_reached) and the hash they give,
/// a 32-bit LCG from 0, when every one of them ran: both are push constants, so no compiler can
/// fold the probe away.
inline constexpr std::uint32_t kProbeIterations = 4;
constexpr std::uint32_t probe_hash() {
  std::uint32_t h = 0;
  for (std::uint32_t i = 0; i < kProbeIterations; ++i) h = h * 1664525u + 1013904223u;
  return h;
}

/// Records the retry pass after a kernel's main dispatch: a barrier, the `kernel` again with
/// `push.retry` = 1 over the workgroups the main dispatch queued in `queue` (a
/// VkDispatchIndirectCommand at offset 0: one item per workgroup, alone with the whole limit;
/// zero workgroups on devices without the limit), and a barrier before anything reads results.
template <class Push>
void record_retry_pass(VkCommandBuffer cmd, const vkw::Algorithm& kernel, const vkw::Buffer& queue,
                       Push push) {
  vkw::memory_barrier(cmd);
  push.retry = 1;
  kernel.record_indirect(cmd, queue, 0, &push);
  vkw::memory_barrier(cmd);
}

}  // namespace lightsolver::detail
