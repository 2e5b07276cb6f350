// The backend registry's queries and make_backend(). Names are looked up in the list that
// CMake generates from the backend modules built (model/backend_registry.hpp).
#include "lightsolver/backends.hpp"

#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "model/backend_registry.hpp"
#include "lightsolver/error.hpp"
#include "lightsolver/timings.hpp"

namespace lightsolver {
namespace {

using detail::Backend;
using detail::backend_entries;
using detail::BackendEntry;

// "auto, embree or vulkan"
std::string spoken_list(const std::vector<std::string>& names) {
  std::string text;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) text += i + 1 == names.size() ? " or " : ", ";
    text += names[i];
  }
  return text;
}

// "a real GPU through vulkan when one is usable, else embree", from the entries built.
std::string auto_description() {
  std::vector<std::string> gpu, cpu;
  for (const BackendEntry& e : backend_entries()) (e.gpu ? gpu : cpu).push_back(e.name);
  std::string cpu_part = cpu.empty() ? "" : cpu.front();
  if (gpu.empty()) return cpu_part + " (this build has no GPU backend)";
  return "a real GPU through " + spoken_list(gpu) + " when one is usable" +
         (cpu.empty() ? "" : ", else " + cpu_part);
}

// Whether `folder` holds an entry whose name starts with `prefix` (false when it cannot be read).
bool has_entry_starting(const char* folder, const std::string& prefix) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().filename().string().rfind(prefix, 0) == 0) return true;
  }
  return false;
}

// Whether the machine shows any GPU device at all. On Linux every GPU driver a GPU API reaches
// exposes a device node: a DRM render node (/dev/dri/renderD*: Mesa, AMD, Intel, virtio and
// NVIDIA's DRM module), NVIDIA's /dev/nvidia*, or WSL2's /dev/dxg. Where there is none, no
// GPU backend can find a real GPU, so "auto" skips their probes: creating a Vulkan instance
// loads every installed driver and costs tens of milliseconds, more than reading and preparing
// a 50k-triangle scene. Elsewhere (not Linux) the backends' own probes decide.
bool gpu_device_visible() {
#ifdef __linux__
  std::error_code ec;
  return std::filesystem::exists("/dev/dxg", ec) || has_entry_starting("/dev/dri", "renderD") ||
         has_entry_starting("/dev", "nvidia");
#else
  return true;
#endif
}

// What "auto" takes, in order: GPU backends that find a real GPU, then CPU backends.
std::vector<const BackendEntry*> auto_candidates() {
  std::vector<const BackendEntry*> out;
  const bool gpu_visible = gpu_device_visible();
  for (const bool gpu : {true, false}) {
    if (gpu && !gpu_visible) continue;
    for (const BackendEntry& e : backend_entries()) {
      if (e.gpu == gpu && e.auto_picks()) out.push_back(&e);
    }
  }
  return out;
}

// `backend`, with a note in `notes` when GPU backends tried before it failed (`why`).
std::unique_ptr<Backend> noting_fallback(std::unique_ptr<Backend> backend, const BackendEntry& e,
                                         const std::string& why, std::vector<std::string>& notes) {
  if (!why.empty()) {
    notes.push_back("the GPU could not be used, traced " +
                    (e.gpu ? "with " + std::string(e.name) : std::string("on the CPU")) +
                    " instead: " + why);
  }
  return backend;
}

std::unique_ptr<Backend> make_auto(const detail::PreparedScene& scene,
                                   std::vector<std::string>& notes) {
  std::string why;  // what the GPU backends tried so far said
  const std::vector<const BackendEntry*> candidates = [] {
    const timings::Scope phase("choose backend (auto probe)");
    return auto_candidates();
  }();
  const timings::Scope phase("build backend");
  for (const BackendEntry* e : candidates) {
    if (!e->gpu) return noting_fallback(e->make(scene), *e, why, notes);
    try {
      return noting_fallback(e->make(scene), *e, why, notes);
    } catch (const std::runtime_error& error) {
      why += (why.empty() ? "" : "; ") + std::string(error.what());
    }
  }
  throw std::runtime_error("no tracing backend could start" + (why.empty() ? "" : ": " + why));
}

}  // namespace

std::vector<BackendInfo> backends() {
  std::vector<BackendInfo> out{{kAutoBackend, auto_description(), false, std::nullopt}};
  for (const BackendEntry& e : backend_entries()) {
    out.push_back({e.name, e.description, e.gpu, std::nullopt});
  }
  return out;
}

std::vector<BackendInfo> available_backends() {
  std::vector<BackendInfo> out = backends();
  bool any = false;
  for (std::size_t i = 1; i < out.size(); ++i) {
    out[i].available = backend_entries()[i - 1].available();
    any = any || *out[i].available;
  }
  out.front().available = any;
  return out;
}

std::vector<std::string> backend_names() {
  std::vector<std::string> names{kAutoBackend};
  for (const BackendEntry& e : backend_entries()) names.emplace_back(e.name);
  return names;
}

namespace detail {

std::unique_ptr<Backend> make_backend(const std::string& name, const PreparedScene& scene,
                                      std::vector<std::string>& notes) {
  if (name == kAutoBackend) return make_auto(scene, notes);
  for (const BackendEntry& e : backend_entries()) {
    if (name != e.name) continue;
    const timings::Scope phase("build backend");
    return e.make(scene);
  }
  throw InputError(
      "", "backend",
      "unknown backend \"" + name + "\" (expected " + spoken_list(backend_names()) + ")");
}

}  // namespace detail
}  // namespace lightsolver
