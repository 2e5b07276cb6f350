#include "vulkan/path_tracer.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <unordered_set>

#include "vulkan/loop_limit.hpp"
#include "vulkan/shaders.hpp"

namespace lightsolver::detail {
namespace {

constexpr std::uint32_t kWorkgroupSize = 64;
// Paths per submission, and room for 8 vertices per path on average (a box room of
// reflectance 0.8 averages 4); a chunk that needs more is traced again in halves.
constexpr std::uint32_t kChunkPaths = 1u << 14;
constexpr std::uint32_t kVertexCapacity = 8 * kChunkPaths;
// control[]: VkDispatchIndirectCommand {x, 1, 1}, pad, vertices appended, paths cut, 2 pads.
constexpr std::uint32_t kControlHeader[8] = {0, 1, 1, 0, 0, 0, 0, 0};
constexpr std::size_t kControlBytes = sizeof(kControlHeader) + kChunkPaths * 4;

}  // namespace

PathVertexTracer::PathVertexTracer(const vkw::Context& ctx, const std::vector<vkw::Buffer>& scene,
                                   const std::vector<vkw::SpecConstant>& spec)
    : ctx_(ctx),
      vertices_(ctx, std::size_t(kVertexCapacity) * sizeof(gpu::PathVertexGpu),
                vkw::MemoryKind::Readback, "path vertices"),
      control_(ctx, kControlBytes, vkw::MemoryKind::Readback, "path-vertex control") {
  std::vector<const vkw::Buffer*> bindings;
  for (const vkw::Buffer& b : scene) bindings.push_back(&b);
  if (bindings.size() != gpu::kPathVertices) {
    throw std::logic_error("path vertices: the scene has " + std::to_string(bindings.size()) +
                           " buffers, path_vertices.comp expects " +
                           std::to_string(gpu::kPathVertices));
  }
  bindings.push_back(&vertices_);
  bindings.push_back(&control_);
  kernel_.emplace(ctx_, shaders::path_vertices(), bindings,
                  static_cast<std::uint32_t>(sizeof(gpu::TracePush)), spec);
}

void PathVertexTracer::trace(vkw::Sequence& seq, const PreparedScene& s, gpu::TracePush push,
                             std::uint64_t first, std::uint64_t count,
                             std::vector<PathVertex>& out) {
  // The shader's 32-bit vertex count cannot wrap: at most max_bounces vertices per path.
  std::uint32_t chunk = static_cast<std::uint32_t>(
      std::clamp<std::uint64_t>((1ull << 32) / std::max(1u, s.max_bounces + 1), 1, kChunkPaths));
  for (std::uint64_t done = 0; done < count;) {
    const auto n = static_cast<std::uint32_t>(std::min<std::uint64_t>(chunk, count - done));
    const std::size_t before = out.size();
    const std::uint32_t appended = trace_chunk(seq, s, push, first + done, n, out);
    if (appended <= kVertexCapacity) {
      for (std::size_t i = before; i < out.size(); ++i) out[i].path += std::uint32_t(done);
      done += n;
    } else if (n == 1) {
      throw std::runtime_error("Vulkan backend: a path has more than " +
                               std::to_string(kVertexCapacity) + " vertices");
    } else {
      // Again in smaller parts, sized by what overflowed, with a margin (deterministic: each
      // path's draws depend on its index only).
      const std::uint64_t fits = std::uint64_t(n) * kVertexCapacity / appended * 3 / 4;
      chunk = static_cast<std::uint32_t>(std::clamp<std::uint64_t>(fits, 1, n / 2));
    }
  }
}

std::uint32_t PathVertexTracer::trace_chunk(vkw::Sequence& seq, const PreparedScene& s,
                                            gpu::TracePush push, std::uint64_t first,
                                            std::uint32_t count, std::vector<PathVertex>& out) {
  VkCommandBuffer cmd = seq.begin();
  vkCmdUpdateBuffer(cmd, control_.handle(), 0, sizeof(kControlHeader), kControlHeader);
  vkw::memory_barrier(cmd);
  push.first_path = first;
  push.path_count = count;
  push.grid_count = kVertexCapacity;
  push.retry = 0;
  push.probe_iterations = kProbeIterations;
  push.probe_hash = probe_hash();
  kernel_->record(cmd, (count + kWorkgroupSize - 1) / kWorkgroupSize, &push);
  record_retry_pass(cmd, *kernel_, control_, push);  // the paths the loop limit cut
  seq.submit_and_wait("tracing path vertices");

  const auto* control = static_cast<const std::uint32_t*>(control_.mapped());
  if (control[5] > 0) {
    throw DeviceLimitError("Vulkan backend: " + std::to_string(control[5]) +
                           " connection paths need more loop iterations than this device (" +
                           ctx_.device_name() + ") allows even traced alone; use --backend embree");
  }
  const std::uint32_t appended = control[4];
  if (appended > kVertexCapacity) return appended;
  const std::unordered_set<std::uint32_t> retried(control + 8, control + 8 + control[0]);
  const auto* records = static_cast<const gpu::PathVertexGpu*>(vertices_.mapped());
  std::vector<gpu::PathVertexGpu> kept;
  kept.reserve(appended);
  for (std::uint32_t i = 0; i < appended; ++i) {
    const gpu::PathVertexGpu& r = records[i];
    // A retried path's first pass may be incomplete: its second pass counts.
    if (r.pass == 0 && retried.count(r.path) != 0) continue;
    // Embree ends a path at a surface that reflects nothing, before the vertex.
    if (!(s.materials[r.material].reflectance > 0.0)) continue;
    kept.push_back(r);
  }
  std::sort(kept.begin(), kept.end(), [](const auto& a, const auto& b) {
    return a.path != b.path ? a.path < b.path : a.vertex < b.vertex;
  });
  for (const gpu::PathVertexGpu& r : kept) {
    out.push_back({vec3(r.origin[0], r.origin[1], r.origin[2]),
                   float(s.materials[r.material].reflectance),
                   vec3(r.normal[0], r.normal[1], r.normal[2]), r.path});
  }
  return appended;
}

}  // namespace lightsolver::detail
