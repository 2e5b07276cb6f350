#pragma once
// What a tracing backend (Embree on the CPU, Vulkan compute) does: trace a range of photon
// paths and add their integer tallies. Because tallies are counts, the sum does not depend on
// how a backend splits or orders the work.
#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "lightsolver/statistics.hpp"
#include "model/groups.hpp"
#include "model/prepared_scene.hpp"

namespace lightsolver::detail {

/// A device limit (lavapipe's loop limit) cut work even when it was traced again alone: this
/// device cannot do it, though another backend can. Callers that can do without the work (the
/// connection of reflected light under "auto") catch this type and say why; others pass it on.
struct DeviceLimitError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct TallyBlock {
  std::vector<Tally> bins;
  std::uint64_t ray_segments = 0;
  std::uint64_t capped_paths = 0;   // paths stopped by max_bounces while still alive
  std::uint64_t cut_paths = 0;      // paths a device's loop limit stopped (lavapipe; not counted)
  std::uint64_t retried_paths = 0;  // paths traced again after the loop limit cut them (Vulkan)
  // Daylight photons leaving an opening (a sky's portal, a sun's opening), those whose way out
  // met the scene (blocked outside: absorbed, no tally) and, of those, the ones that met glass.
  std::uint64_t opening_photons = 0, opening_blocked = 0, opening_glass = 0;

  explicit TallyBlock(std::size_t n = 0) : bins(n) {}
  void add(const TallyBlock& o) {
    for (std::size_t i = 0; i < bins.size(); ++i) {
      bins[i].sum += o.bins[i].sum;
      bins[i].sum_sq += o.bins[i].sum_sq;
    }
    add_counts(o);
  }
  /// Adds `o`'s path and segment counters (not its bins: callers that lay bins out
  /// differently place those themselves).
  void add_counts(const TallyBlock& o) {
    ray_segments += o.ray_segments;
    capped_paths += o.capped_paths;
    cut_paths += o.cut_paths;
    retried_paths += o.retried_paths;
    opening_photons += o.opening_photons;
    opening_blocked += o.opening_blocked;
    opening_glass += o.opening_glass;
  }
};

/// A shadow ray of next-event estimation (direct/next_event.hpp): is anything of the scene on
/// origin + t * direction for 0 < t < t_max? Virtual grids are not geometry: they never block.
struct ShadowRay {
  vec3 origin{0.0f};
  float t_max = 0.0f;
  vec3 direction{0.0f, 0.0f, 1.0f};  // unit
  float pad = 0.0f;                  // 32 bytes: the GPU's std430 layout as is
};

/// A diffuse vertex of a photon path (estimate/reflection_connection.hpp): where the path's next
/// segment would start (offset off the surface as trace() offsets it) and the unit normal of the
/// side it leaves from. Vertex j of a path (j >= 1: after j segments) is kept only where trace()
/// would trace its next segment (j <= max_bounces) and the reflectance is above 0.
struct PathVertex {
  vec3 origin{0.0f};
  float reflectance = 0.0f;
  vec3 normal{0.0f, 0.0f, 1.0f};
  std::uint32_t path = 0;  ///< index within the request: photon first + path
};

class Backend {
 public:
  virtual ~Backend() = default;
  virtual std::string name() const = 0;
  /// What it traces on, for the results' provenance ("CPU: <model> (Embree 3.13.5)", the
  /// Vulkan device's name and driver).
  virtual std::string device() const { return name(); }
  /// Traces, for each range, photons [first, first + count) of its group's stream with
  /// `seed` (PathRng(seed, i, group)), emitted from that group's luminaires, adding into
  /// `out`: group g's bin b at g * scene bins + b (out.bins.size() == groups x scene bins).
  /// Runs in the caller's TBB arena.
  virtual void trace(const std::vector<GroupRange>& ranges, std::uint64_t seed,
                     TallyBlock& out) = 0;
  /// Whether visible() works (next-event estimation needs it; without it the direct light is
  /// traced by photons).
  virtual bool traces_shadow_rays() const { return false; }
  /// out[i] = 1 when nothing of the scene (at its current transforms) lies on rays[i], else 0.
  /// Runs in the caller's TBB arena. Throws DeviceLimitError where a device limit leaves a ray
  /// undecided even traced alone.
  virtual void visible(std::span<const ShadowRay> rays, std::vector<std::uint8_t>& out) {
    (void)rays;
    (void)out;
    throw std::logic_error("the " + name() + " backend cannot trace shadow rays");
  }
  /// Whether path_vertices() works (the connection of reflected light to grids needs it).
  virtual bool traces_path_vertices() const { return false; }
  /// Appends to `out` the diffuse vertices of photons [first, first + count) of `group`, drawn
  /// from PathRng(seed, i, stream) and emitted as trace() emits them, each surviving a
  /// reflection with probability of its reflectance (the photon keeps its power) and leaving
  /// with a cosine lobe, in photon order. For scenes whose every material is diffuse: a path
  /// ends at any other. Runs in the caller's TBB arena. Throws DeviceLimitError where a device
  /// limit cuts a path even traced alone.
  virtual void path_vertices(std::uint32_t group, std::uint64_t first, std::uint64_t count,
                             std::uint64_t seed, std::uint32_t stream,
                             std::vector<PathVertex>& out) {
    (void)group, (void)first, (void)count, (void)seed, (void)stream, (void)out;
    throw std::logic_error("the " + name() + " backend cannot trace path vertices");
  }
  /// Whether set_quasi_random() works (sampler "sobol": run/replicate_run.hpp).
  virtual bool traces_quasi_random() const { return false; }
  /// On: each path's first draws are the scrambled Sobol' point of its photon index, scrambled
  /// by `seed` and its group (model/sobol.hpp); off: Philox only (the default).
  virtual void set_quasi_random(bool on) {
    if (on) throw std::logic_error("the " + name() + " backend has no quasi-random photons");
  }
  /// PreparedScene::luminaires changed (backends holding copies re-upload them).
  virtual void luminaires_changed() {}
  /// Moves a movable mesh; `transform` maps its prepared coordinates to local world space
  /// (rigid). Backends without instancing refuse.
  virtual void set_mesh_transform(std::size_t mesh, const glm::mat4& transform) {
    (void)mesh;
    (void)transform;
    throw std::runtime_error("the " + name() + " backend cannot move geometry");
  }
};

/// The backend named "auto" or one of the registry's names (lightsolver/backends.hpp) for a
/// prepared scene; an unknown name is an InputError listing the names built. When "auto" had
/// to fall back (a GPU that failed to start), the reason is appended to `notes`.
std::unique_ptr<Backend> make_backend(const std::string& name, const PreparedScene& scene,
                                      std::vector<std::string>& notes);

}  // namespace lightsolver::detail
