#pragma once
// The MPI and SLEPc session of a process that runs the distributed eigen-solver backend
// "slepc" (reduction.backend, preproc/PART_FILE.md). The library never starts it by itself:
// the program decides (ffr-reduce does so when the part asks for that backend), constructs one
// ParallelSession for the whole run and keeps it until the end, and every rank of the job runs
// the same pipeline. Without the backend built in (cmake -DFFR_SLEPC=OFF, or the packages
// missing) the constructor throws and slepc_available() is false.

#include <string>

namespace ffr::preproc {

/// Whether this build has the slepc backend (SLEPc, PETSc and MPI linked in).
bool slepc_available();

/// Whether a ParallelSession is alive in this process (the slepc backend needs one).
bool parallel_session_active();

class ParallelSession {
 public:
  /// Starts MPI (if the process has not) and SLEPc. PETSc reads its options from the
  /// environment variable PETSC_OPTIONS only, never from the program's command line. PETSc's
  /// errors are returned to the backend (which throws), not printed. Throws std::runtime_error
  /// if the backend is not built in, a session is already active, or initialization fails.
  ParallelSession();
  ~ParallelSession();
  ParallelSession(const ParallelSession&) = delete;
  ParallelSession& operator=(const ParallelSession&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  /// Collective: returns on every rank once every rank has called it.
  void barrier() const;
  /// Ends every rank of the job with `status` (MPI_Abort): for a rank that failed while the
  /// others may be waiting for it in a collective operation.
  [[noreturn]] void abort(int status) const;

 private:
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace ffr::preproc
