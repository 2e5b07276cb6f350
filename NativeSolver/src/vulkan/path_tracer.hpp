#pragma once
// Backend::path_vertices for the Vulkan backend (Shaders/path_vertices.comp): the diffuse
// vertices of photon paths, the same as the Embree backend's, in chunks of paths, with
// lavapipe's loop limit handled as in trace.comp. Its pipeline is separate from the trace
// pipeline, so runs that never connect reflected light never compile it.
#include <cstdint>
#include <optional>
#include <vector>

#include "model/backend.hpp"
#include "model/prepared_scene.hpp"
#include "vulkan/algorithm.hpp"
#include "vulkan/buffer.hpp"
#include "vulkan/context.hpp"
#include "vulkan/gpu_layout.hpp"
#include "vulkan/sequence.hpp"

namespace lightsolver::detail {

class PathVertexTracer {
 public:
  /// `scene` holds the backend's buffers, indexed by gpu::Binding; they must stay as they are
  /// while this object lives (the backend drops it whenever it replaces one). `spec`: the
  /// trace pipeline's specialisation (the scene's features).
  PathVertexTracer(const vkw::Context& ctx, const std::vector<vkw::Buffer>& scene,
                   const std::vector<vkw::SpecConstant>& spec);

  /// Appends the vertices of paths [first, first + count) to `out` in Backend::path_vertices's
  /// order. `push` carries the group's fields (seed, stream in `group`, luminaires, max_bounces,
  /// instance_count); the rest is set here. Throws DeviceLimitError when the device's loop
  /// limit cuts a path even traced alone (lavapipe, pathological scenes only).
  void trace(vkw::Sequence& seq, const PreparedScene& s, gpu::TracePush push, std::uint64_t first,
             std::uint64_t count, std::vector<PathVertex>& out);

 private:
  // One chunk at path offset `first`; returns the vertices the shader appended, and adds them
  // to `out` unless that is more than the buffer holds (then nothing is added).
  std::uint32_t trace_chunk(vkw::Sequence& seq, const PreparedScene& s, gpu::TracePush push,
                            std::uint64_t first, std::uint32_t count, std::vector<PathVertex>& out);

  const vkw::Context& ctx_;
  vkw::Buffer vertices_;  // host-visible: written by the shader, read by the CPU in place
  vkw::Buffer control_;   // host-visible: counts, the retry pass's dispatch and queue
  std::optional<vkw::Algorithm> kernel_;
};

}  // namespace lightsolver::detail
