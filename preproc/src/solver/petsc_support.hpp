#pragma once
// What the two SLEPc translation units share (slepc_backend.cpp, slepc_distributed.cpp): PETSc's
// error codes turned into the backend's exceptions, and owners that destroy PETSc objects on
// every way out of a function (PETSc objects are handles, not RAII types).
#if FFR_HAVE_SLEPC
#include <slepceps.h>

#include <sstream>
#include <stdexcept>

namespace ffr::preproc::detail {

inline void check(PetscErrorCode ierr, const char* call) {
  if (ierr == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(ierr, &text, nullptr);
  std::ostringstream o;
  o << "slepc backend: " << call << " failed: " << (text ? text : "PETSc error") << " (PETSc error " << ierr << ")";
  throw std::runtime_error(o.str());
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
