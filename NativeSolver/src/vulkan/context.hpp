#pragma once
// Vulkan instance, device and compute queue (the "Manager" of Kompute, reduced to what a compute
// backend needs). Owns everything it creates and releases it in reverse order.
#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <string>

namespace lightsolver::vkw {

/// How to pick and set up the device.
struct ContextOptions {
  /// Accept a CPU implementation (lavapipe) when no GPU is present.
  bool allow_cpu = true;
  /// Enable VK_LAYER_KHRONOS_validation and count its messages; default: the environment
  /// variable LIGHTSOLVER_VULKAN_VALIDATION is set to something other than "0".
  bool validation = validation_requested();

  static bool validation_requested();
};

/// One logical device with one compute queue and a command pool.
class Context {
 public:
  /// Throws std::runtime_error when there is no driver or no device with shaderInt64 and
  /// 64-bit integer storage-buffer atomics.
  explicit Context(const ContextOptions& options = {});
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  VkCommandPool command_pool() const { return pool_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  std::string device_name() const { return properties_.deviceName; }

  /// A memory type allowed by `type_bits` with all of `wanted`, else with all of `fallback`.
  /// Throws when neither exists.
  std::uint32_t memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags wanted,
                            VkMemoryPropertyFlags fallback) const;
  VkMemoryPropertyFlags memory_flags(std::uint32_t type) const;

  /// True when a suitable device that is not a CPU implementation exists. Never throws.
  static bool gpu_available() { return device_available(false); }
  /// True when a suitable device exists, a CPU implementation counting when `allow_cpu`.
  /// Never throws.
  static bool device_available(bool allow_cpu);

  /// Validation-layer warnings and errors seen by any Context in this process.
  static std::size_t validation_message_count();

 private:
  void create_instance(bool validation);
  void pick_device(bool allow_cpu);
  void create_device();
  void release() noexcept;

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  std::uint32_t queue_family_ = 0;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  VkCommandPool pool_ = VK_NULL_HANDLE;
};

}  // namespace lightsolver::vkw
