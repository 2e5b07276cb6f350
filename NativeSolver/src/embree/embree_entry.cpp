// The Embree backend's entry in the backend registry (model/backend_registry.hpp).
#include "model/backend_registry.hpp"
#include "embree/embree_backend.hpp"

namespace lightsolver::detail {

BackendEntry embree_backend_entry() {
  return {"embree",
          "Embree ray tracing on the CPU cores",
          /*gpu=*/false,
          /*available=*/[] { return true; },  // linked in; runs on any CPU the build runs on
          /*auto_picks=*/[] { return true; },
          make_embree_backend};
}

}  // namespace lightsolver::detail
