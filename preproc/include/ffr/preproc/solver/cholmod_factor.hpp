#pragma once
// Sparse Cholesky factorization A = P^T L L^T P on CHOLMOD's analysis (SuiteSparse 5.12, 64-bit
// cholmod_l_* API, supernodal, fill-reducing ordering METIS by default), its numeric part by one
// of two backends (FactorizationBackend): the own supernodal code or CHOLMOD's own.
//
//   CholmodFactor f;                       // options: ordering, memory limit, singularity floor
//   auto stats = f.analyze(K);             // symbolic: nnz(L), flops, memory estimate
//   f.factorize(K);                        // numeric; refuses if it would not fit
//   Eigen::MatrixXd U = f.solve(F);        // many load cases, one factorization
//
// Input: symmetric, full or upper-only storage (only the upper triangle is read; see
// sparse_types.hpp). The matrix is passed to CHOLMOD without copying.
// The library never prints; statistics come back in FactorStatistics / info().
// Not thread-safe: solve() reuses internal workspace (one factor per thread if needed).

#include "ffr/preproc/solver/dense_kernel_choice.hpp"
#include "ffr/preproc/solver/solver_errors.hpp"
#include "ffr/preproc/solver/sparse_types.hpp"

#include <cstdint>
#include <concepts>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace ffr::preproc {

namespace detail {
struct QuotientGraph;  // solver/nodal_ordering.hpp: column groups and their graph
}

enum class Ordering {
  Metis,    ///< METIS nested dissection (default: best for 3D FE meshes)
  Nesdis,   ///< CHOLMOD's own nested dissection (METIS + constrained AMD)
  Amd,      ///< approximate minimum degree: fast, good for 2D / shells
  Natural,  ///< no permutation (tests and tiny problems)
  Auto,     ///< CHOLMOD's default strategy: AMD, then METIS if AMD fills badly
};
const char* to_string(Ordering o);

/// The numeric side of the sparse Cholesky factorization. Both backends share CHOLMOD's symbolic
/// analysis (ordering, elimination tree, supernodes) and the checks after it (memory, pivots).
enum class FactorizationBackend {
  /// The own supernodal code (tree_cholesky.hpp, supernodal_solve.hpp): the numeric factor in
  /// arrays of its own, computed with the independent subtrees of the elimination tree on
  /// threads, packed for the substitutions, which apply each factor entry to a whole block of
  /// right-hand sides at once. CHOLMOD's structures are only read. The default: the faster one
  /// for the eigen-solver's blocks of solves (tools/bench/reduce/RESULTS.md).
  Supernodal,
  /// CHOLMOD's own cholmod_l_factorize and cholmod_l_solve2, untouched: the reference.
  Cholmod,
};
const char* to_string(FactorizationBackend b);
/// "supernodal" or "cholmod" (the part file's reduction.factorization); nullopt for anything else.
std::optional<FactorizationBackend> factorization_backend_from_string(const std::string& name);

struct FactorOptions {
  Ordering ordering = Ordering::Metis;
  /// Refuse to factorize when the estimated peak exceeds this many bytes. 0 = no user limit
  /// (the available memory of the machine/container still applies).
  std::uint64_t memory_limit_bytes = 0;
  /// Refuse a factor with a pivot L_jj^2 below min_pivot_ratio * A_jj (its own diagonal
  /// entry): the matrix is singular to working precision even though every pivot came out
  /// positive (rounding decides the sign of a zero pivot). This is MSC Nastran's MAXRATIO
  /// test (ratio A_jj / D_jj of the matrix diagonal to the factor diagonal, "nearly
  /// singular (having mechanisms)" above the default 1.E7; Nastran Quick Reference Guide,
  /// PARAM MAXRATIO), so the default here is its inverse. Measured on free (singular) 3D
  /// Laplacians the rounding-level pivot ratio grows with size: ~1e-13 at 1e3 DOF, ~4e-12
  /// at 7e4 DOF; nonsingular ones stay above 1e-5 (see tests/solver). Relative to the own
  /// diagonal, not to max L_jj^2 as CHOLMOD's rcond, so that DOFs of very different scale
  /// (rotations next to translations) do not trigger it. 0 disables the check.
  double min_pivot_ratio = 1e-7;
  /// Validate every input (square, finite, accepted storage, symmetry probe; O(nnz)). Off
  /// only when the caller has validated the matrices already.
  bool check_symmetry = true;
  /// Which numeric factorization and substitutions run on CHOLMOD's analysis (both give the
  /// same factor up to rounding): see FactorizationBackend.
  FactorizationBackend backend = FactorizationBackend::Supernodal;
  /// The dense kernels of the supernodal backend's factorization (CHOLMOD's own calls the BLAS).
  DenseKernelChoice dense_kernels = DenseKernelChoice::Auto;
};

