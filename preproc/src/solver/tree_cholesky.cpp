// Numeric supernodal Cholesky with the elimination tree's independent subtrees on threads.
//
// Why: CHOLMOD's supernodal factorization takes the supernodes one after the other and finds
// its parallelism only in the BLAS calls of each. Low in a nested-dissection tree the
// supernodes are small and those calls stay on one core: on the 100k-DOF plate of
// tools/bench/reduce the factorization took 1.7 s on one thread and 1.3 s on two. Disjoint
// subtrees of the supernodal elimination tree write disjoint columns of L and read only their
// own, so they can be factorized at the same time, each with a single-threaded BLAS; the
// supernodes above them (the "top", cut as for the substitutions, solve_schedule.hpp, but
// balancing flops) follow in order with the threaded BLAS. On one thread (or for a small factor)
// every supernode is the top's; the code still pays there, since it places A's entries straight
// into L where CHOLMOD first makes a permuted copy of A (60-77 MB on that plate).
//
// The method is CHOLMOD's left-looking supernodal one (t_cholmod_super_numeric.c). First the
// entries of P A P' are put in their places in L (zero elsewhere), all supernodes at once, by
// all threads. Then for each supernode s, holding columns k1..k2-1 of L on the rows R_s (its
// columns first) in L_s:
//   for each descendant d that has rows in k1..k2-1 (kept in a list of s):
//     C = L_d(R2, :) L_d(R1, :)^T, R1 = d's rows in k1..k2-1, R2 = d's rows from R1 on
//     L_s -= C, scattered through the position of each row in R_s
//     d moves to the list of the supernode that holds its next row
//   L_s(1:nscol, :) <- chol(itself);  L_s(below, :) <- L_s(below, :) L11^-T
//   s joins the list of the supernode of its first row below the diagonal block.
// Each thread links into lists of its own, so that two threads can add to the lists of a top
// supernode without a lock; the top reads them all.
//
// The top's large supernodes are split over the same threads (top_node): the descendants'
// updates by the columns of s they land in (disjoint writes), then L_s by a blocked right-looking
// Cholesky whose triangular solves split the rows and whose trailing updates split the columns.
// Every dense-kernel call (dense_kernels.hpp: the BLAS's, or Eigen's where the BLAS's kernels
// fall short of the CPU) is made by one of these threads and is meant to run on it alone: the
// host program holds the BLAS to one thread under this factorization (ffr-reduce does, see
// ffr/cli/process_threads.hpp). Why not leave the top to a threaded BLAS: OpenBLAS's threaded
// calls from the subtrees' threads queue for its one pool, its idle workers spin beside them, and
// the two-thread factorization took about twice the time of the same with OpenBLAS on one thread
// (tools/bench/reduce/RESULTS.md).
#include "tree_cholesky.hpp"

#include "dense_kernels.hpp"
#include "solve_schedule.hpp"
#include "../run_parts.hpp"

#include <algorithm>
#include <memory>
#include <vector>

