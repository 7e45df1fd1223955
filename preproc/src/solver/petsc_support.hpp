#pragma once
// What the two SLEPc translation units share (slepc_backend.cpp, slepc_distributed.cpp): PETSc's
// error codes turned into the backend's exceptions, and owners that destroy PETSc objects on
// every way out of a function (PETSc objects are handles, not RAII types).
#if FFR_HAVE_SLEPC
#include <slepceps.h>

#include <sstream>
#include <stdexcept>
#include <string>

namespace ffr::preproc::detail {

/// The message PETSc gave with the latest error it raised (the ParallelSession's error handler
/// keeps it; PETSc's error codes alone say only the kind), empty before any.
std::string last_petsc_message();

/// Throws the backend's exception for a failed PETSc call, with `detail`: PETSc's message.
[[noreturn]] inline void fail(PetscErrorCode ierr, const char* call, const std::string& detail) {
  const char* text = nullptr;
  PetscErrorMessage(ierr, &text, nullptr);
  std::ostringstream o;
  o << "slepc backend: " << call << " failed: " << (text ? text : "PETSc error");
  if (!detail.empty()) o << ": " << detail;
  o << " (PETSc error " << ierr << ")";
  throw std::runtime_error(o.str());
}

inline void check(PetscErrorCode ierr, const char* call) {
  if (ierr != 0) fail(ierr, call, last_petsc_message());
}

struct MatGuard {
  Mat m = nullptr;
  ~MatGuard() { if (m) MatDestroy(&m); }
};
struct VecGuard {
  Vec v = nullptr;
  ~VecGuard() { if (v) VecDestroy(&v); }
};
struct EpsGuard {
  EPS e = nullptr;
  ~EpsGuard() { if (e) EPSDestroy(&e); }
};
struct ScatterGuard {
  VecScatter s = nullptr;
  ~ScatterGuard() { if (s) VecScatterDestroy(&s); }
};
struct KspGuard {
  KSP k = nullptr;
  ~KspGuard() { if (k) KSPDestroy(&k); }
};

}  // namespace ffr::preproc::detail
#endif
