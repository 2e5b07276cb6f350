#include "vulkan/vulkan_backend.hpp"

#include <algorithm>
#include <cstring>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/sobol.hpp"
#include "vulkan/algorithm.hpp"
#include "vulkan/buffer.hpp"
#include "vulkan/context.hpp"
#include "vulkan/gpu_scene.hpp"
#include "vulkan/loop_limit.hpp"
#include "vulkan/path_tracer.hpp"
#include "vulkan/sequence.hpp"
#include "vulkan/shaders.hpp"
#include "vulkan/visibility.hpp"

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
constexpr std::uint32_t kCounters = 7;

// The retry list: a VkDispatchIndirectCommand {x, 1, 1} (x counted up by the shader, one group
// per path) and a pad word, then one (path offset, deposit floor) pair per path of a submit.
constexpr std::uint32_t kRetryHeader[4] = {0, 1, 1, 0};
constexpr std::size_t kRetryBytes =
    sizeof(kRetryHeader) + kPathsPerSubmit * 2 * sizeof(std::uint32_t);

// What a buffer holds: `bytes` in all, the first `upload_bytes` of them uploaded from `data`
// (buffers the shader writes upload nothing, the retry list only its header).
struct Contents {
  std::size_t bytes;
  const void* data = nullptr;
  std::size_t upload_bytes = 0;
};

template <class T>
Contents whole(const std::vector<T>& v) {
  const std::size_t bytes = v.size() * sizeof(T);
  return {bytes, v.data(), bytes};
}

// The buffers pack_luminaires() rewrites.
constexpr gpu::Binding kLuminaireBindings[] = {
    gpu::kLuminaires, gpu::kLuminaireCdf, gpu::kPhotometrics, gpu::kPhotoFloats, gpu::kPhotoCdf};

class VulkanBackend final : public Backend {
 public:
  // One buffer per row of gpu::kBuffers, in binding order (buffers_[b] is bound at binding b).
  explicit VulkanBackend(const PreparedScene& s) : s_(s), data_(pack_scene(s)), seq_(ctx_) {
    for (const gpu::BufferInfo& info : gpu::kBuffers) {
      const Contents c = contents(info.binding);
      buffers_.push_back(make_buffer(info.binding, c.bytes));
      upload(info.binding, c);
    }
    make_readback();
    data_.geometry = {};  // on the device now
    build_pipeline();
  }

