#pragma once
// Products of a tall basis Q (n x k, k up to a few hundred) with thin blocks (n x p, p about
// 4): the block Gram-Schmidt of the block Lanczos backend, over parts of the rows on the
// caller's threads.
//
// The two products over a range of rows are a dgemm (a one-thread BLAS under the reducer's
// threads, ffr/cli/process_threads.hpp), or Eigen's where the BLAS's kernels fall short of the
// CPU (DenseKernelChoice::Auto, dense_kernels.hpp). Own kernels that stream Q once, without the
// BLAS's packing of Q, took about a third less time for them, but that was under 3 % of the
// 100k-DOF plate's run of tools/bench/reduce (RESULTS.md there), below the 5 % that an own
// kernel has to save to be kept.

#include <Eigen/Core>

#include <cstdint>

namespace ffr::preproc::detail {

/// C += Q(r0:r1, :)^T V(r0:r1, :). Q is n x k (leading dimension ldq), V is n x p (ldv), C is
/// k x p with leading dimension k; all column-major.
void add_transposed_product(const double* Q, std::int64_t ldq, std::int64_t k, const double* V, std::int64_t ldv,
                            std::int64_t p, std::int64_t r0, std::int64_t r1, double* C);

/// V(r0:r1, :) -= Q(r0:r1, :) C, with the shapes of add_transposed_product.
void subtract_product(const double* Q, std::int64_t ldq, std::int64_t k, const double* C, std::int64_t p,
                      std::int64_t r0, std::int64_t r1, double* V, std::int64_t ldv);

/// Q(:, 0:m) <- Q(:, 0:k) S for the k x m coefficients S (m <= k), written over Q a band of
/// rows at a time (a band's rows of the result need only the same rows of Q): the block
/// Lanczos's Ritz vectors and thick restarts, the Rayleigh-Ritz step of every backend's
/// vectors. Why: the basis is the eigen-solve's largest buffer after the factor (70 MB on the
/// 100k-DOF plate), and a separate n x m result, with the temporary of the product, raised the
/// process's peak by two more n x m matrices (32 MB measured with heaptrack at 20 modes, at the
/// end of the Lanczos stage, which set the peak of the whole run at 1 thread).
/// The bands run on up to max_threads() threads.
void rotate_columns_in_place(Eigen::MatrixXd& Q, Eigen::Index k, const Eigen::Ref<const Eigen::MatrixXd>& S);

/// A^T B (A n x k, B n x p, both with unit inner stride), with add_transposed_product over
/// parts of the rows on up to max_threads() threads, the parts' sums added in order. Why: the
/// Gram matrices of the block Lanczos's normalizations and of the eigen-solver's checks as one
/// product ran on one thread while the other core waited.
Eigen::MatrixXd transposed_product(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& B);

/// X <- X U^{-1} for an upper-triangular p x p U (X n x p), over parts of the rows on up to
/// max_threads() threads (each row is independent).
void solve_upper_on_right(const Eigen::Ref<const Eigen::MatrixXd>& U, Eigen::MatrixXd& X);

}  // namespace ffr::preproc::detail
