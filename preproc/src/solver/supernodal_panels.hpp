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

// Columns of L per sweep step: eight, a whole stripe of the packed factor (factor_packing.hpp),
// whose rows are 64-byte lines. The update rows of T (and, going back, the gathered rows) are
// read and written once per panel, so wider panels halve that traffic against the same stream of
// L: the Lanczos stage of the 100k-DOF plate was a few per cent faster with eight than with four.
// Panels of four would read every line of a stripe twice, so blocks of eight and sixteen
// right-hand sides take panels of eight too (no slower on tools/bench/eigen's 100k grid).
inline constexpr int kPanel = 8;

// Four doubles (simd::v4, kernel_clones.hpp): the compilers' vector extension, not
// auto-vectorisation: left to itself, GCC vectorised the interleaved loops across rows with
// permutations and stack spills, slower than CHOLMOD's solve.
// supernodal_solve.cpp is compiled at -O3 in every optimised build (preproc/CMakeLists.txt):
// at -O2 GCC kept the short loops over a panel's columns as loops over arrays in memory, and
// the sweep ran at two thirds of the speed.
using simd::v4;

// Software prefetch in the direction of the sweep (factor_packing.hpp: a forward sweep reads
// the packed values as one ascending stream, a back sweep as one descending stream), 1 KB ahead
// into L1 and 8 KB ahead into L2, at every row. Why both: one core keeps few misses in flight,
// and its compute does not hide the wait for memory by itself. Over 400 MB of panels of eight
// columns by rows (four right-hand sides), the two prefetches together swept at the speed of a
// plain read loop for panels of 100 to 2000 rows, where a single prefetch, 1 KB or 4 KB ahead,
// lost up to a third of it. The addresses may lie past either end of the factor's values:
// prefetches do not fault, and the address is formed as an integer, not as an out-of-range
// pointer.
inline constexpr Index kNear = 128, kFar = 1024;  // entries

template <bool Down>
inline void prefetch_from(const double* row) {
  const auto at = [&](Index entries) {
    return reinterpret_cast<const void*>(reinterpret_cast<std::uintptr_t>(row) +
                                         static_cast<std::uintptr_t>(Down ? -entries : entries) * sizeof(double));
  };
  simd::prefetch(at(kNear), 3);
  simd::prefetch(at(kFar), 1);
}

// T[i] -= sum_q L(i, q) Y[q] for i < m, q < P: a panel of P columns, L(i, q) = L[i rs + q],
// against P rows of the interleaved block Y, into m interleaved rows of T.
template <int W, int P>
inline void panel_update(const double* L, Index rs, Index m, const double* Y, double* T) {
  if constexpr (W == 1) {
    double y[P];
    for (int q = 0; q < P; ++q) y[q] = Y[q];
    for (Index i = 0; i < m; ++i) {
      prefetch_from<false>(L + i * rs);
      double acc = 0;
      for (int q = 0; q < P; ++q) acc += L[i * rs + q] * y[q];
      T[i] -= acc;
    }
  } else {
    constexpr int NV = W / 4;
    v4 y[P][NV];
    for (int q = 0; q < P; ++q)
      for (int k = 0; k < NV; ++k) y[q][k] = *reinterpret_cast<const v4*>(Y + q * W + 4 * k);
    for (Index i = 0; i < m; ++i) {
      prefetch_from<false>(L + i * rs);
      v4 acc[NV];
      for (int k = 0; k < NV; ++k) acc[k] = *reinterpret_cast<const v4*>(T + i * W + 4 * k);
      for (int q = 0; q < P; ++q) {
        const double l = L[i * rs + q];
        for (int k = 0; k < NV; ++k) acc[k] -= l * y[q][k];
      }
      for (int k = 0; k < NV; ++k) *reinterpret_cast<v4*>(T + i * W + 4 * k) = acc[k];
    }
  }
}

// Y[q] -= sum_i L(i, q) G[i] for q < P: the transposed panel against m interleaved rows G,
// its rows from the last (the back sweep's descending stream). Two rows per iteration into two
// sets of sums: with one set, each sum waits for its previous FMA, and the sweep ran at 7-8 GB/s
// instead of 10-12 (grid pencil, 840 MB factor).
template <int W>
struct DotSum {
  using type = v4;  // four right-hand sides a register
};
template <>
struct DotSum<1> {
  using type = double;
};

template <int W, int P>
inline void panel_dot(const double* L, Index rs, Index m, const double* G, double* Y) {
  constexpr int NV = W < 4 ? 1 : W / 4;
  using Sum = typename DotSum<W>::type;
  Sum acc[2][P][NV] = {};
  const auto rhs = [&](Index i, int k) -> Sum {
    if constexpr (W == 1) return G[i];
    else return *reinterpret_cast<const v4*>(G + i * W + 4 * k);
  };
  Index i = m - 1;
  for (; i >= 1; i -= 2) {
    prefetch_from<true>(L + i * rs);
    prefetch_from<true>(L + (i - 1) * rs);
    for (int h = 0; h < 2; ++h) {
      Sum g[NV];
      for (int k = 0; k < NV; ++k) g[k] = rhs(i - h, k);
      for (int q = 0; q < P; ++q) {
        const double l = L[(i - h) * rs + q];
        for (int k = 0; k < NV; ++k) acc[h][q][k] += l * g[k];
      }
    }
  }
  if (i == 0)
    for (int q = 0; q < P; ++q) {
      const double l = L[q];
      for (int k = 0; k < NV; ++k) acc[0][q][k] += l * rhs(0, k);
    }
  for (int q = 0; q < P; ++q)
    for (int k = 0; k < NV; ++k) {
      if constexpr (W == 1) Y[q] -= acc[0][q][k] + acc[1][q][k];
      else *reinterpret_cast<v4*>(Y + q * W + 4 * k) -= acc[0][q][k] + acc[1][q][k];
    }
}

// The P-wide panel operations for a run-time panel width p (the last panel of a supernode).
template <int W, bool Dot>
inline void panel_p(int p, const double* L, Index rs, Index m, const double* in, double* out) {
  const auto run = [&](auto width) {
    constexpr int P = decltype(width)::value;
    if constexpr (Dot) panel_dot<W, P>(L, rs, m, in, out);
    else panel_update<W, P>(L, rs, m, in, out);
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
inline void update_p(int p, const double* L, Index rs, Index m, const double* Y, double* T) {
  panel_p<W, false>(p, L, rs, m, Y, T);
}
template <int W>
inline void dot_p(int p, const double* L, Index rs, Index m, const double* G, double* Y) {
  panel_p<W, true>(p, L, rs, m, G, Y);
}

}  // namespace ffr::preproc::detail::panels
