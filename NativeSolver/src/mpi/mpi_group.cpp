// The MPI process group: non-blocking collectives waited on with a deadline, so a process
// that died or hangs makes the others fail in bounded time instead of blocking forever.
#include <mpi.h>

#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <thread>

#include "lightsolver/mpi.hpp"

namespace lightsolver::mpi {
namespace {

// Polls a request until it completes or timeout_seconds() pass.
void wait(MPI_Request& request, MPI_Comm comm, const char* what) {
  const double deadline = MPI_Wtime() + timeout_seconds();
  int done = 0;
  while (true) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    if (MPI_Wtime() > deadline) {
      int rank = 0;
      MPI_Comm_rank(comm, &rank);
      throw std::runtime_error("MPI rank " + std::to_string(rank) + ": no answer from the other " +
                               "processes within " + std::to_string(int(timeout_seconds())) +
                               " s (" + what + "): one of them failed or hangs");
    }
    std::this_thread::sleep_for(std::chrono::microseconds(100));
  }
}

class MpiGroup final : public ProcessGroup {
 public:
  explicit MpiGroup(MPI_Comm comm) : comm_(comm) {}
  int rank() const override {
    int r = 0;
    MPI_Comm_rank(comm_, &r);
    return r;
  }
  int size() const override {
    int s = 1;
    MPI_Comm_size(comm_, &s);
    return s;
  }
  // In chunks: MPI counts are ints.
  void sum(std::span<std::uint64_t> values) override {
    for (std::size_t at = 0; at < values.size(); at += kChunk) {
      const int n = static_cast<int>(std::min(kChunk, values.size() - at));
      MPI_Request request;
      MPI_Iallreduce(MPI_IN_PLACE, values.data() + at, n, MPI_UINT64_T, MPI_SUM, comm_, &request);
      wait(request, comm_, "sum of tallies");
    }
  }
  void broadcast(std::span<std::uint64_t> values) override {
    for (std::size_t at = 0; at < values.size(); at += kChunk) {
      const int n = static_cast<int>(std::min(kChunk, values.size() - at));
      MPI_Request request;
      MPI_Ibcast(values.data() + at, n, MPI_UINT64_T, 0, comm_, &request);
      wait(request, comm_, "rank 0's decision");
    }
  }

 private:
  static constexpr std::size_t kChunk = std::size_t(1) << 28;
  MPI_Comm comm_;
};

}  // namespace

bool built() { return true; }

double timeout_seconds() {
  const char* text = std::getenv("LIGHTSOLVER_MPI_TIMEOUT_S");
  if (text == nullptr) return 600.0;
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  return end != text && value > 0.0 ? value : 600.0;
}

Session::Session(int* argc, char*** argv) {
  int provided = 0;
  if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
    throw std::runtime_error("MPI_Init_thread failed");
  }
}

Session::~Session() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}

std::shared_ptr<ProcessGroup> Session::world() const {
  return std::make_shared<MpiGroup>(MPI_COMM_WORLD);
}

void Session::abort(const std::string& message, int code) const {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  std::fprintf(stderr, "lightsolver (MPI rank %d): %s\n", rank, message.c_str());
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);  // MPI_Abort does not return; keeps [[noreturn]] honest
}

std::shared_ptr<ProcessGroup> group_of_fortran_handle(std::int64_t handle) {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) throw std::runtime_error("MPI is not initialised (import mpi4py.MPI first)");
  return std::make_shared<MpiGroup>(MPI_Comm_f2c(static_cast<MPI_Fint>(handle)));
}

}  // namespace lightsolver::mpi