namespace ffr::preproc::detail {
namespace {

using Index = std::int64_t;
using Long = SuiteSparse_long;

// Below this many stored entries a factor is factorized on one thread: threads cost more than
// they give.
constexpr Index kMinEntries = Index{1} << 20;

// A descendant's update is computed in blocks of its columns (at least kMinUpdateColumns wide,
// for the BLAS) when it has more than kMaxUpdate values. Why: the buffer of the largest update,
// met at the top of the tree, is the factorization's last allocation on top of the factor: on
// the 100k-DOF plate of tools/bench/reduce 1.95 million values (15.6 MB) at the end, where the
// run's peak at one thread lies.
constexpr Index kMaxUpdate = Index{1} << 18;
constexpr Index kMinUpdateColumns = 64;

// A top supernode goes to the threads (top_node) from this much work, nscol * nsrow^2 (its own
// Cholesky and about the updates it receives): below it, starting the threads (tens of
// microseconds a fork) costs more than the split gives.
constexpr double kMinSplitWork = 1 << 24;
// Columns of the blocked Cholesky of a split supernode: wide enough for the BLAS's kernels,
// narrow enough that the serial dpotrf of each diagonal block stays small.
constexpr Index kDenseBlock = 128;

// Split points of `count` items over `parts`, item i weighing about (total - i): the columns of a
// trapezoid, the first the longest. cut[0] = 0, cut[parts] = count.
std::vector<Index> trapezoid_cuts(Index count, Index total, unsigned parts) {
  std::vector<Index> cut(parts + 1, count);
  cut[0] = 0;
  double all = 0;
  for (Index i = 0; i < count; ++i) all += static_cast<double>(total - i);
  double sum = 0;
  unsigned p = 1;
  for (Index i = 0; i < count && p < parts; ++i) {
    sum += static_cast<double>(total - i);
    while (p < parts && sum >= all * p / parts) cut[p++] = i + 1;
  }
  return cut;
}

// Per-thread work arrays.
struct Workspace {
  std::vector<Index> map;       // row -> its position in the supernode being computed
  std::vector<Index> relative;  // a descendant's rows -> their positions there
  std::vector<Index> run;       // how many of a descendant's rows from this one on have consecutive positions
  std::unique_ptr<double[]> C;  // a descendant's update
  Index capacity = 0;
  double* update(Index size) {
    if (size > capacity) {
      C.reset(new double[static_cast<std::size_t>(size)]);
      capacity = size;
    }
    return C.get();
  }
};

// d[t] -= s[t] for t < len (d and s never overlap: a column of L and the update buffer).
inline void subtract_run(double* __restrict d, const double* __restrict s, Index len) {
  for (Index t = 0; t < len; ++t) d[t] -= s[t];
}

class TreeCholesky {
 public:
  TreeCholesky(const cholmod_factor& L, double* values, unsigned lists, const DenseKernels& kernels)
      : k_(kernels),
        super_(static_cast<const Long*>(L.super)),
        pi_(static_cast<const Long*>(L.pi)),
        px_(static_cast<const Long*>(L.px)),
        rows_(static_cast<const Long*>(L.s)),
        x_(values),
        xsize_(tree_cholesky_values(L)),
        n_(static_cast<Index>(L.n)),
        nsuper_(static_cast<Index>(L.nsuper)),
        owner_(static_cast<std::size_t>(n_)),
        next_(static_cast<std::size_t>(nsuper_), -1),
        lpos_(static_cast<std::size_t>(nsuper_), 0),
        head_(lists, std::vector<Index>(static_cast<std::size_t>(nsuper_), -1)) {
    for (Index s = 0; s < nsuper_; ++s) {
      for (Index k = super_[s]; k < super_[s + 1]; ++k) owner_[static_cast<std::size_t>(k)] = s;
      widest_ = std::max<Index>(widest_, pi_[s + 1] - pi_[s]);
    }
  }

  Workspace workspace() const {
    Workspace w;
    w.map.assign(static_cast<std::size_t>(n_), -1);
    w.relative.resize(static_cast<std::size_t>(widest_));
    w.run.resize(static_cast<std::size_t>(widest_));
    return w;
  }

  /// Writes the entries of P A P' (A upper-stored, the columns c0..c1-1 of it) into L's layout,
  /// L's other entries left as they are. Each entry has its own place, so parts of the columns
  /// can go to separate threads. Why not CHOLMOD's way, a permuted copy of A scattered
  /// supernode by supernode: the copy is made by one thread before any other can start, and
  /// it takes the memory of A once more during the factorization.
  void scatter(const cholmod_sparse& A, const std::vector<Index>& position, Index c0, Index c1) {
    const auto* Ap = static_cast<const Long*>(A.p);
    const auto* Ai = static_cast<const Long*>(A.i);
    const auto* Anz = A.packed ? nullptr : static_cast<const Long*>(A.nz);
    const auto* Ax = static_cast<const double*>(A.x);
    for (Index c = c0; c < c1; ++c) {
      const Index p1 = Anz ? Ap[c] + Anz[c] : Ap[c + 1];
      const Index pc = position[static_cast<std::size_t>(c)];
      for (Index p = Ap[c]; p < p1; ++p) {
        if (Ai[p] > c) continue;  // the upper triangle only
        const Index pr = position[static_cast<std::size_t>(Ai[p])];
        const Index i = std::max(pr, pc), j = std::min(pr, pc);  // row i >= column j of the lower triangle
        const Index s = owner_[static_cast<std::size_t>(j)];
        const Long* r0 = rows_ + pi_[s];
        const Long* r = std::lower_bound(r0, rows_ + pi_[s + 1], i);
        x_[px_[s] + (j - super_[s]) * (pi_[s + 1] - pi_[s]) + (r - r0)] = Ax[p];
      }
    }
  }

