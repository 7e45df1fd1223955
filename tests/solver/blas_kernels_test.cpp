// OpenBLAS's kernels: the rule that says which ones this CPU suits, and the start-up hook
// (preproc/startup) that makes this test program, like ffr-reduce, run them. Without the hook,
// Debian 12's OpenBLAS 0.3.21 runs its Prescott kernels on an Emerald Rapids Xeon (family 6,
// model 207), and ThisProcessRunsKernelsTheCpuSuits fails there.
#include "solver/blas_kernels.hpp"
#include "solver/library_threads.hpp"

#include "ffr/preproc/solver/cholmod_factor.hpp"

#include <gtest/gtest.h>

#include <string>

using namespace ffr::preproc;

TEST(BlasKernels, OlderKernelsFallShortOfSuitedOnes) {
  EXPECT_TRUE(detail::openblas_core_falls_short("Prescott", "SkylakeX"));
  EXPECT_TRUE(detail::openblas_core_falls_short("SANDYBRIDGE", "Haswell"));  // AVX without FMA
  EXPECT_FALSE(detail::openblas_core_falls_short("SkylakeX", "SkylakeX"));
  EXPECT_FALSE(detail::openblas_core_falls_short("Cooperlake", "SkylakeX"));  // same double kernels
  EXPECT_FALSE(detail::openblas_core_falls_short("Zen", nullptr));            // nothing suited: keep
  EXPECT_FALSE(detail::openblas_core_falls_short(nullptr, "SkylakeX"));       // not OpenBLAS
}

TEST(BlasKernels, ThisProcessRunsKernelsTheCpuSuits) {
  const char* in_use = detail::blas_kernel_name();
  if (!in_use) GTEST_SKIP() << "the BLAS is not OpenBLAS";
  const char* suited = detail::openblas_core_for_this_cpu();
  EXPECT_FALSE(detail::openblas_core_falls_short(in_use, suited))
      << "OpenBLAS runs " << in_use << " kernels on a CPU that suits " << suited;
}

TEST(BlasKernels, FactorStatisticsNameTheKernels) {
  SparseMatrix A(2, 2);
  A.insert(0, 0) = 2;
  A.insert(1, 1) = 3;
  A.insert(0, 1) = 1;
  CholmodFactor f;
  const FactorStatistics s = f.analyze(A);
  const char* in_use = detail::blas_kernel_name();
  EXPECT_EQ(s.blas_kernels, in_use ? std::string(in_use) : std::string());
  EXPECT_TRUE(s.blas_kernels_suited.empty()) << s.blas_kernels_suited;
}
