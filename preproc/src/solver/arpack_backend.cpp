// Second backend: ARPACK-ng's implicitly restarted Lanczos (dsaupd) with reverse
// communication in mode 3 (generalized shift-invert, bmat = 'G', which = 'LM'), followed by
// dseupd for the Ritz vectors. Reference: the dsaupd/dseupd header documentation of
// ARPACK-ng (SRC/dsaupd.f, "Mode 3: K*x = lambda*M*x, K symmetric, M symm. pos. semi-def.,
// OP = (inv[K - sigma*M])*M, B = M").
//
// We call the ISO C bindings dsaupd_c/dseupd_c that ARPACK-ng ships next to dsaupd_/dseupd_
// (same routines, same arguments, no hidden Fortran string-length arguments to get wrong).
// ARPACK keeps internal state in Fortran SAVE variables, so calls are serialized.

#include "eigen_backends.hpp"

#include <climits>
#include <mutex>
#include <sstream>
#include <vector>

extern "C" {
void dsaupd_c(int* ido, const char* bmat, int n, const char* which, int nev, double tol,
              double* resid, int ncv, double* v, int ldv, int* iparam, int* ipntr, double* workd,
              double* workl, int lworkl, int* info);
void dseupd_c(int rvec, const char* howmny, const int* select, double* d, double* z, int ldz,
              double sigma, const char* bmat, int n, const char* which, int nev, double tol,
              double* resid, int ncv, double* v, int ldv, int* iparam, int* ipntr, double* workd,
              double* workl, int lworkl, int* info);
}

namespace ffr::preproc::detail {

namespace {
std::mutex g_arpack_mutex;

std::string dsaupd_message(int info) {
  switch (info) {
    case 1: return "maximum number of restarts reached";
    case 3: return "no shifts could be applied during a cycle (increase ncv)";
    case -1: return "n must be positive";
    case -2: return "nev must be positive";
    case -3: return "ncv must satisfy nev < ncv <= n";
    case -9: return "starting vector is zero";
    case -9999: return "could not build a Lanczos factorization";
  }
  return "error code " + std::to_string(info);
}
}  // namespace

BackendOutcome run_arpack(ShiftInvertOp& op, MassOp& bop, const LanczosRequest& req) {
  BackendOutcome out;
  if (op.rows() > INT_MAX) {
    out.message = "ARPACK backend: the problem exceeds the 32-bit index range of libarpack";
    return out;
  }
  const int n = static_cast<int>(op.rows());
  const int nev = req.nev, ncv = req.ncv;
  std::lock_guard<std::mutex> lock(g_arpack_mutex);

  int ido = 0, info = 1;  // info = 1: resid holds our (projected) starting vector
  std::vector<double> resid(req.v0->data(), req.v0->data() + n);
  std::vector<double> v(static_cast<size_t>(n) * ncv), workd(3 * static_cast<size_t>(n));
  const int lworkl = ncv * (ncv + 8);
  std::vector<double> workl(lworkl);
  int iparam[11] = {0}, ipntr[11] = {0};
  iparam[0] = 1;                 // exact shifts
  iparam[2] = req.max_restarts;  // maximum number of Arnoldi update iterations
  iparam[6] = 3;                 // mode 3: shift-invert for the generalized problem
  std::vector<double> mx(n);

  for (;;) {
    dsaupd_c(&ido, "G", n, "LM", nev, req.tol, resid.data(), ncv, v.data(), n, iparam, ipntr,
             workd.data(), workl.data(), lworkl, &info);
    double* x = workd.data() + ipntr[0] - 1;
    double* y = workd.data() + ipntr[1] - 1;
    if (ido == -1) {         // y = OP x without M x at hand (initialization)
      bop.perform_op(x, mx.data());
      op.perform_op(mx.data(), y);
    } else if (ido == 1) {   // y = OP x with M x given in workd(ipntr(3))
      op.perform_op(workd.data() + ipntr[2] - 1, y);
    } else if (ido == 2) {   // y = M x (inner products)
      bop.perform_op(x, y);
    } else {
      break;  // 99: done (or an error reported in info)
    }
  }
  out.iterations = iparam[2];
  out.converged = iparam[4];
  if (info < 0 || info == 1 || info == 3) {
    std::ostringstream os;
    os << "ARPACK dsaupd: " << dsaupd_message(info) << " (" << out.converged << " of " << nev
       << " converged, ncv = " << ncv << ")";
    out.message = os.str();
    return out;
  }
  std::vector<int> select(ncv, 1);
  out.lambda.resize(nev);
  out.X.resize(n, nev);
  int einfo = 0;
  dseupd_c(1, "A", select.data(), out.lambda.data(), out.X.data(), n, req.sigma, "G", n, "LM",
           nev, req.tol, resid.data(), ncv, v.data(), n, iparam, ipntr, workd.data(),
           workl.data(), lworkl, &einfo);
  if (einfo != 0) {
    out.message = "ARPACK dseupd failed with info = " + std::to_string(einfo);
    return out;
  }
  out.converged = iparam[4];
  if (out.converged < nev) {
    std::ostringstream os;
    os << "ARPACK: only " << out.converged << " of " << nev << " eigenpairs converged";
    out.message = os.str();
    return out;
  }
  out.success = true;
  return out;
}

}  // namespace ffr::preproc::detail
