#pragma once
// Thread counts of the libraries under the eigen-solver, which do not follow ours, and the
// lookup of those libraries' functions in the running process.

#include <dlfcn.h>

namespace ffr::preproc::detail {

/// A function of the libraries CHOLMOD brings along (its OpenMP runtime, BLAS, LAPACK), looked
/// up in the running process rather than linked: they are CHOLMOD's dependencies, not ours, and
/// another BLAS or a CHOLMOD built without OpenMP simply lacks the symbol (null then).
template <class F>
F* find_symbol(const char* name) {
  return reinterpret_cast<F*>(dlsym(RTLD_DEFAULT, name));
}

/// Runs CHOLMOD's own OpenMP loops on the calling thread. Debian's CHOLMOD asks for a
/// compiled-in CHOLMOD_OMP_NUM_THREADS (4) in the supernodal factorization, whatever
/// OMP_NUM_THREADS or --threads say; on a 2-core machine those threads fight the BLAS threads
/// (measured on the 100k-DOF plate of tools/bench/reduce: factorization 3.2 s with them,
/// 1.7 s without, at 1 thread; at 2 threads 1.8-2.2 s against 1.4 s). The BLAS is where the
/// parallel work is. Per thread (OpenMP's max-active-levels is a per-task setting): call it
/// on the thread that factorizes. No effect when no OpenMP runtime is loaded.
void keep_openmp_on_this_thread();

/// The name of OpenBLAS's kernels in use (openblas_get_corename: "SkylakeX", "Haswell", ...),
/// or null when the BLAS is not OpenBLAS. Inline: the executables' start-up hook
/// (preproc/startup) calls it in programs without the library.
inline const char* blas_kernel_name() {
  static auto* const corename = find_symbol<char*()>("openblas_get_corename");
  return corename ? corename() : nullptr;
}

/// Sets OpenBLAS's thread count (openblas_set_num_threads), when OpenBLAS is the BLAS.
void set_blas_threads(unsigned n);

}  // namespace ffr::preproc::detail
