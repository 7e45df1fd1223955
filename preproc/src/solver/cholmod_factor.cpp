#include "ffr/preproc/solver/cholmod_factor.hpp"

#include "blas_kernels.hpp"
#include "cholmod_bridge.hpp"
#include "grouped_symbolic.hpp"
#include "library_threads.hpp"
#include "nodal_ordering.hpp"
#include "numeric_backends.hpp"
#include "pattern_hash.hpp"
#include "tree_cholesky.hpp"
#include "ffr/preproc/solver/memory.hpp"
#include "ffr/preproc/threads.hpp"
#include "../stopwatch.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <sstream>
#include <string>
#include <variant>

namespace ffr::preproc {

static_assert(SymmetricFactorization<CholmodFactor>);

const char* to_string(FactorizationBackend b) {
  switch (b) {
    case FactorizationBackend::Supernodal: return "supernodal";
    case FactorizationBackend::Cholmod: return "cholmod";
  }
  return "?";
}

std::optional<FactorizationBackend> factorization_backend_from_string(const std::string& name) {
  if (name == "supernodal") return FactorizationBackend::Supernodal;
  if (name == "cholmod") return FactorizationBackend::Cholmod;
  return std::nullopt;
}

const char* to_string(Ordering o) {
  switch (o) {
    case Ordering::Metis: return "METIS";
    case Ordering::Nesdis: return "NESDIS";
    case Ordering::Amd: return "AMD";
    case Ordering::Natural: return "natural";
    case Ordering::Auto: return "auto";
  }
  return "?";
}

const char* to_string(FactorStatus s) {
  switch (s) {
    case FactorStatus::Empty: return "empty";
    case FactorStatus::Analyzed: return "analyzed";
    case FactorStatus::Factorized: return "factorized";
    case FactorStatus::Failed: return "failed";
  }
  return "?";
}

namespace {

using Clock = std::chrono::steady_clock;

const char* ordering_name(int cholmod_ordering) {
  switch (cholmod_ordering) {
    case CHOLMOD_NATURAL: return "natural";
    case CHOLMOD_GIVEN: return "given";
    case CHOLMOD_AMD: return "AMD";
    case CHOLMOD_METIS: return "METIS";
    case CHOLMOD_NESDIS: return "NESDIS";
    case CHOLMOD_COLAMD: return "COLAMD";
    case CHOLMOD_POSTORDERED: return "natural (postordered)";
  }
  return "unknown";
}


}  // namespace

struct CholmodFactor::Impl {
  FactorOptions opt;
  detail::CholmodCommon common;  // declared before L: L is freed in ~Impl while common lives
  cholmod_factor* L = nullptr;   // CHOLMOD's analysis (and CHOLMOD's numeric factor for its backend)
  std::uint64_t pattern = 0;
  int analyses = 0;  // symbolic analyses done by this factor
  FactorInfo info;
  // The numeric factor and its solves, by the backend of opt.backend; set by each successful
  // factorization, cleared by a new analysis.
  std::variant<detail::SupernodalNumeric, detail::CholmodNumeric> numeric;
  // The numeric factorization's dense kernels (CHOLMOD's own factorization calls the BLAS).
  const detail::DenseKernels* dense = opt.backend == FactorizationBackend::Cholmod
                                          ? &detail::blas_dense_kernels()
                                          : &detail::select_dense_kernels(opt.dense_kernels);

