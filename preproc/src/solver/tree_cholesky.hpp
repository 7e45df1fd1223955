#pragma once
// Numeric supernodal Cholesky on CHOLMOD's symbolic factor, with the independent subtrees of
// the elimination tree factorized on separate threads (tree_cholesky.cpp says why and how).

#include <cholmod.h>

#include <cstdint>

namespace ffr::preproc::detail {

struct DenseKernels;

/// How many values the numeric factor of the supernodal symbolic factor L has, in CHOLMOD's
/// layout (px[nsuper]): the size of the array tree_cholesky fills.
std::int64_t tree_cholesky_values(const cholmod_factor& L);

/// Bytes of work arrays tree_cholesky takes beside L on `threads` threads, an upper bound: per
/// thread the update buffer (capped, see tree_cholesky.cpp) and the row maps, once the
/// supernode lists and the column maps.
std::uint64_t tree_cholesky_workspace_bytes(const cholmod_factor& L, unsigned threads);

/// The share of the factorization's flops that tree_cholesky would run in the subtrees, on
/// `threads` threads; 0 when it would not pay (one thread, a small factor, a tree whose top
/// dominates).
double tree_cholesky_share(const cholmod_factor& L, unsigned threads);

/// Computes the numeric values of L = chol(P A P') into `values` (tree_cholesky_values(L) of
/// them) in CHOLMOD's supernodal layout, as cholmod_l_factorize would put them into L->x: A
/// upper-stored (stype > 0), L a supernodal analysis of A by CHOLMOD, only read (its structure:
/// super, pi, px, s, Perm). Returns the first permuted column whose pivot is not positive, or
/// L.n when A is positive definite (the columns from there on are then not valid).
/// The subtrees of the elimination tree run on up to `threads` threads; the dense work of each
/// supernode goes to `kernels`, on the thread that factorizes it.
std::int64_t tree_cholesky(const cholmod_sparse& A, const cholmod_factor& L, double* values, unsigned threads,
                           const DenseKernels& kernels);

}  // namespace ffr::preproc::detail