  void zero(Index begin, Index end) { std::fill(x_ + begin, x_ + end, 0.0); }
  Index stored() const { return xsize_; }

  /// Whether top_node should split supernode s over threads.
  bool worth_splitting(Index s) const {
    const double nscol = static_cast<double>(super_[s + 1] - super_[s]), nsrow = static_cast<double>(pi_[s + 1] - pi_[s]);
    return nscol >= 2 * kDenseBlock && nscol * nsrow * nsrow >= kMinSplitWork;
  }

  /// A supernode of the top, reading all lists and linking into list 0, with its work split
  /// over ws.size() threads (one workspace each). Same result as node(s, 0, true, ws[0]) up to
  /// rounding. Returns the first failing column, or n.
  Index top_node(Index s, std::vector<Workspace>& ws) {
    const auto parts = static_cast<unsigned>(ws.size());
    const Index k1 = super_[s], k2 = super_[s + 1], nscol = k2 - k1;
    const Index psi = pi_[s], nsrow = pi_[s + 1] - psi;
    double* Ls = x_ + px_[s];
    std::vector<Index> ds;
    for (auto& head : head_) {
      for (Index d = head[static_cast<std::size_t>(s)]; d >= 0; d = next_[static_cast<std::size_t>(d)]) ds.push_back(d);
      head[static_cast<std::size_t>(s)] = -1;
    }
    // The updates: each thread takes the columns cut[t] .. cut[t+1]-1 of s from every
    // descendant (a column of s is written by one thread only).
    const std::vector<Index> cut = trapezoid_cuts(nscol, nsrow, parts);
    run_parts(parts, [](unsigned p) { return p; }, [&](unsigned t, unsigned, unsigned) {
      Workspace& w = ws[t];
      for (Index k = 0; k < nsrow; ++k) w.map[static_cast<std::size_t>(rows_[psi + k])] = k;
      for (const Index d : ds) update_from(d, k2, Ls, nsrow, w, cut[t], cut[t + 1]);
    });
    for (const Index d : ds) advance(d, k2, 0);
    // L_s <- its Cholesky factor, blocked: per block of columns, the diagonal block by dpotrf
    // (serial), the rows below it by dtrsm split over the threads by rows, then the trailing
    // columns of s updated by syrk/gemm split over the threads by columns.
    const int ld = static_cast<int>(nsrow);
    for (Index k0 = 0; k0 < nscol; k0 += kDenseBlock) {
      const Index b = std::min(kDenseBlock, nscol - k0), r0 = k0 + b;
      double* Lk = Ls + k0 + k0 * nsrow;  // the diagonal block
      const int nb = static_cast<int>(b);
      const int info = k_.cholesky_lower(nb, Lk, ld);
      if (info != 0) return k1 + k0 + (info > 0 ? info - 1 : 0);
      if (r0 == nsrow) break;
      const Index below = nsrow - r0;
      run_parts(parts, [&](unsigned p) { return below * static_cast<Index>(p) / static_cast<Index>(parts); },
                [&](unsigned, Index i0, Index i1) {
                  const int m = static_cast<int>(i1 - i0);
                  if (m > 0) k_.solve_lower_transposed_on_right(m, nb, Lk, ld, Lk + b + i0, ld);
                });
      if (r0 == nscol) continue;
      // Trailing columns r0 .. nscol-1 of s: column j loses L(j:, k0:r0) L(j, k0:r0)^T.
      const std::vector<Index> tcut = trapezoid_cuts(nscol - r0, nsrow - r0, parts);
      run_parts(parts, [](unsigned p) { return p; }, [&](unsigned t, unsigned, unsigned) {
        const Index c0 = r0 + tcut[t], c1 = r0 + tcut[t + 1];
        if (c1 <= c0) return;
        const int nc = static_cast<int>(c1 - c0), nbelow = static_cast<int>(nsrow - c1);
        const double* Lc = Ls + c0 + k0 * nsrow;  // L(c0:, k0:r0)
        double* Ac = Ls + c0 + c0 * nsrow;        // s's block (c0:, c0:c1)
        k_.syrk_lower(nc, nb, -1.0, Lc, ld, 1.0, Ac, ld);
        if (nbelow > 0) k_.gemm('N', 'T', nbelow, nc, nb, -1.0, Lc + nc, ld, Lc, ld, 1.0, Ac + nc, ld);
      });
    }
    if (nsrow > nscol) {
      lpos_[static_cast<std::size_t>(s)] = nscol;
      link(s, rows_[psi + nscol], 0);
    }
    return n_;
  }

