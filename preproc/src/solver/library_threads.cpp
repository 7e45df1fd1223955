#include "library_threads.hpp"

namespace ffr::preproc::detail {

void keep_openmp_on_this_thread() {
  // max-active-levels 0: no parallel region becomes active, so each runs on one thread.
  static auto* const set_levels = find_symbol<void(int)>("omp_set_max_active_levels");
  if (set_levels) set_levels(0);
}

void set_blas_threads(unsigned n) {
  static auto* const set_threads = find_symbol<void(int)>("openblas_set_num_threads");
  if (set_threads && n > 0) set_threads(static_cast<int>(n));
}

}  // namespace ffr::preproc::detail
