// Packing of the numeric supernodal factor (factor_packing.hpp says why and the layout).
#include "factor_packing.hpp"

#include <algorithm>
#include <cstring>

namespace ffr::preproc::detail {
namespace {

using Index = std::int64_t;

// Packed values of a supernode of nscol columns and nsrow rows.
Index packed_size(Index nscol, Index nsrow) {
  const Index stripes = (nscol + kStripe - 1) / kStripe, last = stripes - 1;
  return stripe_offset(nsrow, last) + (nscol - kStripe * last) * (nsrow - kStripe * last);
}

}  // namespace

std::vector<SuiteSparse_long> packed_offsets(const cholmod_factor& L) {
  const auto* super = static_cast<const SuiteSparse_long*>(L.super);
  const auto* pi = static_cast<const SuiteSparse_long*>(L.pi);
  const Index nsuper = static_cast<Index>(L.nsuper);
  std::vector<SuiteSparse_long> offsets(static_cast<std::size_t>(nsuper + 1), 0);
  for (Index s = 0; s < nsuper; ++s)
    offsets[static_cast<std::size_t>(s + 1)] =
        offsets[static_cast<std::size_t>(s)] + packed_size(super[s + 1] - super[s], pi[s + 1] - pi[s]);
  return offsets;
}

void pack_values(cholmod_factor& L, const std::vector<SuiteSparse_long>& offsets, cholmod_common* c) {
  const auto* super = static_cast<const SuiteSparse_long*>(L.super);
  const auto* pi = static_cast<const SuiteSparse_long*>(L.pi);
  const auto* px = static_cast<const SuiteSparse_long*>(L.px);
  auto* x = static_cast<double*>(L.x);
  // Columns in order: a column's packed place is never after its place in CHOLMOD's layout
  // (the packed offsets are prefix sums of smaller blocks), and its packed end never after
  // where the next column starts there, so nothing is overwritten before it is moved.
  for (Index s = 0; s < static_cast<Index>(L.nsuper); ++s) {
    const Index nscol = super[s + 1] - super[s], nsrow = pi[s + 1] - pi[s];
    const double* from = x + px[s];
    double* to = x + offsets[static_cast<std::size_t>(s)];
    for (Index j = 0; j < nscol; ++j) {
      const Index t = j / kStripe, r0 = kStripe * t, ld = nsrow - r0;
      std::memmove(to + stripe_offset(nsrow, t) + (j - r0) * ld, from + j * nsrow + r0,
                   static_cast<std::size_t>(ld) * sizeof(double));
    }
  }
  // Shrinking in place cannot fail for want of memory; if the allocator declines, the values
  // stay where they are, packed, in the larger block.
  size_t size = L.xsize;
  const auto packed = static_cast<size_t>(offsets.back());
  void* shrunk = cholmod_l_realloc(std::max<size_t>(packed, 1), sizeof(double), L.x, &size, c);
  if (shrunk) {
    L.x = shrunk;
    L.xsize = size;
  }
}

bool unpack_storage(cholmod_factor& L, std::size_t full_size, cholmod_common* c) {
  if (L.xsize >= full_size) return true;
  size_t size = L.xsize;
  void* grown = cholmod_l_realloc(full_size, sizeof(double), L.x, &size, c);
  if (!grown || size != full_size) return false;
  L.x = grown;
  L.xsize = size;
  return true;
}

}  // namespace ffr::preproc::detail
