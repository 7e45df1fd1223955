// Start-up hook of ffr's executables that factorize (ffr-reduce, the tests, the benchmarks):
// when OpenBLAS has picked kernels older than this CPU's vector units (see
// preproc/src/solver/blas_kernels.hpp for when, and what it costs), it has OpenBLAS choose
// again with OPENBLAS_CORETYPE set to the suited ones. A user's OPENBLAS_CORETYPE stands.
//
// Why not just set the variable: OpenBLAS reads it once, in its own initialiser, and nothing in
// the process runs before that and keeps an environment change (an executable's .preinit_array
// runs first, but glibc's initialiser then resets the environment to the one the kernel passed;
// measured: a setenv made there is gone by main). So this runs as a constructor, after the
// libraries' initialisers, before any BLAS call, and asks OpenBLAS which kernels it chose.
// Where they fall short it repeats OpenBLAS's choice with the variable set, through two
// functions its DYNAMIC_ARCH builds export (gotoblas_dynamic_quit, gotoblas_dynamic_init), which
// make the same selection and kernel set-up as at load. A build without them (not DYNAMIC_ARCH)
// has no other kernels to choose and is left alone; if the new choice does not take, the
// variable is taken back. Either way the factorization's log line names the kernels in use.
//
// An object linked into executables and not part of the library: a library should not change
// its host's BLAS.

#include <strings.h>

#include <cstdlib>

#include "solver/blas_kernels.hpp"
#include "solver/library_threads.hpp"

namespace {

using ffr::preproc::detail::blas_kernel_name;
using ffr::preproc::detail::find_symbol;

__attribute__((constructor)) void use_suited_openblas_kernels() {
  const char* set = std::getenv("OPENBLAS_CORETYPE");
  if (set && *set) return;  // the user's choice stands
  const char* in_use = blas_kernel_name();
  if (!in_use) return;  // no OpenBLAS in this process
  const char* suited = ffr::preproc::detail::openblas_core_for_this_cpu();
  if (!ffr::preproc::detail::openblas_core_falls_short(in_use, suited)) return;
  auto* quit = find_symbol<void()>("gotoblas_dynamic_quit");
  auto* init = find_symbol<void()>("gotoblas_dynamic_init");
  if (!quit || !init || setenv("OPENBLAS_CORETYPE", suited, 1) != 0) return;
  quit();
  init();
  // Kept set when it took, so that child processes (and OpenBLAS, should it read it again) agree.
  if (strcasecmp(blas_kernel_name(), suited) != 0) unsetenv("OPENBLAS_CORETYPE");
}

}  // namespace
