#include "vulkan/shaders.hpp"

namespace lightsolver::detail::shaders {
namespace {

constexpr std::uint32_t kTrace[] = {
#include "trace.spv.inc"
};

constexpr std::uint32_t kVisibility[] = {
#include "visibility.spv.inc"
};

constexpr std::uint32_t kPathVertices[] = {
#include "path_vertices.spv.inc"
};

}  // namespace

std::span<const std::uint32_t> trace() { return kTrace; }

std::span<const std::uint32_t> visibility() { return kVisibility; }

std::span<const std::uint32_t> path_vertices() { return kPathVertices; }

}  // namespace lightsolver::detail::shaders
