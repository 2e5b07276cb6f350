// Builds without MPI (LIGHTSOLVER_MPI=OFF or no MPI found): the same API, refusing clearly.
#include <cstdlib>
#include <stdexcept>

#include "lightsolver/mpi.hpp"

namespace lightsolver::mpi {
namespace {
const char* kNoMpi =
    "this lightsolver was built without MPI (configure with OpenMPI installed and "
    "-DLIGHTSOLVER_MPI=ON)";
}

bool built() { return false; }

double timeout_seconds() { return 600.0; }

Session::Session(int*, char***) { throw std::runtime_error(kNoMpi); }
Session::~Session() = default;
std::shared_ptr<ProcessGroup> Session::world() const { throw std::runtime_error(kNoMpi); }
void Session::abort(const std::string&, int code) const { std::exit(code); }
std::shared_ptr<ProcessGroup> group_of_fortran_handle(std::int64_t) {
  throw std::runtime_error(kNoMpi);
}

}  // namespace lightsolver::mpi
