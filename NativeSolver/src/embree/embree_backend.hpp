#pragma once
// The CPU backend: Embree's rtcIntersect1 per segment, paths spread over TBB workers.
#include <memory>

#include "model/backend.hpp"

namespace lightsolver::detail {

/// Which path kernel traces (embree/path_kernel.hpp): the one the scene analysis picks, or the
/// general one with every effect compiled in (same tallies, for comparisons and benchmarks).
enum class EmbreeKernel { Specialised, General };

/// Builds the Embree scene for `scene` (which must outlive the backend). The kernel is the
/// specialised one unless the environment sets LIGHTSOLVER_EMBREE_KERNEL=general.
std::unique_ptr<Backend> make_embree_backend(const PreparedScene& scene);

/// The same with the kernel chosen by the caller.
std::unique_ptr<Backend> make_embree_backend(const PreparedScene& scene, EmbreeKernel kernel);

struct KernelFeatures;

/// The compiled kernel an Embree backend runs; throws std::logic_error for another backend.
KernelFeatures embree_kernel(const Backend& backend);

}  // namespace lightsolver::detail
