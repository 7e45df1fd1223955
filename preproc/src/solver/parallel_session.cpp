#include "ffr/preproc/solver/parallel_session.hpp"

#include <atomic>
#include <cstdlib>
#include <stdexcept>

#if FFR_HAVE_SLEPC
#include "petsc_support.hpp"

#include <slepcsys.h>  // and MPI's C interface, without its C++ bindings

#include <mutex>
#include <string>
#endif

namespace ffr::preproc {
namespace {
std::atomic<bool> g_active{false};
}  // namespace

bool parallel_session_active() { return g_active; }

#if FFR_HAVE_SLEPC

namespace {
std::mutex g_message_mutex;
std::string g_message;

// PETSc's error handler of the session: the first message of an error (where it was raised:
// MUMPS's INFOG codes are only in it) kept for the backend's exception, nothing printed, the
// error code returned as PetscReturnErrorHandler does.
PetscErrorCode keep_message(MPI_Comm, int, const char*, const char*, PetscErrorCode n, PetscErrorType p, const char* mess,
                            void*) {
  if (p == PETSC_ERROR_INITIAL) {
    std::lock_guard<std::mutex> lock(g_message_mutex);
    g_message = mess ? mess : "";
  }
  return n;
}
}  // namespace

std::string detail::last_petsc_message() {
  std::lock_guard<std::mutex> lock(g_message_mutex);
  return g_message;
}

bool slepc_available() { return true; }

ParallelSession::ParallelSession() {
  if (g_active.exchange(true)) throw std::runtime_error("parallel session: one is already active in this process");
  // Options from PETSC_OPTIONS only: the program's own arguments are not PETSc's.
  if (SlepcInitializeNoArguments() != 0) {
    g_active = false;
    throw std::runtime_error("parallel session: SLEPc (and MPI) could not be initialized");
  }
  // Errors come back as codes (the backend turns them into exceptions with PETSc's text) rather
  // than a traceback on stderr; and the process keeps its own handling of signals.
  PetscPushErrorHandler(keep_message, nullptr);
  PetscPopSignalHandler();
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank_);
  MPI_Comm_size(PETSC_COMM_WORLD, &size_);
}

ParallelSession::~ParallelSession() {
  PetscPopErrorHandler();
  SlepcFinalize();
  g_active = false;
}

void ParallelSession::barrier() const { MPI_Barrier(PETSC_COMM_WORLD); }

void ParallelSession::abort(int status) const {
  MPI_Abort(MPI_COMM_WORLD, status);
  std::abort();  // MPI_Abort does not return
}

#else

bool slepc_available() { return false; }

ParallelSession::ParallelSession() {
  throw std::runtime_error(
      "the slepc backend is not built into this program (configure with -DFFR_SLEPC=ON and Debian's slepc-dev, "
      "petsc-dev and libopenmpi-dev)");
}
ParallelSession::~ParallelSession() = default;
void ParallelSession::barrier() const {}
void ParallelSession::abort(int status) const { std::exit(status); }

#endif

}  // namespace ffr::preproc
