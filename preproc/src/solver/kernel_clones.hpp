#pragma once
// What the memory-bound kernels of the solver share (supernodal substitutions, tall-skinny
// products, sparse products).
//
// FFR_KERNEL_CLONES: compile a memory-bound kernel for AVX-512 and AVX2/FMA as well as the
// baseline, the version chosen at load time. Why: the project builds for plain x86-64 (no
// -march), whose SSE2 code needs several instructions per multiply-add where these kernels
// must keep up with memory.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define FFR_KERNEL_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"), flatten))
#else
#define FFR_KERNEL_CLONES
#endif

// The baseline clone passes v4 by value without AVX registers, and GCC notes at every use that
// this ABI differs from the AVX clones' (-Wpsabi). The helpers are inline and never cross a
// clone boundary, so the note is off for the rest of the including file (the kernel files only).
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace ffr::preproc::detail::simd {

// Four doubles, loaded and stored at any 8-byte alignment: GCC's vector extension, which the
// clones compile to AVX registers. (Eigen's fixed-size vectors would not do: Eigen picks its
// packet width from the flags of the whole file, SSE2 here, whatever the clone's target.)
typedef double v4 __attribute__((vector_size(32), aligned(8), may_alias));

inline v4 load(const double* p) { return *reinterpret_cast<const v4*>(p); }
inline void store(double* p, v4 v) { *reinterpret_cast<v4*>(p) = v; }

}  // namespace ffr::preproc::detail::simd