  // Simulation::set_luminaire: same-sized data is re-uploaded in place; the pipeline is rebuilt
  // only when the set of luminaire types (its specialisation) or a buffer's size changes.
  void luminaires_changed() override {
    const auto old_features = data_.features;
    std::size_t old_bytes[std::size(kLuminaireBindings)];
    for (std::size_t i = 0; i < std::size(kLuminaireBindings); ++i) {
      old_bytes[i] = contents(kLuminaireBindings[i]).bytes;
    }
    const std::size_t old_tally_bytes = tally_bytes_;
    pack_luminaires(s_, data_);
    bool resized = false;
    if (tally_bytes() != old_tally_bytes) {  // the groups changed: tallies and their readback
      drop_pipelines();
      buffers_[gpu::kTallies] = make_buffer(gpu::kTallies, tally_bytes());
      make_readback();
      resized = true;
    }
    for (std::size_t i = 0; i < std::size(kLuminaireBindings); ++i) {
      const gpu::Binding b = kLuminaireBindings[i];
      const Contents c = contents(b);
      if (c.bytes != old_bytes[i]) {
        drop_pipelines();  // their descriptor sets refer to the old buffer
        buffers_[b] = make_buffer(b, c.bytes);
        resized = true;
      }
      upload(b, c);
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
    upload(gpu::kInstances, contents(gpu::kInstances));
  }

  std::string name() const override { return "vulkan"; }

  bool traces_shadow_rays() const override { return true; }

  // Shaders/sobol.glsl: the CPU's points, scrambles and Philox tails, bit for bit.
  bool traces_quasi_random() const override { return true; }
  // A specialisation constant: the pipeline is built again when the sampler changes.
  void set_quasi_random(bool on) override {
    if (on == quasi_random_) return;
    const std::lock_guard lock(submit_mutex_);
    quasi_random_ = on;
    build_pipeline();
  }

  // Shaders/visibility.comp, its pipeline made on first use (and again after buffers changed).
  // Callers may call it from several threads (Embree's is thread-safe): one at a time here.
  void visible(std::span<const ShadowRay> rays, std::vector<std::uint8_t>& out) override {
    const std::lock_guard lock(submit_mutex_);
    if (rays.empty()) {
      out.clear();
      return;
    }
    if (!shadows_) shadows_.emplace(ctx_, buffers_, !data_.instances.empty());
    shadows_->visible(seq_, rays, static_cast<std::uint32_t>(data_.instances.size()), out);
  }

  // Shaders/path_vertices.comp, its own small pipeline made on first use (and again after
  // buffers or features changed), so ordinary traces never compile it.
  bool traces_path_vertices() const override { return true; }
  void path_vertices(std::uint32_t group, std::uint64_t first, std::uint64_t count,
                     std::uint64_t seed, std::uint32_t stream,
                     std::vector<PathVertex>& out) override {
    const std::lock_guard lock(submit_mutex_);
    if (count == 0) return;
    if (!paths_) {
      std::vector<vkw::SpecConstant> spec = data_.features;
      spec.push_back({gpu::kWorkgroupSize, kWorkgroupSize});
      paths_.emplace(ctx_, buffers_, spec);
    }
    const auto [lum_first, lum_count] = data_.group_luminaires.at(group);
    gpu::TracePush push{};
    push.seed = seed;
    push.max_bounces = s_.max_bounces;
    push.luminaire_count = lum_count;
    push.instance_count = static_cast<std::uint32_t>(data_.instances.size());
    push.group = stream;  // path_vertices.comp: the photon stream
    push.luminaire_first = lum_first;
    paths_->trace(seq_, s_, push, first, count, out);
  }

  std::string device() const override { return ctx_.device_name(); }

  // Tallies reach `out` only after the whole range succeeded, so a caller may retry the same
  // range on another backend after an exception.
  // Each group's range is its own dispatches: its stream, luminaires and tallies are push
  // constants.
  void trace(const std::vector<GroupRange>& ranges, std::uint64_t seed, TallyBlock& out) override {
    const std::lock_guard lock(submit_mutex_);
    // The records' direct_by_photons flags follow each run's next-event plan: same sizes,
    // uploaded in place when they changed.
    if (pack_target_records(s_, data_)) {
      upload(gpu::kMeshes, contents(gpu::kMeshes));
      upload(gpu::kGrids, contents(gpu::kGrids));
    }
    // Ranges share a submission up to kPathsPerSubmit paths: a sky of 2306 patch groups traced
    // in a batch is not 2306 submissions, each waited for (on lavapipe most of such a run's
    // time went to waking its threads for them).
    bool cleared = false;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    std::uint64_t recorded = 0;  // paths in `cmd`
    for (std::size_t r = 0; r < ranges.size(); ++r) {
      const GroupRange& range = ranges[r];
      const auto [lum_first, lum_count] = data_.group_luminaires.at(range.group);
      for (std::uint64_t done = 0; done < range.count;) {
        if (cmd == VK_NULL_HANDLE) cmd = seq_.begin(), recorded = 0;
        const std::uint64_t n = std::min(kPathsPerSubmit - recorded, range.count - done);
        if (!cleared) {
          vkCmdFillBuffer(cmd, buffers_[gpu::kTallies].handle(), 0, VK_WHOLE_SIZE, 0);
          vkCmdFillBuffer(cmd, buffers_[gpu::kCounters].handle(), 0, VK_WHOLE_SIZE, 0);
          cleared = true;
        }
        vkw::memory_barrier(cmd);  // clears or the previous batch's atomics come first
        gpu::TracePush push{range.first + done,
                            seed,
                            static_cast<std::uint32_t>(n),
                            s_.max_bounces,
                            lum_count,
                            static_cast<std::uint32_t>(data_.grids.size()),
                            static_cast<std::uint32_t>(data_.instances.size()),
                            0,
                            kProbeIterations,
                            probe_hash(),
                            range.group,
                            lum_first,
                            static_cast<std::uint32_t>(range.group * s_.bins.size()),
                            s_.groups[range.group].next_event ? 1u : 0u,
                            s_.groups[range.group].connect ? 1u : 0u,
                            {0, 0, 0}};
        trace_->record(cmd, groups(n), &push);
        record_retries(cmd, push);
        done += n;
        recorded += n;
        if (recorded == kPathsPerSubmit) {
          seq_.submit_and_wait("tracing photons");
          cmd = VK_NULL_HANDLE;
        }
      }
    }
    if (!cleared) return;
    if (cmd == VK_NULL_HANDLE) cmd = seq_.begin();
    record_readback(cmd);
    seq_.submit_and_wait("tracing photons");
    add_readback(out);
  }

 private:
  // What each binding holds. No default: a binding added to trace_bindings.h without a case
  // here draws -Wswitch at compile time and throws on the first run. The geometry cases are
  // only valid in the constructor (the host copy is dropped once uploaded).
  Contents contents(gpu::Binding binding) const {
    const GpuGeometry& g = data_.geometry;
    switch (binding) {
      case gpu::kNodes:
        return whole(g.nodes);
      case gpu::kTris:
        return whole(g.tris);
      case gpu::kTriNormals:
        return whole(g.normals);
      case gpu::kMeshes:
        return whole(data_.meshes);
      case gpu::kMaterials:
        return whole(data_.materials);
      case gpu::kLuminaires:
        return whole(data_.luminaires);
      case gpu::kLuminaireCdf:
        return whole(data_.cdf53);
      case gpu::kGrids:
        return whole(data_.grids);
      case gpu::kTallies:
        return {tally_bytes()};
      case gpu::kCounters:
        return {kCounters * sizeof(std::uint64_t)};
      case gpu::kPhotometrics:
        return whole(data_.photometrics);
      case gpu::kPhotoFloats:
        return whole(data_.photo_floats);
      case gpu::kPhotoCdf:
        return whole(data_.photo_cdf53);
      case gpu::kInstances:
        return whole(data_.instances);
      case gpu::kRetry:
        return {kRetryBytes, kRetryHeader, sizeof(kRetryHeader)};
      case gpu::kSobol: {
        const SobolDirections& v = sobol_directions();  // row j: 16 coordinates, 4 uvec4s
        return {sizeof(v), v.data(), sizeof(v)};
      }
      case gpu::kBindingCount:
        break;
    }
    throw std::logic_error("Vulkan backend: no contents for binding " + std::to_string(binding));
  }

  // Every group's tallies (model/groups.hpp: at most 2^26 of them, checked before tracing).
  std::size_t tally_bytes() const {
    return 2 * sizeof(std::uint64_t) * s_.groups.size() * s_.bins.size();
  }

  // Empty arrays still need a valid binding: 16 bytes of zeros.
  vkw::Buffer make_buffer(gpu::Binding binding, std::size_t bytes) const {
    const char* label = gpu::kBuffers[binding].label;
    check_size(label, bytes);
    return vkw::Buffer(ctx_, std::max<std::size_t>(bytes, 16), vkw::MemoryKind::Device, label);
  }

  void upload(gpu::Binding binding, const Contents& c) {
    if (c.upload_bytes > 0) vkw::upload(ctx_, buffers_[binding], c.data, c.upload_bytes);
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

  // Before a buffer is replaced: the descriptor sets refer to it.
  void drop_pipelines() {
    trace_.reset();
    shadows_.reset();
    paths_.reset();
  }

  void build_pipeline() {
    drop_pipelines();
    std::vector<const vkw::Buffer*> bindings;
    for (const auto& b : buffers_) bindings.push_back(&b);
    std::vector<vkw::SpecConstant> spec = data_.features;
    spec.push_back({gpu::kWorkgroupSize, kWorkgroupSize});
    spec.push_back({gpu::kQuasiRandom, quasi_random_ ? 1u : 0u});
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
    record_retry_pass(cmd, *trace_, buffers_[gpu::kRetry], push);
    vkCmdFillBuffer(cmd, buffers_[gpu::kRetry].handle(), 0, sizeof(std::uint32_t), 0);
  }

  void make_readback() {
    tally_bytes_ = tally_bytes();
    readback_.reset();
    readback_.emplace(ctx_, tally_bytes_ + kCounters * sizeof(std::uint64_t),
                      vkw::MemoryKind::Readback, "tally readback");
  }

  void record_readback(VkCommandBuffer cmd) {
    vkw::memory_barrier(cmd);
    const vkw::Buffer& tallies = buffers_[gpu::kTallies];
    const VkDeviceSize tally_size = readback_->size() - kCounters * sizeof(std::uint64_t);
    const VkBufferCopy t{0, 0, tally_size};
    vkCmdCopyBuffer(cmd, tallies.handle(), readback_->handle(), 1, &t);
    const VkBufferCopy c{0, tally_size, kCounters * sizeof(std::uint64_t)};
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
    out.opening_photons += v[2 * out.bins.size() + 4];
    out.opening_blocked += v[2 * out.bins.size() + 5];
    out.opening_glass += v[2 * out.bins.size() + 6];
  }

  const PreparedScene& s_;            // owned by the caller (Simulation), updated in place
  GpuSceneData data_;                 // host copy of what is small and may change
  vkw::Context ctx_;                  // destroyed after everything created from it
  std::vector<vkw::Buffer> buffers_;  // indexed by gpu::Binding, one per row of gpu::kBuffers
  std::optional<vkw::Buffer> readback_;
  std::size_t tally_bytes_ = 0;  // the tallies the buffers were made for
  std::optional<vkw::Algorithm> trace_;
  std::optional<ShadowRayTracer> shadows_;  // made by the first visible()
  std::optional<PathVertexTracer> paths_;   // made by the first path_vertices()
  vkw::Sequence seq_;
  std::mutex submit_mutex_;  // trace() and visible() share seq_ and the buffers
  bool quasi_random_ = false;
};

}  // namespace

std::unique_ptr<Backend> make_vulkan_backend(const PreparedScene& scene) {
  return std::make_unique<VulkanBackend>(scene);
}

bool vulkan_gpu_available() { return vkw::Context::gpu_available(); }

std::size_t vulkan_validation_message_count() { return vkw::Context::validation_message_count(); }

}  // namespace lightsolver::detail