  explicit Impl(FactorOptions o) : opt(o) {
    if (opt.backend == FactorizationBackend::Cholmod) numeric.emplace<detail::CholmodNumeric>();
    else std::get<detail::SupernodalNumeric>(numeric).use(*dense);
  }
  ~Impl() {
    clear_numeric();
    if (L) cholmod_l_free_factor(&L, common.get());
  }
  void clear_numeric() {
    std::visit([](auto& b) { b.clear(); }, numeric);
  }
  bool supernodal() const { return opt.backend == FactorizationBackend::Supernodal; }
  [[noreturn]] void fail(const std::string& msg) {
    info.status = FactorStatus::Failed;
    info.message = msg;
    throw SolverError(msg);
  }
  std::string cholmod_error(const char* what) {
    std::string e = detail::CholmodCommon::take_last_error();
    std::ostringstream os;
    os << what << " failed (CHOLMOD status " << common.get()->status << ")";
    if (!e.empty()) os << ": " << e;
    return os.str();
  }
  void analyze(const SparseMatrix& A, const detail::NodalOrdering* given = nullptr);
  void analyze_groups(const detail::QuotientGraph& q, const std::vector<std::int64_t>& perm, std::int64_t vertices,
                      std::uint64_t hash, std::int64_t upper_nnz);
  void record_analysis(std::int64_t n_cols, std::int64_t upper_nnz, double lnz, double flops, const std::string& ordering,
                       std::int64_t vertices, Clock::time_point t0);
  void factorize(const SparseMatrix& A, double shift);
  void check_memory(std::uint64_t needed);
  [[noreturn]] void throw_not_posdef(std::int64_t permuted, bool singular, double ratio);
};

void CholmodFactor::Impl::analyze(const SparseMatrix& A, const detail::NodalOrdering* given) {
  // With an order given, A is a structure only (its values are not read; factorize checks the
  // matrix it gets).
  if (opt.check_symmetry && !given) validate_symmetric(A, "matrix to factorize");
  else if (A.rows() != A.cols() || A.rows() == 0)
    throw std::invalid_argument("matrix to factorize: must be square and non-empty");
  cholmod_common* c = common.get();
  switch (opt.ordering) {
    case Ordering::Auto: c->nmethods = 0; break;
    case Ordering::Metis: c->nmethods = 1; c->method[0].ordering = CHOLMOD_METIS; break;
    case Ordering::Nesdis: c->nmethods = 1; c->method[0].ordering = CHOLMOD_NESDIS; break;
    case Ordering::Amd: c->nmethods = 1; c->method[0].ordering = CHOLMOD_AMD; break;
    case Ordering::Natural: c->nmethods = 1; c->method[0].ordering = CHOLMOD_NATURAL; break;
  }
  clear_numeric();
  if (L) cholmod_l_free_factor(&L, c);
  info = FactorInfo{};

  std::int64_t upper_nnz = 0;
  pattern = detail::upper_pattern_hash(A, &upper_nnz);
  cholmod_sparse view = detail::view_upper(A);
  if (given) {
    view.xtype = CHOLMOD_PATTERN;
    view.x = nullptr;
  }
  const auto t0 = Clock::now();
  // METIS on the node graph where the matrix has one (see nodal_ordering.hpp); CHOLMOD then
  // only post-orders it and does the symbolic factorization.
  detail::NodalOrdering nodal;
  if (given) nodal = *given;
  else if (opt.ordering == Ordering::Metis) nodal = detail::nodal_metis_ordering(A);
  if (!nodal.perm.empty()) {
    c->nmethods = 1;
    c->method[0].ordering = CHOLMOD_GIVEN;
    static_assert(sizeof(SuiteSparse_long) == sizeof(std::int64_t));
    L = cholmod_l_analyze_p(&view, reinterpret_cast<SuiteSparse_long*>(nodal.perm.data()), nullptr, 0, c);
  } else {
    L = cholmod_l_analyze(&view, c);
  }
  if (!L || c->status < CHOLMOD_OK) fail(cholmod_error("symbolic analysis (cholmod_l_analyze)"));
  if (!L->is_super) fail("symbolic analysis did not produce a supernodal factor");
  record_analysis(A.rows(), upper_nnz, c->lnz, c->fl, nodal.perm.empty() ? ordering_name(L->ordering) : "METIS",
                  nodal.perm.empty() ? A.rows() : nodal.groups, t0);
}

void CholmodFactor::Impl::analyze_groups(const detail::QuotientGraph& q, const std::vector<std::int64_t>& perm,
                                         std::int64_t vertices, std::uint64_t hash, std::int64_t upper_nnz) {
  cholmod_common* c = common.get();
  clear_numeric();
  if (L) cholmod_l_free_factor(&L, c);
  info = FactorInfo{};
  const auto t0 = Clock::now();
  const std::vector<std::int64_t> order = detail::group_order(q, perm);
  if (order.empty()) throw std::invalid_argument("matrix to factorize: the given order splits a group of columns");
  const detail::GroupedSymbolic g = detail::grouped_symbolic(q, order, c);
  L = g.L;
  if (!L) fail(cholmod_error("symbolic analysis of the node graph (cholmod_l_analyze_p)"));
  pattern = hash;
  record_analysis(q.first.back(), upper_nnz, g.lnz, g.flops, "METIS", vertices, t0);
}

void CholmodFactor::Impl::record_analysis(std::int64_t n_cols, std::int64_t upper_nnz, double lnz, double flops,
                                          const std::string& ordering, std::int64_t vertices, Clock::time_point t0) {
  cholmod_common* c = common.get();
  // The analysis's work arrays in Common (about 7 n values) would otherwise stay allocated
  // through the factorization and the eigen-solve, the run's memory peaks; CHOLMOD allocates
  // them again where it needs them.
  cholmod_l_free_work(c);

  FactorStatistics& s = info.stats;
  s.analyses = ++analyses;
  s.analyze_seconds = seconds_since(t0);
  s.n = n_cols;
  s.nnz_A = upper_nnz;
  s.nnz_L = lnz;
  s.flops = flops;
  s.factor_entries = static_cast<std::int64_t>(L->xsize);
  s.supernodes = static_cast<std::int64_t>(L->nsuper);
  s.ordering = ordering;
  s.ordering_vertices = vertices;
  s.dense_kernels = dense->name;
  if (const char* kernels = detail::blas_kernel_name()) {
    s.blas_kernels = kernels;
    const char* suited = detail::openblas_core_for_this_cpu();
    if (detail::openblas_core_falls_short(kernels, suited)) s.blas_kernels_suited = suited;
  }
  // Estimates in bytes (8-byte doubles and SuiteSparse_long):
  //  factor   = values (xsize) + supernode row indices (ssize) + super/pi/px arrays +
  //             Perm, ColCount, IPerm and per-column bookkeeping (~4n);
  //  workspace of the supernodal backend on one thread (tree_cholesky_workspace_bytes; more
  //             threads add theirs in factorize), or of cholmod_l_factorize = the update matrix
  //             C (maxcsize) + the permuted copy of A's upper triangle (values + indices + column
  //             pointers) + Common's Iwork, Xwork and the supernodal Map/RelativeMap (~8n).
  const std::uint64_t n = static_cast<std::uint64_t>(s.n);
  s.factor_bytes = 8u * (L->xsize + L->ssize + 3u * (L->nsuper + 1u) + 4u * n);
  const std::uint64_t workspace =
      supernodal() ? detail::tree_cholesky_workspace_bytes(*L, 1)
          : 8u * L->maxcsize + 16u * static_cast<std::uint64_t>(upper_nnz) + 8u * (n + 1u) + 64u * n;
  s.peak_bytes = s.factor_bytes + workspace;
  info.status = FactorStatus::Analyzed;
}

void CholmodFactor::Impl::check_memory(std::uint64_t needed) {
  const auto avail = available_memory_bytes();
  std::uint64_t limit = std::numeric_limits<std::uint64_t>::max();
  std::string source;
  if (avail) {
    limit = *avail;
    source = "MemAvailable of /proc/meminfo (or the cgroup limit)";
  }
  if (opt.memory_limit_bytes > 0 && opt.memory_limit_bytes < limit) {
    limit = opt.memory_limit_bytes;
    source = "the memory limit given by the caller";
  }
  if (needed > limit) {
    const FactorStatistics& s = info.stats;
    std::ostringstream os;
    os << "Cholesky factor will not fit: needs about " << format_bytes(needed) << " (" << needed
       << " bytes: nnz(L) = " << static_cast<std::int64_t>(s.nnz_L)
       << ", stored entries = " << s.factor_entries << ", n = " << s.n << "), available "
       << format_bytes(limit) << " (" << limit << " bytes, " << source << ")";
    info.message = os.str();
    throw InsufficientMemoryError(os.str(), needed, limit);
  }
}

void CholmodFactor::Impl::throw_not_posdef(std::int64_t permuted, bool singular, double ratio) {
  const auto* perm = static_cast<const SuiteSparse_long*>(L->Perm);
  const std::int64_t col = perm ? perm[permuted] : permuted;
  std::ostringstream os;
  os << "matrix is not positive definite: ";
  if (singular)
    os << "numerically singular, pivot L_jj^2 / A_jj = " << ratio << " < "
       << opt.min_pivot_ratio << " at column " << col;
  else
    os << "non-positive pivot at column " << col;
  os << " (0-based; column " << permuted << " in the " << info.stats.ordering
     << " order). A stiffness matrix fails here when the model has a mechanism or an "
        "unconstrained rigid-body motion; K - sigma*M fails when sigma is above an eigenvalue.";
  info.status = FactorStatus::Failed;
  info.message = os.str();
  throw NotPositiveDefiniteError(os.str(), col, permuted, singular);
}

void CholmodFactor::Impl::factorize(const SparseMatrix& A, double shift) {
  std::int64_t upper_nnz = 0;
  if (!L || A.rows() != info.stats.n || detail::upper_pattern_hash(A, &upper_nnz) != pattern) {
    analyze(A);
  } else if (opt.check_symmetry) {
    validate_symmetric(A, "matrix to factorize");
  }
  // The supernodal backend runs independent subtrees on threads (tree_cholesky.hpp), each
  // with an update matrix and a row map of its own; CHOLMOD's factor is numeric in L already
  // after a first factorization, so only its workspace is new then.
  const unsigned threads = max_threads();
  const double share = supernodal() ? detail::tree_cholesky_share(*L, threads) : 0.0;
  const FactorStatistics& s = info.stats;
  const std::uint64_t per_thread =
      share > 0 ? detail::tree_cholesky_workspace_bytes(*L, threads) - detail::tree_cholesky_workspace_bytes(*L, 1) : 0u;
  const bool cholmod_numeric = !supernodal() && L->xtype != CHOLMOD_PATTERN;
  check_memory((cholmod_numeric ? s.peak_bytes - s.factor_bytes : s.peak_bytes) + per_thread);

  cholmod_common* c = common.get();
  const cholmod_sparse view = detail::view_upper(A);
  const auto t0 = Clock::now();
  clear_numeric();
  info.status = FactorStatus::Analyzed;
  info.stats.factor_parallel_fraction = share;
  info.stats.backend = opt.backend;
  const detail::NumericResult r = std::visit(
      [&](auto& b) { return b.factorize(view, A, *L, c, share > 0 ? threads : 1u); }, numeric);
  info.stats.factorize_seconds = seconds_since(t0);
  info.stats.cholmod_peak_bytes = c->memory_usage;
  info.shift = shift;
  if (!r.ok) fail(cholmod_error(supernodal() ? "numeric factorization (allocation of the factor)"
                                             : "numeric factorization (cholmod_l_factorize)"));
  if (r.minor < static_cast<std::int64_t>(L->n)) throw_not_posdef(r.minor, false, 0.0);
  info.stats.rcond = r.rcond;
  info.stats.min_pivot_ratio = r.pivots.ratio;
  info.stats.min_pivot_column = r.pivots.column;
  if (opt.min_pivot_ratio > 0 && !(r.pivots.ratio >= opt.min_pivot_ratio)) {
    clear_numeric();
    throw_not_posdef(r.pivots.permuted_column, true, r.pivots.ratio);
  }
  if (const auto* sn = std::get_if<detail::SupernodalNumeric>(&numeric)) {
    info.stats.packed_entries = sn->packed_entries();
    info.stats.solve_threads = static_cast<int>(sn->solve_threads());
    info.stats.solve_parallel_fraction = sn->solve_parallel_fraction();
  } else {
    info.stats.packed_entries = static_cast<std::int64_t>(L->xsize);
    info.stats.solve_threads = 1;
    info.stats.solve_parallel_fraction = 0;
  }
  info.status = FactorStatus::Factorized;
  info.message.clear();
}

CholmodFactor::CholmodFactor(FactorOptions options) : impl_(std::make_unique<Impl>(options)) {}
CholmodFactor::~CholmodFactor() = default;
CholmodFactor::CholmodFactor(CholmodFactor&&) noexcept = default;
CholmodFactor& CholmodFactor::operator=(CholmodFactor&&) noexcept = default;

const FactorStatistics& CholmodFactor::analyze(const SparseMatrix& A) {
  impl_->analyze(A);
  return impl_->info.stats;
}

const FactorStatistics& CholmodFactor::analyze(const SparseMatrix& A, const std::vector<std::int64_t>& perm,
                                               std::int64_t vertices, const std::string& name) {
  const auto n = static_cast<std::int64_t>(A.cols());
  std::vector<char> seen(static_cast<std::size_t>(std::max<std::int64_t>(n, 0)), 0);
  bool valid = static_cast<std::int64_t>(perm.size()) == n;
  for (std::size_t k = 0; valid && k < perm.size(); ++k) {
    const std::int64_t c = perm[k];
    valid = c >= 0 && c < n && !seen[static_cast<std::size_t>(c)];
    if (valid) seen[static_cast<std::size_t>(c)] = 1;
  }
  if (!valid)
    throw std::invalid_argument("matrix to factorize: the given order is not a permutation of its " + std::to_string(n) +
                                " columns");
  detail::NodalOrdering given{perm, vertices};
  impl_->analyze(A, &given);
  impl_->info.stats.ordering = name;
  return impl_->info.stats;
}

const FactorStatistics& CholmodFactor::analyze_groups(const detail::QuotientGraph& q, const std::vector<std::int64_t>& perm,
                                                      std::int64_t vertices, std::uint64_t pattern_hash,
                                                      std::int64_t upper_nnz) {
  impl_->analyze_groups(q, perm, vertices, pattern_hash, upper_nnz);
  return impl_->info.stats;
}

void CholmodFactor::factorize(const SparseMatrix& A) { impl_->factorize(A, 0.0); }

void CholmodFactor::factorize_shifted(const SparseRef& A, const SparseRef& B,
                                      double sigma) {
  if (impl_->opt.check_symmetry) {
    validate_symmetric(A, "A of A - sigma*B");
    validate_symmetric(B, "B of A - sigma*B");
  }
  // C is upper-only by construction; its symmetry follows from A's and B's.
  factorize_shifted_upper(shifted_upper(A, B, sigma), sigma);
}

void CholmodFactor::factorize_shifted_upper(const SparseMatrix& C, double sigma) {
  const SymmetricStorage s = detect_storage(C);
  if (s != SymmetricStorage::UpperOnly && s != SymmetricStorage::Diagonal)
    throw std::invalid_argument("factorize_shifted_upper: C must hold the upper triangle only");
  const bool check = impl_->opt.check_symmetry;
  impl_->opt.check_symmetry = false;  // upper-only: symmetric by construction
  try {
    impl_->factorize(C, sigma);
  } catch (...) {
    impl_->opt.check_symmetry = check;
    throw;
  }
  impl_->opt.check_symmetry = check;
}

Eigen::MatrixXd CholmodFactor::solve(const Eigen::Ref<const Eigen::MatrixXd>& B) const {
  Eigen::MatrixXd X(B.rows(), B.cols());
  solve(B, X);
  return X;
}

void CholmodFactor::solve(const Eigen::Ref<const Eigen::MatrixXd>& B, Eigen::Ref<Eigen::MatrixXd> X) const {
  Impl& m = *impl_;
  if (!factorized()) throw std::logic_error("CholmodFactor::solve: no valid factorization");
  if (B.rows() != m.info.stats.n || X.rows() != B.rows() || X.cols() != B.cols()) {
    std::ostringstream os;
    os << "CholmodFactor::solve: right-hand sides " << B.rows() << " x " << B.cols() << " and solutions " << X.rows()
       << " x " << X.cols() << " for a matrix of " << m.info.stats.n << " rows";
    throw std::invalid_argument(os.str());
  }
  std::visit([&](const auto& b) { b.solve(B.data(), B.outerStride(), B.cols(), X.data(), X.outerStride()); },
             m.numeric);
}

void CholmodFactor::solve(const double* b, double* x) const {
  Impl& m = *impl_;
  if (!factorized()) throw std::logic_error("CholmodFactor::solve: no valid factorization");
  const auto n = m.info.stats.n;
  std::visit([&](const auto& be) { be.solve(b, n, 1, x, n); }, m.numeric);
}

std::int64_t CholmodFactor::rows() const { return impl_->info.stats.n; }
bool CholmodFactor::factorized() const { return impl_->info.status == FactorStatus::Factorized; }
const FactorInfo& CholmodFactor::info() const { return impl_->info; }
const FactorOptions& CholmodFactor::options() const { return impl_->opt; }

}  // namespace ffr::preproc
