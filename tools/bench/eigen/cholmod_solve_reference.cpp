#include "cholmod_solve_reference.hpp"

#include <cholmod.h>

#include <algorithm>
#include <chrono>
#include <limits>
#include <stdexcept>

namespace ffr::bench {

ReferenceSolve cholmod_reference_solve(const ffr::preproc::SparseMatrix& A, const Eigen::MatrixXd& B,
                                       int repeats) {
  cholmod_common c;
  cholmod_l_start(&c);
  c.print = 0;
  c.supernodal = CHOLMOD_SUPERNODAL;
  c.nmethods = 1;
  c.method[0].ordering = CHOLMOD_METIS;
  cholmod_sparse a{};
  a.nrow = a.ncol = static_cast<size_t>(A.rows());
  a.nzmax = static_cast<size_t>(A.nonZeros());
  a.p = const_cast<ffr::preproc::SparseMatrix::StorageIndex*>(A.outerIndexPtr());
  a.i = const_cast<ffr::preproc::SparseMatrix::StorageIndex*>(A.innerIndexPtr());
  a.x = const_cast<double*>(A.valuePtr());
  a.stype = 1;
  a.itype = CHOLMOD_LONG;
  a.xtype = CHOLMOD_REAL;
  a.dtype = CHOLMOD_DOUBLE;
  a.sorted = 1;
  a.packed = 1;
  cholmod_dense b{};
  b.nrow = static_cast<size_t>(B.rows());
  b.ncol = static_cast<size_t>(B.cols());
  b.nzmax = b.d = b.nrow;
  b.nzmax *= b.ncol;
  b.x = const_cast<double*>(B.data());
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  cholmod_factor* L = cholmod_l_analyze(&a, &c);
  cholmod_dense *X = nullptr, *Y = nullptr, *E = nullptr;
  ReferenceSolve r;
  r.seconds = std::numeric_limits<double>::infinity();
  bool ok = L && cholmod_l_factorize(&a, L, &c) && c.status == CHOLMOD_OK;
  for (int k = 0; ok && k < repeats; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    ok = cholmod_l_solve2(CHOLMOD_A, L, &b, nullptr, &X, nullptr, &Y, &E, &c);
    r.seconds = std::min(r.seconds, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  if (ok) r.X = Eigen::Map<const Eigen::MatrixXd>(static_cast<const double*>(X->x), B.rows(), B.cols());
  cholmod_l_free_dense(&X, &c);
  cholmod_l_free_dense(&Y, &c);
  cholmod_l_free_dense(&E, &c);
  cholmod_l_free_factor(&L, &c);
  cholmod_l_finish(&c);
  if (!ok) throw std::runtime_error("eigen_bench: CHOLMOD reference factorization or solve failed");
  return r;
}

}  // namespace ffr::bench
