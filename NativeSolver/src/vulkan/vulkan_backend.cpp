#include "vulkan/vulkan_backend.hpp"

#include <algorithm>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "vulkan/algorithm.hpp"
#include "vulkan/buffer.hpp"
#include "vulkan/context.hpp"
#include "vulkan/gpu_scene.hpp"
#include "vulkan/sequence.hpp"
#include "vulkan/shaders.hpp"

namespace lightsolver::detail {
namespace {

constexpr std::uint32_t kWorkgroupSize = 64;
// Paths per submission: short enough that no dispatch approaches a driver watchdog (about 2 s
// on desktop GPUs), long enough to amortise the submit (lavapipe: ~0.1-0.5 s per submission).
constexpr std::uint64_t kPathsPerSubmit = 1u << 16;
// One path per invocation (trace.comp relies on it: lavapipe's loop limit must not be able to
// end the grid-stride loop before an invocation's path was traced).
static_assert(kPathsPerSubmit <= 65535ull * kWorkgroupSize);
// Ray segments, capped paths, paths cut for good, paths traced again.
constexpr std::uint32_t kCounters = 4;

// lavapipe's loop-limit probe (trace.comp): a few iterations of a 32-bit LCG from 0.
constexpr std::uint32_t kProbeIterations = 4;
constexpr std::uint32_t probe_hash() {
  std::uint32_t h = 0;
  for (std::uint32_t i = 0; i < kProbeIterations; ++i) h = h * 1664525u + 1013904223u;
  return h;
}

// The retry list: a VkDispatchIndirectCommand {x, 1, 1} (x counted up by the shader, one group
// per path) and a pad word, then one (path offset, deposit floor) pair per path of a submit.
constexpr std::uint32_t kRetryHeader[4] = {0, 1, 1, 0};
constexpr std::size_t kRetryBytes =
    sizeof(kRetryHeader) + kPathsPerSubmit * 2 * sizeof(std::uint32_t);

struct LuminaireBuffer {
  gpu::Binding binding;
  const char* name;
  const void* data;
  std::size_t bytes;
};

template <class T>
std::size_t bytes_of(const std::vector<T>& v) {
  return v.size() * sizeof(T);
}

class VulkanBackend final : public Backend {
 public:
  explicit VulkanBackend(const PreparedScene& s) : s_(s), data_(pack_scene(s)), seq_(ctx_) {
    const GpuGeometry& g = data_.geometry;
    add_buffer("BVH nodes", g.nodes.data(), bytes_of(g.nodes));
    add_buffer("triangles", g.tris.data(), bytes_of(g.tris));
    add_buffer("triangle normals", g.normals.data(), bytes_of(g.normals));
    add_buffer("meshes", data_.meshes.data(), bytes_of(data_.meshes));
    add_buffer("materials", data_.materials.data(), bytes_of(data_.materials));
    add_buffer("luminaires", data_.luminaires.data(), bytes_of(data_.luminaires));
    add_buffer("luminaire CDF", data_.cdf53.data(), bytes_of(data_.cdf53));
    add_buffer("grids", data_.grids.data(), bytes_of(data_.grids));
    const std::size_t tally_bytes = 2 * sizeof(std::uint64_t) * s.bins.size();
    add_buffer("tallies", nullptr, tally_bytes);
    add_buffer("counters", nullptr, kCounters * sizeof(std::uint64_t));
    add_buffer("photometric luminaires", data_.photometrics.data(), bytes_of(data_.photometrics));
    add_buffer("photometric tables", data_.photo_floats.data(), bytes_of(data_.photo_floats));
    add_buffer("photometric CDF", data_.photo_cdf53.data(), bytes_of(data_.photo_cdf53));
    add_buffer("instances", data_.instances.data(), bytes_of(data_.instances));
    add_buffer("retry list", nullptr, kRetryBytes);
    vkw::upload(ctx_, buffers_[gpu::kRetry], kRetryHeader, sizeof(kRetryHeader));
    readback_.emplace(ctx_, tally_bytes + kCounters * sizeof(std::uint64_t),
                      vkw::MemoryKind::Readback, "tally readback");
    data_.geometry = {};  // on the device now
    build_pipeline();
  }

