// The Vulkan backend's entry in the backend registry (model/backend_registry.hpp).
#include "model/backend_registry.hpp"
#include "vulkan/context.hpp"
#include "vulkan/vulkan_backend.hpp"

namespace lightsolver::detail {

BackendEntry vulkan_backend_entry() {
  return {"vulkan",
          "Vulkan compute on the best device: a GPU, else a CPU implementation such as lavapipe",
          /*gpu=*/true,
          /*available=*/[] { return vkw::Context::device_available(true); },
          /*auto_picks=*/vulkan_gpu_available,
          make_vulkan_backend};
}

}  // namespace lightsolver::detail
