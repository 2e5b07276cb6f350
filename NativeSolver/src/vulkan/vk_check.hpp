#pragma once
// Turns failed Vulkan calls into std::runtime_error with a message a user can act on (device
// lost, out of memory, no driver), so callers can fall back or report instead of crashing.
#include <vulkan/vulkan.h>

#include <string>

namespace lightsolver::vkw {

/// Name of a VkResult ("VK_ERROR_DEVICE_LOST").
const char* result_name(VkResult r);

/// Throws std::runtime_error: "Vulkan: <what> failed: <result> (<advice>)".
[[noreturn]] void fail(VkResult r, const std::string& what);

/// Throws unless r == VK_SUCCESS.
inline void check(VkResult r, const char* what) {
  if (r != VK_SUCCESS) fail(r, what);
}

}  // namespace lightsolver::vkw