  // Simulation::set_luminaire: same-sized data is re-uploaded in place; the pipeline is rebuilt
  // only when the set of luminaire types (its specialisation) or a buffer's size changes.
  void luminaires_changed() override {
    const auto old_features = data_.features;
    const std::size_t old_bytes[] = {bytes_of(data_.luminaires), bytes_of(data_.cdf53),
                                     bytes_of(data_.photometrics), bytes_of(data_.photo_floats),
                                     bytes_of(data_.photo_cdf53)};
    pack_luminaires(s_, data_);
    const LuminaireBuffer parts[] = {
        {gpu::kLuminaires, "luminaires", data_.luminaires.data(), bytes_of(data_.luminaires)},
        {gpu::kLuminaireCdf, "luminaire CDF", data_.cdf53.data(), bytes_of(data_.cdf53)},
        {gpu::kPhotometrics, "photometric luminaires", data_.photometrics.data(),
         bytes_of(data_.photometrics)},
        {gpu::kPhotoFloats, "photometric tables", data_.photo_floats.data(),
         bytes_of(data_.photo_floats)},
        {gpu::kPhotoCdf, "photometric CDF", data_.photo_cdf53.data(), bytes_of(data_.photo_cdf53)}};
    bool resized = false;
    for (std::size_t i = 0; i < std::size(parts); ++i) {
      if (parts[i].bytes != old_bytes[i]) {
        replace_buffer(parts[i].binding, parts[i].name, parts[i].bytes);
        resized = true;
      }
      if (parts[i].bytes > 0)
        vkw::upload(ctx_, buffers_[parts[i].binding], parts[i].data, parts[i].bytes);
    }
    if (resized || !same(old_features, data_.features)) build_pipeline();
  }

  // Only the instance record changes: each movable mesh keeps its own BVH in its prepared
  // coordinates, so a move costs one small upload, no rebuild.
  void set_mesh_transform(std::size_t mesh, const glm::mat4& transform) override {
    const auto it = std::find_if(data_.instance_roots.begin(), data_.instance_roots.end(),
                                 [&](const GpuInstanceRoot& r) { return r.mesh == mesh; });
    if (it == data_.instance_roots.end()) {
      throw std::logic_error("mesh " + std::to_string(mesh) + " is not movable");
    }
    const std::size_t k = it - data_.instance_roots.begin();
    data_.instances[k] = pack_instance(*it, transform);
    vkw::upload(ctx_, buffers_[gpu::kInstances], data_.instances.data(), bytes_of(data_.instances));
  }

  std::string name() const override { return "vulkan"; }

  // Tallies reach `out` only after the whole range succeeded, so a caller may retry the same
  // range on another backend after an exception.
  void trace(std::uint64_t first, std::uint64_t count, std::uint64_t seed,
             TallyBlock& out) override {
    for (std::uint64_t done = 0; done < count;) {
      const std::uint64_t n = std::min(kPathsPerSubmit, count - done);
      VkCommandBuffer cmd = seq_.begin();
      if (done == 0) {
        vkCmdFillBuffer(cmd, buffers_[gpu::kTallies].handle(), 0, VK_WHOLE_SIZE, 0);
        vkCmdFillBuffer(cmd, buffers_[gpu::kCounters].handle(), 0, VK_WHOLE_SIZE, 0);
      }
      vkw::memory_barrier(cmd);  // clears or the previous batch's atomics come first
      gpu::TracePush push{first + done,
                          seed,
                          static_cast<std::uint32_t>(n),
                          s_.max_bounces,
                          static_cast<std::uint32_t>(data_.luminaires.size()),
                          static_cast<std::uint32_t>(data_.grids.size()),
                          static_cast<std::uint32_t>(data_.instances.size()),
                          0,
                          kProbeIterations,
                          probe_hash(),
                          0};
      trace_->record(cmd, groups(n), &push);
      record_retries(cmd, push);
      done += n;
      if (done == count) record_readback(cmd);
      seq_.submit_and_wait("tracing photons");
    }
    add_readback(out);
  }

 private:
  void add_buffer(const char* name, const void* data, std::size_t bytes) {
    check_size(name, bytes);
    // Empty arrays still need a valid binding: 16 bytes of zeros.
    buffers_.emplace_back(ctx_, std::max<std::size_t>(bytes, 16), vkw::MemoryKind::Device, name);
    if (data) vkw::upload(ctx_, buffers_.back(), data, bytes);
  }

  void check_size(const char* name, std::size_t bytes) const {
    const VkDeviceSize limit = ctx_.properties().limits.maxStorageBufferRange;
    if (bytes > limit) {
      throw std::runtime_error("Vulkan backend: the " + std::string(name) + " buffer needs " +
                               std::to_string(bytes >> 20) + " MiB, more than this device's " +
                               std::to_string(limit >> 20) + " MiB storage-buffer limit (" +
                               std::to_string(s_.triangle_count) +
                               " triangles); use --backend embree");
    }
  }

