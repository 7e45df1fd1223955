#pragma once
// The name of the BLAS kernels in the running process, for the factorization's statistics.

#include <dlfcn.h>

namespace ffr::preproc::detail {

/// The name of OpenBLAS's kernels in use (openblas_get_corename: "SkylakeX", "Haswell", ...),
/// or null when the BLAS is not OpenBLAS. Looked up in the process rather than linked: OpenBLAS
/// is CHOLMOD's BLAS, not a dependency of this library, and another BLAS lacks the symbol. Read
/// only: the library never changes the BLAS's kernels or threads (the executables' main() sets
/// the thread counts, ffr/cli/process_threads.hpp).
inline const char* blas_kernel_name() {
  static auto* const corename = reinterpret_cast<char* (*)()>(dlsym(RTLD_DEFAULT, "openblas_get_corename"));
  return corename ? corename() : nullptr;
}

}  // namespace ffr::preproc::detail
