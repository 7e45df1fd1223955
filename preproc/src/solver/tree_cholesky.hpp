#pragma once
// Numeric supernodal Cholesky on CHOLMOD's symbolic factor, with the independent subtrees of
// the elimination tree factorized on separate threads (tree_cholesky.cpp says why and how).

#include <cholmod.h>

#include <cstdint>

namespace ffr::preproc::detail {

/// Whether tree_cholesky can factorize L: supernodal, and the BLAS and LAPACK routines found.
bool tree_cholesky_available(const cholmod_factor& L);

/// Bytes of work arrays tree_cholesky takes beside L on `threads` threads, an upper bound: per
/// thread the update buffer (capped, see tree_cholesky.cpp) and the row maps, once the
/// supernode lists and the column maps.
std::uint64_t tree_cholesky_workspace_bytes(const cholmod_factor& L, unsigned threads);

/// The share of the factorization's flops that tree_cholesky would run in the subtrees, on
/// `threads` threads; 0 when it would not pay (one thread, a small factor, a tree whose top
/// dominates) or cannot run (the BLAS and LAPACK routines not found in the process).
double tree_cholesky_share(const cholmod_factor& L, unsigned threads);

/// Computes the numeric values of L = chol(P A P') into L's own supernodal layout, as
/// cholmod_l_factorize would: A upper-stored (stype > 0), L analysed by CHOLMOD for it
/// (supernodal, symbolic or numeric). Sets L->minor to the first permuted column whose pivot is
/// not positive (L->n when A is positive definite; the columns from there on are then not
/// valid). Returns false, with nothing computed, when it cannot run (not
/// tree_cholesky_available; A not upper-stored) or when CHOLMOD's
/// allocation of L's values fails (c->status tells why). BLAS runs
/// single-threaded inside the subtrees and on `threads` threads for the top, and is left at
/// `threads` threads.
bool tree_cholesky(const cholmod_sparse& A, cholmod_factor& L, unsigned threads, cholmod_common* c);

}  // namespace ffr::preproc::detail
