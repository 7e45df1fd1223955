#pragma once
// The numeric supernodal factor packed for the substitutions: each supernode's diagonal block
// without most of its upper triangle.
//
// Why: CHOLMOD keeps supernode s as one dense nsrow x nscol column-major block, whose diagonal
// block L11 is a full square. Its strict upper triangle is never read after the factorization
// (the substitutions read L11's lower triangle only), yet it takes memory through the whole
// eigen-solve. On the 100k-DOF plate of tools/bench/reduce packing keeps 47.45 of the factor's
// 54.37 million values (55 MB less) at the Lanczos stage, which sets the run's memory peak at
// one thread.
//
// The packed layout keeps a supernode's columns in stripes of kStripe: stripe t holds columns
// kStripe t .. kStripe (t + 1) - 1, each from row kStripe t down, with one leading dimension
// nsrow - kStripe t. A panel of the substitutions (supernodal_panels.hpp: 8 or 4 columns, a
// divisor of kStripe, starting at a multiple of its width) thus still lies in one stripe with
// one leading dimension, and the kernels are unchanged; only the strict upper triangles of
// the kStripe x kStripe blocks on the diagonal stay.

#include <cholmod.h>

#include <cstdint>
#include <vector>

namespace ffr::preproc::detail {

inline constexpr std::int64_t kStripe = 8;

/// Where stripe t of a supernode of nsrow rows starts, from the supernode's first packed value:
/// the stripes before it hold kStripe columns of nsrow - kStripe u rows each (u < t).
inline std::int64_t stripe_offset(std::int64_t nsrow, std::int64_t t) {
  return kStripe * t * nsrow - kStripe * kStripe * t * (t - 1) / 2;
}

/// The packed start of every supernode's values (nsuper + 1 entries, the last one the packed
/// size) of a supernodal factor.
std::vector<SuiteSparse_long> packed_offsets(const cholmod_factor& L);

/// Moves the numeric values of L (CHOLMOD's layout) into the packed layout of `offsets`, in
/// place, and hands the freed tail back to the allocator (L->xsize becomes the packed size).
/// From then on only code that knows the packed layout may read L's values: not CHOLMOD
/// (its solve, rcond, or factorization on top of them; see unpack_storage).
void pack_values(cholmod_factor& L, const std::vector<SuiteSparse_long>& offsets, cholmod_common* c);

/// Gives a packed L the storage of CHOLMOD's layout again (full_size values, their contents
/// undefined), for a new factorization. False when the allocation fails (c->status says so).
bool unpack_storage(cholmod_factor& L, std::size_t full_size, cholmod_common* c);

}  // namespace ffr::preproc::detail
