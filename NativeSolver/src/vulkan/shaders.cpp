#include "vulkan/shaders.hpp"

namespace lightsolver::detail::shaders {
namespace {

constexpr std::uint32_t kTrace[] = {
#include "trace.spv.inc"
};

}  // namespace

std::span<const std::uint32_t> trace() { return kTrace; }

}  // namespace lightsolver::detail::shaders
