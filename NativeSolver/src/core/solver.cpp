// Backend selection and the one-shot solve(): a Simulation used once.
#include "lightsolver/solver.hpp"

#include "core/backend.hpp"
#ifdef LIGHTSOLVER_HAVE_VULKAN
#include "vulkan/vulkan_backend.hpp"
#endif
#include "lightsolver/simulation.hpp"

namespace lightsolver {
namespace detail {

// "auto": a real GPU through Vulkan when one is usable, else Embree (lavapipe is slower than
// Embree, so a CPU Vulkan device is used only when asked for by name).
std::unique_ptr<Backend> make_backend(const std::string& name, const PreparedScene& scene,
                                      std::vector<std::string>& notes) {
  if (name == "embree") return make_embree_backend(scene);
#ifdef LIGHTSOLVER_HAVE_VULKAN
  if (name == "vulkan") return make_vulkan_backend(scene);
  if (name == "auto" && vulkan_gpu_available()) {
    try {
      return make_vulkan_backend(scene);
    } catch (const std::runtime_error& e) {
      notes.push_back(std::string("the GPU could not be used, traced on the CPU instead: ") +
                      e.what());
    }
  }
  const char* expected = "expected auto, embree or vulkan";
#else
  const char* expected = "expected auto or embree";
#endif
  if (name == "auto") return make_embree_backend(scene);
  throw InputError("", "backend", "unknown backend \"" + name + "\" (" + expected + ")");
}

}  // namespace detail

const char* version() { return LIGHTSOLVER_VERSION; }

Results solve(const Scene& scene, const SolveOptions& options, const ProgressFn& progress) {
  Simulation::Options sim;
  sim.backend = options.backend;
  sim.threads = options.threads;
  Simulation simulation(scene, sim);
  return simulation.run(options, progress);
}

}  // namespace lightsolver
