#pragma once
// The Vulkan compute backend: the same photon paths as the Embree backend (same Philox streams,
// same physics, same bins), traced by Shaders/trace.comp through a BVH built by Embree.
#include <cstddef>
#include <memory>

#include "model/backend.hpp"

namespace lightsolver::detail {

/// Creates the backend on the best Vulkan device (a GPU if any, else a CPU implementation such
/// as lavapipe). Throws std::runtime_error with a clear message when there is no usable device,
/// the device is lost, memory runs out or the scene exceeds a device limit.
std::unique_ptr<Backend> make_vulkan_backend(const PreparedScene& scene);

/// True when a real GPU (not a CPU implementation) with the features the backend needs exists.
/// Never throws.
bool vulkan_gpu_available();

/// Validation-layer warnings and errors so far in this process (validation is enabled by the
/// environment variable LIGHTSOLVER_VULKAN_VALIDATION=1); tests require 0.
std::size_t vulkan_validation_message_count();

}  // namespace lightsolver::detail
