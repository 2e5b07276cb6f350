#pragma once
// The CPU backend: Embree's rtcIntersect1 per segment, paths spread over TBB workers.
#include <memory>

#include "core/backend.hpp"

namespace lightsolver::detail {

/// Builds the Embree scene for `scene` (which must outlive the backend).
std::unique_ptr<Backend> make_embree_backend(const PreparedScene& scene);

}  // namespace lightsolver::detail
