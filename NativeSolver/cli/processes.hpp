#pragma once
// The processes sharing this command's runs under mpirun (docs/cluster.md): set once by main();
// null when the command runs alone. Only rank 0 prints and writes files.
#include <memory>

#include "lightsolver/process_group.hpp"

namespace lightsolver::cli {

inline std::shared_ptr<ProcessGroup>& processes() {
  static std::shared_ptr<ProcessGroup> group;
  return group;
}

/// False on the ranks other than 0 (they trace, rank 0 reports).
inline bool reports() { return !processes() || processes()->rank() == 0; }

}  // namespace lightsolver::cli
