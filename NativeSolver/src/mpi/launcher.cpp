// Whether an MPI launcher started this process: the same test with and without MPI built (a
// build without it must refuse rather than run the whole job once per process).
#include <cstdlib>

#include "lightsolver/mpi.hpp"

namespace lightsolver::mpi {

bool launched() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"}) {
    if (std::getenv(name) != nullptr) return true;
  }
  return false;
}

}  // namespace lightsolver::mpi
