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
    add_buffer("counters", nullptr, 2 * sizeof(std::uint64_t));
    add_buffer("photometric luminaires", data_.photometrics.data(), bytes_of(data_.photometrics));
    add_buffer("photometric tables", data_.photo_floats.data(), bytes_of(data_.photo_floats));
    add_buffer("photometric CDF", data_.photo_cdf53.data(), bytes_of(data_.photo_cdf53));
    add_buffer("instances", data_.instances.data(), bytes_of(data_.instances));
    readback_.emplace(ctx_, tally_bytes + 2 * sizeof(std::uint64_t), vkw::MemoryKind::Readback,
                      "tally readback");
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
      const gpu::TracePush push{first + done,
                                seed,
                                static_cast<std::uint32_t>(n),
                                s_.max_bounces,
                                static_cast<std::uint32_t>(data_.luminaires.size()),
                                static_cast<std::uint32_t>(data_.grids.size()),
                                static_cast<std::uint32_t>(data_.instances.size()),
                                0};
      trace_->record(cmd, groups(n), &push);
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

  void record_readback(VkCommandBuffer cmd) {
    vkw::memory_barrier(cmd);
    const vkw::Buffer& tallies = buffers_[gpu::kTallies];
    const VkDeviceSize tally_bytes = readback_->size() - 2 * sizeof(std::uint64_t);
    const VkBufferCopy t{0, 0, tally_bytes};
    vkCmdCopyBuffer(cmd, tallies.handle(), readback_->handle(), 1, &t);
    const VkBufferCopy c{0, tally_bytes, 2 * sizeof(std::uint64_t)};
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
