#pragma once
// What the runtime's small dense kernels share (SmallLU, the weighted Gram, the matrix-vector
// products): FFR_RT_CLONES compiles a kernel for AVX2 (x86-64-v3) as well as the baseline, the
// version chosen at load time. Why: the runtime builds for plain x86-64 (no -march), where
// Eigen and GCC use SSE2, and a step calls these kernels hundreds of times on vectors of tens of
// entries. The files that use them are also compiled at -O3 (runtime/CMakeLists.txt): GCC
// vectorises loops of run-time length at -O3 only.
// No AVX-512 clone: on vectors of 10 to 90 entries its 8-wide loops leave longer remainders,
// and the benchmark's step ran about 2 % slower with it (tools/bench/runtime_step/RESULTS.md).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define FFR_RT_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define FFR_RT_CLONES
#endif

// GCC notes at every use of a 32-byte vector in the baseline clone that its ABI differs from the
// AVX clones' (-Wpsabi); the vectors never cross a function boundary, so the note is off for the
// rest of the including file (the kernel files only).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace ffr::runtime::detail::simd {

// Four doubles at any 8-byte alignment (GCC's vector extension), for the reductions GCC does
// not vectorise by itself without reassociating (-ffast-math).
typedef double v4 __attribute__((vector_size(32), aligned(8), may_alias));
typedef long long m4 __attribute__((vector_size(32)));  ///< a comparison's lanes: all ones or zero
inline v4 load(const double* p) { return *reinterpret_cast<const v4*>(p); }
/// Lanes l >= from (0 <= from <= 4): the rows of a last block of four, started at m - 4 so
/// that it stays inside the column, that the whole blocks before it have not done.
inline m4 lanes_from(long long from) { return m4{0, 1, 2, 3} >= from; }

}  // namespace ffr::runtime::detail::simd
