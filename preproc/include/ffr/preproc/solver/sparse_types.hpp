#pragma once
// The sparse matrix type the FE assembly produces and the solver layer consumes.
//
// Storage convention for symmetric matrices (stiffness K, mass M, K - sigma*M):
//   * full storage (both triangles) is the normal case and is what the assembly produces;
//   * upper-only storage (entries with row <= col only) is accepted as well.
// The factorization reads the upper triangle only (CHOLMOD stype = +1); products with a
// symmetric matrix go through sym_multiply(), which picks the plain product for full
// storage and Eigen's selfadjointView<Upper> for upper-only storage. Lower-only storage is
// NOT accepted: it would be read as a diagonal matrix, so detect_storage() reports it and
// the solvers refuse it.
//
// 64-bit indices throughout: several million DOF with ~100 entries per row overflow int32
// nonzero counts, and CHOLMOD's cholmod_l_* API takes SuiteSparse_long (= int64 on LP64).

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <cstdint>

namespace ffr::preproc {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, std::int64_t>;

/// What the products and the eigen-solvers read: a compressed SparseMatrix, or a Map of
/// arrays held elsewhere (the reductions' mass matrix on the stiffness matrix's index arrays,
/// reduction.cpp), without a copy. An uncompressed SparseMatrix is copied into a compressed
/// one for the call.
using SparseRef = Eigen::Ref<const SparseMatrix, Eigen::StandardCompressedFormat>;

enum class SymmetricStorage {
  Full,       ///< both triangles stored
  UpperOnly,  ///< only row <= col stored (the lower triangle is implied)
  LowerOnly,  ///< only row >= col stored with at least one strictly-lower entry: refused
  Diagonal,   ///< no off-diagonal entries (either convention)
};

/// Classifies how a square matrix stores its symmetric entries. O(nnz), no allocation.
SymmetricStorage detect_storage(const SparseRef& A);

/// y = A x for a symmetric A given in full or upper-only storage (see above).
Eigen::MatrixXd sym_multiply(const SparseRef& A, SymmetricStorage storage,
                             const Eigen::Ref<const Eigen::MatrixXd>& X);

/// The same into Y (resized when it is not A.rows() x X.cols(); Y must not be X): no new
/// n x m result where the caller keeps one (the block Lanczos's loop).
void sym_multiply(const SparseRef& A, SymmetricStorage storage, const Eigen::Ref<const Eigen::MatrixXd>& X,
                  Eigen::MatrixXd& Y);

/// Largest absolute column sum of the symmetric matrix, taking implied lower entries into
/// account (the 1-norm, equal to the infinity-norm for symmetric A). O(nnz).
double sym_norm1(const SparseRef& A, SymmetricStorage storage);

/// Always-on input validation shared by the factorization and the eigen-solver: square,
/// finite values, accepted storage, and (for full storage) numerical symmetry checked with
/// a random probe |x^T A y - y^T A x| <= tol * ||A||_1 ||x|| ||y|| (O(nnz), no transpose
/// copy). Throws std::invalid_argument whose message starts with `what` (e.g. "K").
SymmetricStorage validate_symmetric(const SparseRef& A, const char* what,
                                    double symmetry_tol = 1e-10);

}  // namespace ffr::preproc
