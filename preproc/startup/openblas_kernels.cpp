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
// Where they fall short it repeats OpenBLAS's choice with the variable set, through the two
// functions its DYNAMIC_ARCH builds export for that (gotoblas_dynamic_quit, gotoblas_dynamic_init:
// the same selection and kernel set-up as at load). Should they be missing or the choice not
// take, it starts the program again with the variable set (one exec: about 0.15 s measured).
//
// An object linked into executables and not part of the library: a library should not change
// its host's BLAS or restart it.

#include <dlfcn.h>
#include <strings.h>
#include <unistd.h>

#include <cstdlib>

#include "solver/blas_kernels.hpp"

namespace {

template <class F>
F* symbol(const char* name) {
  return reinterpret_cast<F*>(dlsym(RTLD_DEFAULT, name));
}

__attribute__((constructor)) void use_suited_openblas_kernels(int, char** argv, char**) {
  const char* set = std::getenv("OPENBLAS_CORETYPE");
  if (set && *set) return;  // the user's choice, or this hook's in a restarted process
  auto* corename = symbol<char*()>("openblas_get_corename");
  if (!corename) return;  // no OpenBLAS in this process
  const char* suited = ffr::preproc::detail::openblas_core_for_this_cpu();
  if (!ffr::preproc::detail::openblas_core_falls_short(corename(), suited)) return;
  if (setenv("OPENBLAS_CORETYPE", suited, 1) != 0) return;

  auto* quit = symbol<void()>("gotoblas_dynamic_quit");
  auto* init = symbol<void()>("gotoblas_dynamic_init");
  if (quit && init) {
    quit();
    init();
    if (strcasecmp(corename(), suited) == 0) return;
  }
  if (argv) execv("/proc/self/exe", argv);
  // Only when everything failed: carry on with what OpenBLAS has; the factorization's log line
  // names the kernels and the variable to set.
  unsetenv("OPENBLAS_CORETYPE");
}

}  // namespace
