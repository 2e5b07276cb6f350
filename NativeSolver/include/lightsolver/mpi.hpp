#pragma once
/// \file mpi.hpp
/// The MPI process group (builds with LIGHTSOLVER_MPI; docs/cluster.md). Only the CLI and the
/// Python module include it; the core sees ProcessGroup.

#include <cstdint>
#include <memory>
#include <string>

#include "lightsolver/process_group.hpp"

namespace lightsolver::mpi {

/// True when this build has MPI.
bool built();

/// True when this process was started by an MPI launcher (mpirun, srun): the launcher's
/// environment says so. A plain start does not initialise MPI at all.
bool launched();

/// Initialises MPI for the process's lifetime (thread level "funneled": only the main thread
/// calls MPI; TBB workers trace). Finalises in the destructor; aborts the whole job when the
/// process ends with an error while the others may still wait (abort()).
class Session {
 public:
  Session(int* argc, char*** argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  /// The group of every process of the job (MPI_COMM_WORLD).
  std::shared_ptr<ProcessGroup> world() const;
  /// Ends every process of the job with `code` after printing `message` (rank-prefixed) to
  /// stderr: a failed rank must not leave the others waiting.
  [[noreturn]] void abort(const std::string& message, int code) const;
};

/// The group of an existing communicator given by its Fortran handle (mpi4py: `comm.py2f()`),
/// so the Python module needs no MPI headers of mpi4py's; MPI must be initialised by its owner.
std::shared_ptr<ProcessGroup> group_of_fortran_handle(std::int64_t handle);

/// Seconds a process waits for the others in one reduction before it declares the job failed
/// (LIGHTSOLVER_MPI_TIMEOUT_S, default 600).
double timeout_seconds();

}  // namespace lightsolver::mpi
