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
// The packed layout keeps a supernode's columns in stripes of kStripe: stripe t holds the w
// columns kStripe t .. kStripe t + w - 1 (w = kStripe but for a last, narrower stripe), each from
// row kStripe t down, row by row: the w values of a row are adjacent, rows w apart. A panel of the
// substitutions (supernodal_panels.hpp: 8 or 4 columns, a divisor of kStripe, starting at a
// multiple of its width) thus lies in one stripe, and only the strict upper triangles of the
// kStripe x kStripe blocks on the diagonal stay.
//
// Why rows, not CHOLMOD's columns: a sweep then reads a stripe as one stream, a 64-byte line
// per row, instead of eight streams of one column each, which restart at every panel. Most of a
// factor's panels are short (on the 100k-DOF plate 41 % of the values lie in supernodes of at most
// 128 columns), and a core keeps few streams in flight: in a kernel benchmark of 400 MB of
// panels (four right-hand sides), panels of 100 rows were swept at 19-23 GB/s by rows against
// 7-8 GB/s by columns, of 600 rows at 16-20 against 12-16 GB/s.

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
/// place (a stripe at a time through a buffer of kStripe rows' height), and hands the freed tail back to the allocator (L->xsize becomes the packed size).
/// From then on only code that knows the packed layout may read L's values: not CHOLMOD
/// (its solve, rcond, or factorization on top of them; see unpack_storage).
void pack_values(cholmod_factor& L, const std::vector<SuiteSparse_long>& offsets, cholmod_common* c);

/// Gives a packed L the storage of CHOLMOD's layout again (full_size values, their contents
/// undefined), for a new factorization. False when the allocation fails (c->status says so).
bool unpack_storage(cholmod_factor& L, std::size_t full_size, cholmod_common* c);

}  // namespace ffr::preproc::detail
