#pragma once
// The inner kernels of the supernodal substitutions (supernodal_solve.cpp, their only user,
// which compiles them once per instruction set): a panel of up to eight columns of a supernode
// applied to an interleaved block of W right-hand sides, in the forward (update) and the back
// (dot-product) direction.

#include "kernel_clones.hpp"

#include <cstdint>
#include <type_traits>

namespace ffr::preproc::detail::panels {

using Index = std::int64_t;

// Columns of L per sweep step for W interleaved right-hand sides. Eight for up to four: the
// update rows of T (and, going back, the gathered rows) are read and written once per panel, so
// wider panels halve that traffic against the same stream of L; on the 100k-DOF plate (92
// solves of 4 right-hand sides) the Lanczos stage was faster in seven of seven alternating
// runs, by 1-11 % (2.52-3.00 s against 2.59-3.09 s with four). Four for wider blocks, whose
// P x W values of Y no longer fit the 16 vector registers of AVX2 with eight (16 right-hand
// sides: 0.235-0.314 s a solve against 0.210-0.227 s with four, tools/bench/eigen, 100k grid).
template <int W>
constexpr int kPanel = W >= 8 ? 4 : 8;

// Four doubles (simd::v4, kernel_clones.hpp): GCC's vector extension, not auto-vectorisation: left to itself, GCC vectorised the interleaved loops across rows with
// permutations and stack spills, slower than CHOLMOD's solve.
// supernodal_solve.cpp is compiled at -O3 in every optimised build (preproc/CMakeLists.txt):
// at -O2 GCC kept the short loops over a panel's columns as loops over arrays in memory, and
// the sweep ran at two thirds of the speed.
using simd::v4;

// Software prefetch, kAhead entries (eight cache lines) ahead down each of the panel's columns,
// once a line. Why: one core's stream from memory is bounded by the misses it can have in flight
// (a plain read loop on one core of the Emerald Rapids VM of tools/bench/reduce reached 7.4 GB/s,
// two cores 14 GB/s), and the panel's P column streams left the hardware prefetcher short of
// that. Measured on the 100k-DOF plate, alternating with the code without it: the Lanczos stage
// (92 solves) at 1 thread 2.59-3.23 s against 2.83-3.44 s (medians 2.79 and 3.01), at 2 threads
// 1.77-1.99 s against 1.93-2.04 s; 32, 64 and 128 entries ahead were alike, 256 slower.
inline constexpr Index kAhead = 64;

// Prefetch of L[offset], also past the end of the factor's values near a supernode's last rows:
// prefetches do not fault, and the address is formed as an integer, not as an out-of-range
// pointer.
inline void prefetch_entry(const double* L, Index offset) {
  __builtin_prefetch(reinterpret_cast<const void*>(reinterpret_cast<std::uintptr_t>(L) +
                                                   static_cast<std::uintptr_t>(offset) * sizeof(double)));
}

// T[i] -= sum_q L(i, q) Y[q] for i < m, q < P: P columns of L from L (leading dimension ld)
// against P rows of the interleaved block Y, into m interleaved rows of T.
template <int W, int P>
inline void panel_update(const double* L, Index ld, Index m, const double* Y, double* T) {
  if constexpr (W == 1) {
    // One right-hand side: plain AXPYs down the columns, vectorised across rows.
    double y[P];
    for (int q = 0; q < P; ++q) y[q] = Y[q];
    for (Index i = 0; i < m; ++i) {
      double acc = T[i];
      for (int q = 0; q < P; ++q) acc -= L[i + q * ld] * y[q];
      T[i] = acc;
    }
  } else {
    constexpr int NV = W / 4;
    v4 y[P][NV];
    for (int q = 0; q < P; ++q)
      for (int k = 0; k < NV; ++k) y[q][k] = *reinterpret_cast<const v4*>(Y + q * W + 4 * k);
    for (Index i = 0; i < m; ++i) {
      if ((i & 7) == 0)
        for (int q = 0; q < P; ++q) prefetch_entry(L, i + kAhead + q * ld);
      v4 acc[NV];
      for (int k = 0; k < NV; ++k) acc[k] = *reinterpret_cast<const v4*>(T + i * W + 4 * k);
      for (int q = 0; q < P; ++q) {
        const double l = L[i + q * ld];
        for (int k = 0; k < NV; ++k) acc[k] -= l * y[q][k];
      }
      for (int k = 0; k < NV; ++k) *reinterpret_cast<v4*>(T + i * W + 4 * k) = acc[k];
    }
  }
}

// Y[q] -= sum_i L(i, q) G[i] for q < P: the transposed panel against m interleaved rows G.
template <int W, int P>
inline void panel_dot(const double* L, Index ld, Index m, const double* G, double* Y) {
  if constexpr (W == 1) {
    // One right-hand side: dot products, with four partial sums per column across rows.
    v4 acc[P] = {};
    Index i = 0;
    for (; i + 4 <= m; i += 4) {
      const v4 g = *reinterpret_cast<const v4*>(G + i);
      for (int q = 0; q < P; ++q) acc[q] += *reinterpret_cast<const v4*>(L + i + q * ld) * g;
    }
    for (int q = 0; q < P; ++q) {
      double sum = (acc[q][0] + acc[q][1]) + (acc[q][2] + acc[q][3]);
      for (Index r = i; r < m; ++r) sum += L[r + q * ld] * G[r];
      Y[q] -= sum;
    }
  } else {
    // Two rows per iteration into two sets of sums: with one set, each sum waits for its
    // previous FMA, and the sweep ran at 7-8 GB/s instead of 10-12 (grid pencil, 840 MB factor).
    constexpr int NV = W / 4;
    v4 acc[2][P][NV] = {};
    Index i = 0;
    for (; i + 2 <= m; i += 2) {
      if ((i & 7) == 0)
        for (int q = 0; q < P; ++q) prefetch_entry(L, i + kAhead + q * ld);
      for (int h = 0; h < 2; ++h) {
        v4 g[NV];
        for (int k = 0; k < NV; ++k) g[k] = *reinterpret_cast<const v4*>(G + (i + h) * W + 4 * k);
        for (int q = 0; q < P; ++q) {
          const double l = L[i + h + q * ld];
          for (int k = 0; k < NV; ++k) acc[h][q][k] += l * g[k];
        }
      }
    }
    for (; i < m; ++i) {
      v4 g[NV];
      for (int k = 0; k < NV; ++k) g[k] = *reinterpret_cast<const v4*>(G + i * W + 4 * k);
      for (int q = 0; q < P; ++q) {
        const double l = L[i + q * ld];
        for (int k = 0; k < NV; ++k) acc[0][q][k] += l * g[k];
      }
    }
    for (int q = 0; q < P; ++q)
      for (int k = 0; k < NV; ++k) *reinterpret_cast<v4*>(Y + q * W + 4 * k) -= acc[0][q][k] + acc[1][q][k];
  }
}

// The P-wide panel operations for a run-time panel width p (the last panel of a supernode).
template <int W, bool Dot>
inline void panel_p(int p, const double* L, Index ld, Index m, const double* in, double* out) {
  const auto run = [&](auto width) {
    constexpr int P = decltype(width)::value;
    if constexpr (Dot) panel_dot<W, P>(L, ld, m, in, out);
    else panel_update<W, P>(L, ld, m, in, out);
  };
  switch (p) {
    case 8: run(std::integral_constant<int, 8>{}); break;
    case 7: run(std::integral_constant<int, 7>{}); break;
    case 6: run(std::integral_constant<int, 6>{}); break;
    case 5: run(std::integral_constant<int, 5>{}); break;
    case 4: run(std::integral_constant<int, 4>{}); break;
    case 3: run(std::integral_constant<int, 3>{}); break;
    case 2: run(std::integral_constant<int, 2>{}); break;
    default: run(std::integral_constant<int, 1>{}); break;
  }
}
template <int W>
inline void update_p(int p, const double* L, Index ld, Index m, const double* Y, double* T) {
  panel_p<W, false>(p, L, ld, m, Y, T);
}
template <int W>
inline void dot_p(int p, const double* L, Index ld, Index m, const double* G, double* Y) {
  panel_p<W, true>(p, L, ld, m, G, Y);
}

}  // namespace ffr::preproc::detail::panels
