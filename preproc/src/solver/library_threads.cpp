#include "library_threads.hpp"

#include <dlfcn.h>

namespace ffr::preproc::detail {
namespace {

// Looked up in the running process rather than linked: the OpenMP runtime and OpenBLAS are
// CHOLMOD's dependencies, not ours, and another BLAS or a CHOLMOD built without OpenMP simply
// lacks the symbol.
template <class F>
F* find_symbol(const char* name) {
  return reinterpret_cast<F*>(dlsym(RTLD_DEFAULT, name));
}

}  // namespace

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
