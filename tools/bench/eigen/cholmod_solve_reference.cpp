#include "cholmod_solve_reference.hpp"

// The library's own CHOLMOD glue (a silent cholmod_common with the project's supernodal
// settings, zero-copy views of Eigen storage), so that the peer runs as the library sets it up.
#include "../../../preproc/src/solver/cholmod_bridge.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <stdexcept>

namespace ffr::bench {

ReferenceSolve cholmod_reference_solve(const ffr::preproc::SparseMatrix& A, const Eigen::MatrixXd& B,
                                       int repeats) {
  namespace d = ffr::preproc::detail;
  d::CholmodCommon common;
  cholmod_common* c = common.get();
  c->nmethods = 1;
  c->method[0].ordering = CHOLMOD_METIS;
  cholmod_sparse a = d::view_upper(A);
  cholmod_dense b = d::view_dense(B.data(), static_cast<size_t>(B.rows()), static_cast<size_t>(B.cols()),
                                  static_cast<size_t>(B.rows()));
  cholmod_factor* L = cholmod_l_analyze(&a, c);
  cholmod_dense *X = nullptr, *Y = nullptr, *E = nullptr;
  ReferenceSolve r;
  r.seconds = std::numeric_limits<double>::infinity();
  bool ok = L && cholmod_l_factorize(&a, L, c) && c->status == CHOLMOD_OK;
  for (int k = 0; ok && k < repeats; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    ok = cholmod_l_solve2(CHOLMOD_A, L, &b, nullptr, &X, nullptr, &Y, &E, c);
    r.seconds = std::min(r.seconds, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  if (ok) r.X = Eigen::Map<const Eigen::MatrixXd>(static_cast<const double*>(X->x), B.rows(), B.cols());
  cholmod_l_free_dense(&X, c);
  cholmod_l_free_dense(&Y, c);
  cholmod_l_free_dense(&E, c);
  cholmod_l_free_factor(&L, c);
  if (!ok) throw std::runtime_error("eigen_bench: CHOLMOD reference factorization or solve failed");
  return r;
}

}  // namespace ffr::bench
