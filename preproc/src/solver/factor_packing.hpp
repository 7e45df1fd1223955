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
// tools/bench/reduce the sweeps by rows took about a third less time than by columns, close to
// what a plain read loop over the factor takes on one core; packing by rows costs about a
// hundredth of a second more than by columns.

#include <cholmod.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
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

/// Moves the numeric values x of the factor analysed as L (CHOLMOD's supernodal layout, L's
/// structure only read) into the packed layout of `offsets`, in place in x (a stripe at a time
/// through a buffer of kStripe rows' height). The first offsets.back() values of x are then the
/// packed factor; the rest is free to give back (FactorValues::shrink).
void pack_values(const cholmod_factor& L, double* x, const std::vector<SuiteSparse_long>& offsets);

/// The numeric values of a factor, owned by the supernodal backend (never by CHOLMOD's
/// structures): allocated with malloc so that packing can hand the freed tail back in place
/// (realloc to a smaller size does not copy).
class FactorValues {
 public:
  FactorValues() = default;
  ~FactorValues() { std::free(p_); }
  FactorValues(const FactorValues&) = delete;
  FactorValues& operator=(const FactorValues&) = delete;
  /// n values, contents undefined; false (nothing held) when the allocation fails.
  bool allocate(std::size_t n) {
    std::free(p_);
    size_ = 0;
    p_ = static_cast<double*>(std::malloc(std::max<std::size_t>(n, 1) * sizeof(double)));
    if (p_) size_ = n;
    return p_ != nullptr;
  }
  void release() {
    std::free(p_);
    p_ = nullptr;
    size_ = 0;
  }
  /// Keeps the first n values and gives the rest back to the allocator.
  void shrink(std::size_t n) {
    if (n >= size_) return;
    if (void* q = std::realloc(p_, std::max<std::size_t>(n, 1) * sizeof(double))) p_ = static_cast<double*>(q);
    size_ = n;
  }
  double* data() { return p_; }
  const double* data() const { return p_; }
  std::size_t size() const { return size_; }

 private:
  double* p_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace ffr::preproc::detail