  /// Supernode s (its entries of P A P' already in place, the rest zero), with the lists it
  /// links into and reads: the thread's own `list` (subtrees), or all of them (the top, list 0
  /// for new links). Returns the first failing column, or n.
  Index node(Index s, unsigned list, bool all_lists, Workspace& w) {
    const Index k1 = super_[s], k2 = super_[s + 1], nscol = k2 - k1;
    const Index psi = pi_[s], nsrow = pi_[s + 1] - psi;
    double* Ls = x_ + px_[s];
    for (Index k = 0; k < nsrow; ++k) w.map[static_cast<std::size_t>(rows_[psi + k])] = k;
    const unsigned first = all_lists ? 0u : list, last = all_lists ? static_cast<unsigned>(head_.size()) : list + 1;
    for (unsigned l = first; l < last; ++l) {
      Index d = head_[l][static_cast<std::size_t>(s)];
      head_[l][static_cast<std::size_t>(s)] = -1;
      while (d >= 0) {
        const Index after = next_[static_cast<std::size_t>(d)];
        update_from(d, k2, Ls, nsrow, w, 0, k2 - k1);
        advance(d, k2, list);
        d = after;
      }
    }
    const int nc = static_cast<int>(nscol), nr = static_cast<int>(nsrow);
    const int info = k_.cholesky_lower(nc, Ls, nr);
    if (info != 0) return k1 + (info > 0 ? info - 1 : 0);
    if (nsrow > nscol) {
      k_.solve_lower_transposed_on_right(nr - nc, nc, Ls, nr, Ls + nscol, nr);
      lpos_[static_cast<std::size_t>(s)] = nscol;
      link(s, rows_[psi + nscol], list);
    }
    return n_;
  }

 private:
  void link(Index d, Index row, unsigned list) {
    auto& head = head_[list][static_cast<std::size_t>(owner_[static_cast<std::size_t>(row)])];
    next_[static_cast<std::size_t>(d)] = head;
    head = d;
  }

  // Descendant d, having updated the supernode whose columns end at k2, moves to the list of the
  // supernode that holds its next row, if any.
  void advance(Index d, Index k2, unsigned list) {
    const Index pdi = pi_[d], ndrow = pi_[d + 1] - pdi;
    Index pos = lpos_[static_cast<std::size_t>(d)];
    while (pos < ndrow && rows_[pdi + pos] < k2) ++pos;
    lpos_[static_cast<std::size_t>(d)] = pos;
    if (pos < ndrow) link(d, rows_[pdi + pos], list);
  }

