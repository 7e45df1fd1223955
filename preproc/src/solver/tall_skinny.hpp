#pragma once
// Products of a tall basis Q (n x k, k up to a few hundred) with thin blocks (n x p, p about
// 4): the block Gram-Schmidt of the block Lanczos backend. Each kernel streams the rows
// [r0, r1) of Q once, in chunks whose slice of the thin block stays in L1.
//
// Why not Eigen's GEMM: it packs the whole operand Q into a buffer before multiplying, so a
// product with 4 columns reads Q, writes its copy and reads that again. On the 100k-DOF
// plate's basis (88 columns, 72 MB) Q^T V took 10.9 ms and V -= Q C 20.8 ms that way, against
// the 3.5 ms that one read of Q at memory speed takes.

#include <cstdint>

namespace ffr::preproc::detail {

/// C += Q(r0:r1, :)^T V(r0:r1, :). Q is n x k (leading dimension ldq), V is n x p (ldv), C is
/// k x p with leading dimension k; all column-major.
void add_transposed_product(const double* Q, std::int64_t ldq, std::int64_t k, const double* V, std::int64_t ldv,
                            std::int64_t p, std::int64_t r0, std::int64_t r1, double* C);

/// V(r0:r1, :) -= Q(r0:r1, :) C, with the shapes of add_transposed_product.
void subtract_product(const double* Q, std::int64_t ldq, std::int64_t k, const double* C, std::int64_t p,
                      std::int64_t r0, std::int64_t r1, double* V, std::int64_t ldv);

}  // namespace ffr::preproc::detail
