// Which dense kernels run (dense_kernels.hpp): the Eigen variant for this CPU, and the rule of
// "auto".
#include "dense_kernels.hpp"

#include "blas_kernels.hpp"
#include "library_threads.hpp"

extern "C" const ffr::preproc::detail::DenseKernels* ffr_dense_kernels_eigen_baseline();
#if defined(FFR_DENSE_EIGEN_X86_LEVELS)
// Compiled for x86-64-v3 and -v4 and linked as objects of their own (preproc/CMakeLists.txt).
extern "C" const ffr::preproc::detail::DenseKernels* ffr_dense_kernels_eigen_x86_64_v3();
extern "C" const ffr::preproc::detail::DenseKernels* ffr_dense_kernels_eigen_x86_64_v4();
#endif

namespace ffr::preproc::detail {

std::vector<const DenseKernels*> eigen_dense_kernel_variants() {
  std::vector<const DenseKernels*> variants{ffr_dense_kernels_eigen_baseline()};
#if defined(FFR_DENSE_EIGEN_X86_LEVELS)
  // __builtin_cpu_supports also checks that the OS saves the wider registers (XCR0).
  __builtin_cpu_init();
  if (__builtin_cpu_supports("x86-64-v3")) variants.push_back(ffr_dense_kernels_eigen_x86_64_v3());
  if (__builtin_cpu_supports("x86-64-v4")) variants.push_back(ffr_dense_kernels_eigen_x86_64_v4());
#endif
  return variants;
}

const DenseKernels& eigen_dense_kernels() {
  // Chosen once: the Gram-Schmidt products ask for their kernels at every call.
  static const DenseKernels* const widest = eigen_dense_kernel_variants().back();
  return *widest;
}

bool blas_kernels_fall_short() {
#if defined(__x86_64__) && defined(__GNUC__)
  const char* in_use = blas_kernel_name();
  if (!in_use) return false;
  __builtin_cpu_init();
  if (!(__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))) return false;
  return openblas_core_predates_avx2(in_use);
#endif
  return false;
}

const DenseKernels& select_dense_kernels(DenseKernelChoice choice) {
  switch (choice) {
    case DenseKernelChoice::Blas: return blas_dense_kernels();
    case DenseKernelChoice::Eigen: return eigen_dense_kernels();
    case DenseKernelChoice::Auto: break;
  }
  static const DenseKernels* const chosen = blas_kernels_fall_short() ? &eigen_dense_kernels() : &blas_dense_kernels();
  return *chosen;
}

}  // namespace ffr::preproc::detail
