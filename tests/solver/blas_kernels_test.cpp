// OpenBLAS's kernels: the rule that says which ones this CPU suits (the reduction's log advises
// OPENBLAS_CORETYPE when the ones in use fall short; the library itself never changes them).
// Reference for the rule: OpenBLAS's kernel sets (Prescott/Core2/.../Sandybridge are pre-AVX2;
// Cooperlake shares SkylakeX's double-precision kernels).
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

TEST(BlasKernels, FactorStatisticsNameTheKernels) {
  SparseMatrix A(2, 2);
  A.insert(0, 0) = 2;
  A.insert(1, 1) = 3;
  A.insert(0, 1) = 1;
  CholmodFactor f;
  const FactorStatistics s = f.analyze(A);
  const char* in_use = detail::blas_kernel_name();
  EXPECT_EQ(s.blas_kernels, in_use ? std::string(in_use) : std::string());
  const char* suited = detail::openblas_core_for_this_cpu();
  EXPECT_EQ(s.blas_kernels_suited, detail::openblas_core_falls_short(in_use, suited) ? std::string(suited) : std::string());
}