  void replace_buffer(gpu::Binding binding, const char* name, std::size_t bytes) {
    trace_.reset();  // its descriptor set refers to the old buffer
    buffers_.erase(buffers_.begin() + binding);
    check_size(name, bytes);
    buffers_.emplace(buffers_.begin() + binding, ctx_, std::max<std::size_t>(bytes, 16),
                     vkw::MemoryKind::Device, name);
  }

  void build_pipeline() {
    trace_.reset();
    std::vector<const vkw::Buffer*> bindings;
    for (const auto& b : buffers_) bindings.push_back(&b);
    std::vector<vkw::SpecConstant> spec = data_.features;
    spec.push_back({gpu::kWorkgroupSize, kWorkgroupSize});
    trace_.emplace(ctx_, shaders::trace(), bindings, sizeof(gpu::TracePush), spec);
  }

  static bool same(const std::vector<vkw::SpecConstant>& a,
                   const std::vector<vkw::SpecConstant>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const auto& x, const auto& y) {
      return x.id == y.id && x.value == y.value;
    });
  }

  std::uint32_t groups(std::uint64_t paths) const {
    const std::uint64_t limit =
        std::min<std::uint64_t>(65535, ctx_.properties().limits.maxComputeWorkGroupCount[0]);
    return static_cast<std::uint32_t>(
        std::clamp<std::uint64_t>((paths + kWorkgroupSize - 1) / kWorkgroupSize, 1, limit));
  }

  // The paths the main dispatch queued (lavapipe's loop limit cut them short) are traced again,
  // one per workgroup (the others' invocations return at once), which gives each the whole
  // limit; then the queue is emptied.
  // Zero groups on devices without the limit.
  void record_retries(VkCommandBuffer cmd, gpu::TracePush push) {
    vkw::memory_barrier(cmd);
    push.retry = 1;
    trace_->record_indirect(cmd, buffers_[gpu::kRetry], 0, &push);
    vkw::memory_barrier(cmd);
    vkCmdFillBuffer(cmd, buffers_[gpu::kRetry].handle(), 0, sizeof(std::uint32_t), 0);
  }

  void record_readback(VkCommandBuffer cmd) {
    vkw::memory_barrier(cmd);
    const vkw::Buffer& tallies = buffers_[gpu::kTallies];
    const VkDeviceSize tally_bytes = readback_->size() - kCounters * sizeof(std::uint64_t);
    const VkBufferCopy t{0, 0, tally_bytes};
    vkCmdCopyBuffer(cmd, tallies.handle(), readback_->handle(), 1, &t);
    const VkBufferCopy c{0, tally_bytes, kCounters * sizeof(std::uint64_t)};
    vkCmdCopyBuffer(cmd, buffers_[gpu::kCounters].handle(), readback_->handle(), 1, &c);
    vkw::memory_barrier(cmd);
  }

  void add_readback(TallyBlock& out) const {
    const auto* v = static_cast<const std::uint64_t*>(readback_->mapped());
    for (std::size_t i = 0; i < out.bins.size(); ++i) {
      out.bins[i].sum += v[2 * i];
      out.bins[i].sum_sq += v[2 * i + 1];
    }
    out.ray_segments += v[2 * out.bins.size()];
    out.capped_paths += v[2 * out.bins.size() + 1];
    out.cut_paths += v[2 * out.bins.size() + 2];
    out.retried_paths += v[2 * out.bins.size() + 3];
  }

  const PreparedScene& s_;            // owned by the caller (Simulation), updated in place
  GpuSceneData data_;                 // host copy of what is small and may change
  vkw::Context ctx_;                  // destroyed after everything created from it
  std::vector<vkw::Buffer> buffers_;  // indexed by gpu::Binding
  std::optional<vkw::Buffer> readback_;
  std::optional<vkw::Algorithm> trace_;
  vkw::Sequence seq_;
};

}  // namespace

std::unique_ptr<Backend> make_vulkan_backend(const PreparedScene& scene) {
  return std::make_unique<VulkanBackend>(scene);
}

bool vulkan_gpu_available() { return vkw::Context::gpu_available(); }

std::size_t vulkan_validation_message_count() { return vkw::Context::validation_message_count(); }

}  // namespace lightsolver::detail