struct FactorStatistics {
  std::int64_t n = 0;              ///< matrix dimension
  std::int64_t nnz_A = 0;          ///< entries of the upper triangle given to CHOLMOD
  double nnz_L = 0;                ///< nnz(L) of the "pure" factor (Common->lnz)
  std::int64_t factor_entries = 0; ///< stored values incl. supernodal amalgamation zeros (L->xsize)
  std::int64_t packed_entries = 0; ///< values kept after factorize, for the substitutions (supernodal
                                   ///< backend: most of the diagonal blocks' upper triangles dropped)
  double flops = 0;                ///< flop count of the LL^T factorization (Common->fl)
  std::int64_t supernodes = 0;
  std::uint64_t factor_bytes = 0;  ///< estimated size of the numeric factor
  std::uint64_t peak_bytes = 0;    ///< estimated peak during factorization (factor + workspace)
  std::string ordering;            ///< ordering actually used (L->ordering): "METIS", "AMD", ...
  std::int64_t ordering_vertices = 0;  ///< vertices of the graph ordered: n, or the nodes (METIS on the node graph)
  int analyses = 0;                ///< symbolic analyses this factor has done (factorize adds one for a new structure)
  double analyze_seconds = 0;
  double factorize_seconds = 0;
  double rcond = 0;                ///< CHOLMOD's min(L_jj^2)/max(L_jj^2) after factorize
  double min_pivot_ratio = 0;      ///< min over j of L_jj^2 / A_jj after factorize
  std::int64_t min_pivot_column = -1;  ///< the column (input numbering) where it occurs
  std::uint64_t cholmod_peak_bytes = 0;  ///< measured peak of CHOLMOD's allocations
  int solve_threads = 0;           ///< threads of the substitutions after factorize (max_threads() at most)
  double solve_parallel_fraction = 0;  ///< share of the factor's entries they sweep in parallel
  double factor_parallel_fraction = 0;  ///< share of the flops factorized in parallel subtrees
  FactorizationBackend backend = FactorizationBackend::Supernodal;  ///< which one factorized
  std::string blas_kernels;        ///< OpenBLAS's kernels in use (openblas_get_corename), empty for another BLAS
  std::string blas_kernels_suited; ///< kernels this CPU would run, when those in use are older; else empty
  std::string dense_kernels;       ///< the factorization's dense kernels after factorize: "BLAS", "Eigen (x86-64-v4)", ...
};

enum class FactorStatus { Empty, Analyzed, Factorized, Failed };
const char* to_string(FactorStatus s);

struct FactorInfo {
  FactorStatus status = FactorStatus::Empty;
  std::string message;  ///< reason of the last failure, empty otherwise
  double shift = 0;     ///< sigma of the factorized A - sigma*B (0 after factorize(A))
  FactorStatistics stats;
};

/// The sparse Cholesky factorization: CHOLMOD's analysis, then the numeric backend of
/// FactorOptions::backend.
class CholmodFactor {
 public:
  explicit CholmodFactor(FactorOptions options = {});
  ~CholmodFactor();
  CholmodFactor(CholmodFactor&&) noexcept;
  CholmodFactor& operator=(CholmodFactor&&) noexcept;
  CholmodFactor(const CholmodFactor&) = delete;
  CholmodFactor& operator=(const CholmodFactor&) = delete;

