#pragma once
// SPIR-V of the library's compute shaders, compiled from Shaders/ by glslc at build time and
// embedded as uint32 arrays.
#include <cstdint>
#include <span>

namespace lightsolver::detail::shaders {

std::span<const std::uint32_t> trace();
std::span<const std::uint32_t> visibility();
std::span<const std::uint32_t> path_vertices();

}  // namespace lightsolver::detail::shaders
