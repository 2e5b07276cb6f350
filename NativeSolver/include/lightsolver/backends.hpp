#pragma once
/// \file backends.hpp
/// The tracing backends built into this library: the one list that SolveOptions::backend is
/// checked against and that the CLI's --backend, the Python module's backends() and the
/// workbench's Backend property take their names from. Which backends exist depends on the
/// build (Embree always; Vulkan where it was found), never on a list spelled elsewhere.

#include <optional>
#include <string>
#include <vector>

namespace lightsolver {

/// The backend name that lets the machine decide: the first GPU backend that finds a real GPU
/// (a CPU implementation such as Mesa lavapipe is slower than Embree, so it is used only when
/// asked for by name), else the CPU backend (Embree). When a GPU fails to start, the run falls
/// back to the CPU and says why in its warnings.
inline constexpr const char* kAutoBackend = "auto";

/// One value that SolveOptions::backend (and Simulation::Options::backend) accepts.
struct BackendInfo {
  std::string name;         ///< "auto", "embree", "vulkan" (where built), ...
  std::string description;  ///< one line for help texts
  bool gpu = false;         ///< traces through a GPU API (false for "auto", which chooses)
  /// Whether it can start on this machine (a device exists); set by available_backends()
  /// only, because finding out loads the GPU drivers. "auto" is available when any backend is.
  std::optional<bool> available;
};

/// "auto" first, then every backend built into this library in build order. Cheap: loads no
/// driver, so command-line help can use it.
std::vector<BackendInfo> backends();

/// backends() with `available` set for each (looks for Vulkan devices). Never throws.
std::vector<BackendInfo> available_backends();

/// The names of backends(), "auto" first.
std::vector<std::string> backend_names();

}  // namespace lightsolver