  /// Symbolic analysis (ordering, elimination tree, supernodes). Throws std::invalid_argument
  /// for bad input, SolverError if CHOLMOD fails (e.g. out of memory in the ordering).
  const FactorStatistics& analyze(const SparseMatrix& A);

  /// The same with a fill-reducing order the caller computed: perm[k] = the column of A at
  /// position k, a permutation of 0 .. n-1; `vertices` = the size of the graph it was
  /// computed on and `name` what computed it (both reported in the statistics). Why: the reductions order the mesh's node
  /// graph before A's values exist, without forming A's own graph (10x its edges).
  /// Only A's structure is read (its upper triangle; the values may be unset): factorize checks
  /// the matrix it is given. Throws std::invalid_argument when perm is not a permutation of A's
  /// columns.
  const FactorStatistics& analyze(const SparseMatrix& A, const std::vector<std::int64_t>& perm, std::int64_t vertices,
                                  const std::string& name);

  /// The same from the graph of A's column groups (detail::grouped_symbolic: a mesh node's
  /// DOFs, whose columns have one structure), without A: perm must keep each group's columns
  /// together, in order; pattern_hash and upper_nnz are those of the upper triangle A will have
  /// (detail::PatternHash), which factorize checks. Why: the symbolic analysis of the node graph
  /// is several times cheaper than that of A (grouped_symbolic.hpp).
  const FactorStatistics& analyze_groups(const detail::QuotientGraph& q, const std::vector<std::int64_t>& perm,
                                         std::int64_t vertices, std::uint64_t pattern_hash, std::int64_t upper_nnz);

  /// Numeric factorization of A. Re-analyzes first if A's pattern differs from the analyzed
  /// one. Throws InsufficientMemoryError before allocating the factor if it would not fit,
  /// NotPositiveDefiniteError naming the failing column.
  void factorize(const SparseMatrix& A);

  /// Factorizes C = A - sigma*B. C is formed once, upper triangle only, by merging the two
  /// column patterns (no intermediate full-size sum).
  void factorize_shifted(const SparseRef& A, const SparseRef& B, double sigma);

  /// The same for C = shifted_upper(A, B, sigma) the caller already holds (e.g. built for
  /// analyze): C is not formed a second time, so only one copy lives during the numeric
  /// factorization. Throws std::invalid_argument if C has entries below the diagonal.
  void factorize_shifted_upper(const SparseMatrix& C, double sigma);

  /// X = A^{-1} B for a dense block of right-hand sides (one column per load case). Columns
  /// are solved up to 16 at a time, so the extra memory stays 16n doubles.
  Eigen::MatrixXd solve(const Eigen::Ref<const Eigen::MatrixXd>& B) const;

  /// x = A^{-1} b for one vector (the eigen-solver's operator); b and x may alias.
  void solve(const double* b, double* x) const;
  /// X = A^{-1} B into X (B's size; B and X may be the same matrix), without a new result.
  void solve(const Eigen::Ref<const Eigen::MatrixXd>& B, Eigen::Ref<Eigen::MatrixXd> X) const;

  std::int64_t rows() const;
  bool factorized() const;
  const FactorInfo& info() const;
  const FactorOptions& options() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// What the eigen-solver's operators and the reductions need of a sparse symmetric factorization
/// A = P^T L L^T P: a symbolic analysis of A's structure, a numeric factorization, solves of
/// blocks of right-hand sides, and a status. CholmodFactor meets it whichever backend it runs.
template <class F>
concept SymmetricFactorization = requires(F& f, const F& cf, const SparseMatrix& A,
                                          const Eigen::Ref<const Eigen::MatrixXd>& B, Eigen::Ref<Eigen::MatrixXd> X) {
  f.analyze(A);
  f.factorize(A);
  cf.solve(B, X);
  { cf.info() } -> std::convertible_to<const FactorInfo&>;
  { cf.rows() } -> std::convertible_to<std::int64_t>;
};

/// C = A - sigma*B, upper triangle only (row <= col), both inputs full or upper-only.
/// Exposed for tests and for callers that need the shifted matrix itself.
SparseMatrix shifted_upper(const SparseRef& A, const SparseRef& B, double sigma);

}  // namespace ffr::preproc
