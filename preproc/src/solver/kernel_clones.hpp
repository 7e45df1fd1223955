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

#if defined(__GNUC__)  // GCC and Clang
// Four doubles, loaded and stored at any 8-byte alignment: the compilers' vector extension, which
// the clones compile to AVX registers. (Eigen's fixed-size vectors would not do: Eigen picks its
// packet width from the flags of the whole file, SSE2 here, whatever the clone's target.)
typedef double v4 __attribute__((vector_size(32), aligned(8), may_alias));

inline v4 load(const double* p) { return *reinterpret_cast<const v4*>(p); }
inline void store(double* p, v4 v) { *reinterpret_cast<v4*>(p) = v; }

inline void prefetch(const void* p, int locality) {
  // The locality argument must be a constant for the builtin.
  if (locality >= 3) __builtin_prefetch(p, 0, 3);
  else __builtin_prefetch(p, 0, 1);
}
#else
// Any other compiler: the same operations on a plain struct of four doubles, so the kernels
// compile and stay correct (left to the compiler's own vectorisation).
struct v4 {
  double x[4];
  double& operator[](int i) { return x[i]; }
  double operator[](int i) const { return x[i]; }
  v4& operator+=(const v4& b) {
    for (int i = 0; i < 4; ++i) x[i] += b.x[i];
    return *this;
  }
  v4& operator-=(const v4& b) {
    for (int i = 0; i < 4; ++i) x[i] -= b.x[i];
    return *this;
  }
};
inline v4 operator+(v4 a, const v4& b) { return a += b; }
inline v4 operator-(v4 a, const v4& b) { return a -= b; }
inline v4 operator*(const v4& a, const v4& b) { return {{a.x[0] * b.x[0], a.x[1] * b.x[1], a.x[2] * b.x[2], a.x[3] * b.x[3]}}; }
inline v4 operator*(double s, const v4& b) { return {{s * b.x[0], s * b.x[1], s * b.x[2], s * b.x[3]}}; }
inline v4 operator*(const v4& b, double s) { return s * b; }

inline v4 load(const double* p) { return {{p[0], p[1], p[2], p[3]}}; }
inline void store(double* p, v4 v) {
  for (int i = 0; i < 4; ++i) p[i] = v.x[i];
}
inline void prefetch(const void*, int) {}
#endif

}  // namespace ffr::preproc::detail::simd
