#pragma once
// Thread counts of the process's numerical libraries, set once by an executable's main() from its
// --threads option. The libraries of this project never set them: a thread count is the host
// program's decision (a library may run inside a program with its own BLAS and OpenMP plans).
//
// The functions are looked up in the running process rather than linked: OpenBLAS and the OpenMP
// runtime are dependencies of CHOLMOD, not of the executables, and another BLAS (or a CHOLMOD
// built without OpenMP) simply lacks the symbol; then nothing is set.

#include <dlfcn.h>

#include <string_view>

namespace ffr::cli {

/// Holds OpenBLAS to n threads (openblas_set_num_threads) and keeps OpenMP regions inactive
/// (omp_set_max_active_levels(0)). Why OpenMP off: Debian's CHOLMOD opens its OpenMP loops with
/// a compiled-in num_threads(4) whatever OMP_NUM_THREADS says, and those threads then compete
/// with the BLAS threads, where the parallel work of CHOLMOD's supernodal factorization is; the
/// reducer's own threads (ffr::preproc::set_max_threads) do not use OpenMP.
inline void set_numerical_library_threads(unsigned n) {
  if (n == 0) return;
  if (auto* blas = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads")))
    blas(static_cast<int>(n));
  if (auto* levels = reinterpret_cast<void (*)(int)>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels")))
    levels(0);
}

/// The BLAS thread count that goes with `threads` threads of the reducer's own and its sparse
/// Cholesky backend ("supernodal" or "cholmod", the part file's reduction.factorization).
///  - supernodal: 1. That factorization runs the elimination tree's independent subtrees, and
///    the column blocks of the supernodes above them, on the reducer's own threads, each
///    calling the BLAS; a threaded BLAS under them has more threads than cores. With OpenBLAS
///    (pthreads build) concurrent threaded calls also queue for its one thread pool while its
///    idle workers spin: on the 100k-DOF plate of tools/bench/reduce at two threads the
///    factorization took about twice as long with OpenBLAS at two threads as at one
///    (tools/bench/reduce/RESULTS.md).
///  - cholmod: `threads`. CHOLMOD takes the supernodes one after the other and finds its
///    parallelism only inside the BLAS calls of each.
inline unsigned blas_threads_for(std::string_view factorization, unsigned threads) {
  return factorization == "cholmod" ? threads : 1u;
}

}  // namespace ffr::cli