  // Subtracts descendant d's update from the supernode s (its columns end at k2) held in Ls:
  // only from the columns c0 .. c1-1 of s (all of them: 0, nscol), so that threads can share
  // the columns of one supernode. Leaves d where it is in the lists (advance() moves it on).
  void update_from(Index d, Index k2, double* Ls, Index nsrow, Workspace& w, Index c0, Index c1) {
    const Index ndcol = super_[d + 1] - super_[d];
    const Index pdi = pi_[d], ndrow = pi_[d + 1] - pdi;
    const Index pos = lpos_[static_cast<std::size_t>(d)];
    const Long* r = rows_ + pdi + pos;
    const Index ndrow2 = ndrow - pos;
    Index ndrow1 = 0;
    while (ndrow1 < ndrow2 && r[ndrow1] < k2) ++ndrow1;
    const double* Ld = x_ + px_[d] + pos;
    const int kc = static_cast<int>(ndcol), ld = static_cast<int>(ndrow);
    Index* rel = w.relative.data();
    Index* run = w.run.data();
    for (Index i = 0; i < ndrow2; ++i) rel[i] = w.map[static_cast<std::size_t>(r[i])];
    // Runs of rows that land on consecutive rows of s (a node's three DOFs at least, often
    // whole stretches of a separator): each column of C is subtracted run by run, with
    // contiguous loads and stores the compiler vectorizes, where one indexed access per entry
    // was 55 % of this file's time on the 100k-DOF plate (tools/bench/reduce, perf).
    if (ndrow2 > 0) run[ndrow2 - 1] = 1;
    for (Index i = ndrow2 - 2; i >= 0; --i) run[i] = rel[i + 1] == rel[i] + 1 ? run[i + 1] + 1 : 1;
    // The rows ja .. jb-1 of R1 land in the columns c0 .. c1-1 of s (rel is ascending).
    Index ja = 0;
    while (ja < ndrow1 && rel[ja] < c0) ++ja;
    Index jb = ja;
    while (jb < ndrow1 && rel[jb] < c1) ++jb;
    // C = L_d(R2, :) L_d(R1, :)^T, its lower part in the columns ja .. jb-1, by blocks of `width`
    // of its columns: block [j0, j0 + b) takes the rows from j0 on, the b x b top by syrk, the
    // rest by gemm. One block unless it would exceed kMaxUpdate values.
    const Index cols = jb - ja;
    if (cols == 0) return;
    const Index width = (ndrow2 - ja) * cols > kMaxUpdate ? std::max(kMinUpdateColumns, kMaxUpdate / (ndrow2 - ja)) : cols;
    double* C = w.update((ndrow2 - ja) * std::min(width, cols));
    for (Index j0 = ja; j0 < jb; j0 += width) {
      const Index b = std::min(width, jb - j0), m = ndrow2 - j0;
      const int nb = static_cast<int>(b), nm = static_cast<int>(m), nbelow = static_cast<int>(m - b);
      k_.syrk_lower(nb, kc, 1.0, Ld + j0, ld, 0.0, C, nm);
      if (nbelow > 0) k_.gemm('N', 'T', nbelow, nb, kc, 1.0, Ld + j0 + b, ld, Ld + j0, ld, 0.0, C + b, nm);
      // Rows of d in s's columns sit at positions 0..nscol-1 of R_s, so rel[j] is a column.
      for (Index jj = 0; jj < b; ++jj) {
        const Index j = j0 + jj;
        double* dst = Ls + rel[j] * nsrow;
        const double* src = C + jj * m;  // src[i - j0] is row i of C's column j
        for (Index i = j; i < ndrow2;) {
          subtract_run(dst + rel[i], src + (i - j0), run[i]);
          i += run[i];
        }
      }
    }
  }

