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
// substitutions (supernodal_panels.hpp: a whole stripe) thus reads one 64-byte line a row, and only
// the strict upper triangles of the kStripe x kStripe blocks on the diagonal stay.
//
// Why rows, not CHOLMOD's columns: a forward sweep then reads all the packed values as one
// ascending stream and a back sweep as one descending stream, which a core prefetches well,
// instead of eight streams of one column each, restarted at every panel. On the 100k-DOF plate of
// tools/bench/reduce (one thread, 23 block solves of four right-hand sides, the sweeps timed in
// the solver) the forward sweeps took 0.49-0.51 s against 0.64-0.72 s by columns, the back sweeps
// 0.51-0.54 s against 0.74-0.82 s: 20 GB/s over the 430 MB of the factor, where a plain read loop
// reaches 22-25 GB/s on that machine. Packing by rows costs 0.05-0.06 s there, by columns 0.04-0.05.

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