  const DenseKernels& k_;
  const Long *super_, *pi_, *px_, *rows_;
  double* x_;
  Index xsize_, n_, nsuper_;
  Index widest_ = 0;  // most rows of a supernode
  std::vector<Index> owner_;  // column -> supernode
  std::vector<Index> next_, lpos_;
  std::vector<std::vector<Index>> head_;  // per list: supernode -> first descendant
};

}  // namespace

std::int64_t tree_cholesky_values(const cholmod_factor& L) {
  const auto* px = static_cast<const Long*>(L.px);
  return L.is_super && L.nsuper > 0 && px ? static_cast<std::int64_t>(px[L.nsuper]) : 0;
}

std::uint64_t tree_cholesky_workspace_bytes(const cholmod_factor& L, unsigned threads) {
  const auto* pi = static_cast<const Long*>(L.pi);
  const Index n = static_cast<Index>(L.n), nsuper = static_cast<Index>(L.nsuper);
  Index widest = 0;
  for (Index s = 0; s < nsuper; ++s) widest = std::max<Index>(widest, pi[s + 1] - pi[s]);
  // update_from's buffer: C whole when it has at most kMaxUpdate values, else column blocks of
  // max(kMinUpdateColumns, kMaxUpdate / rows) on at most `widest` rows; never more than C whole.
  const Index update = std::min<Index>(static_cast<Index>(L.maxcsize), std::max(kMaxUpdate, kMinUpdateColumns * widest));
  const Index per_thread = update + n + 2 * widest;             // C, map, relative, run
  const Index shared = 2 * n + (2 + static_cast<Index>(threads)) * nsuper;  // owner, position; next, lpos, lists
  return 8u * static_cast<std::uint64_t>(static_cast<Index>(threads) * per_thread + shared);
}

double tree_cholesky_share(const cholmod_factor& L, unsigned threads) {
  if (threads < 2 || !L.is_super) return 0.0;
  return make_solve_schedule(L, threads, kMinEntries, TreeWork::Flops).parallel_fraction;
}

Index tree_cholesky(const cholmod_sparse& A, const cholmod_factor& L, double* values, unsigned threads,
                    const DenseKernels& kernels) {
  SolveSchedule plan = make_solve_schedule(L, threads, 0, TreeWork::Flops);
  // No cut (a caller on one thread): every supernode is the top's.
  if (plan.parts.empty()) plan.top = {{0, static_cast<Index>(L.nsuper) - 1}};
  const unsigned parts = static_cast<unsigned>(std::max<std::size_t>(1, plan.parts.size()));
  TreeCholesky chol(L, values, parts, kernels);
  {
    // L <- P A P' in its layout, zero elsewhere (the first touch of the factor's memory too).
    const Index n = static_cast<Index>(L.n), stored = chol.stored();
    const auto* perm = static_cast<const Long*>(L.Perm);
    std::vector<Index> position(static_cast<std::size_t>(n));
    for (Index k = 0; k < n; ++k) position[static_cast<std::size_t>(perm ? perm[k] : k)] = k;
    run_parts(parts, [&](unsigned p) { return stored * static_cast<Index>(p) / static_cast<Index>(parts); },
              [&](unsigned, Index b, Index e) { chol.zero(b, e); });
    run_parts(parts, [&](unsigned p) { return n * static_cast<Index>(p) / static_cast<Index>(parts); },
              [&](unsigned, Index b, Index e) { chol.scatter(A, position, b, e); });
  }
  Index minor = static_cast<Index>(L.n);
  if (!plan.parts.empty()) {
    // The subtrees: one list of them per thread. A thread stops
    // at its first failing supernode; the lowest failing column over the threads is the one
    // CHOLMOD, which goes in order, would report.
    std::vector<Index> failed(parts, minor);
    // Each thread calls the dense kernels for its own supernodes (a one-thread BLAS, see the
    // top of this file; no thread count is changed here: it is the host program's).
    run_parts(parts, [](unsigned p) { return p; }, [&](unsigned t, unsigned, unsigned) {
      Workspace w = chol.workspace();
      for (const SupernodeRange& range : plan.parts[t])
        for (Index s = range.first; s <= range.last && failed[t] == minor; ++s) failed[t] = chol.node(s, t, false, w);
    });
    minor = *std::min_element(failed.begin(), failed.end());
  }
  if (minor == static_cast<Index>(L.n)) {
    // The top in order; its large supernodes split over the threads (one workspace each).
    std::vector<Workspace> ws;
    ws.push_back(chol.workspace());
    for (const SupernodeRange& range : plan.top)
      for (Index s = range.first; s <= range.last && minor == static_cast<Index>(L.n); ++s) {
        if (parts > 1 && chol.worth_splitting(s)) {
          while (ws.size() < parts) ws.push_back(chol.workspace());
          minor = chol.top_node(s, ws);
        } else {
          minor = chol.node(s, 0, true, ws[0]);
        }
      }
  }
  return minor;
}

}  // namespace ffr::preproc::detail
