#pragma once
// Which OpenBLAS kernels suit this CPU, and whether the ones in use fall short of them.
//
// Why: OpenBLAS (built with DYNAMIC_ARCH, as Debian ships it) picks its kernels from the CPU's
// family and model number, and a model newer than the release falls back to the oldest x86-64
// kernels. Debian 12's OpenBLAS 0.3.21 runs Prescott (SSE3) kernels on an Emerald Rapids Xeon
// (family 6, model 207), which has AVX-512, and the factorization of the 100k-DOF plate of
// tools/bench/reduce takes about 2.5 times as long with them as with the SkylakeX kernels
// (RESULTS.md there). The features, not the model number, say which kernels the CPU can run.
// The library only reports this (the factorization's statistics, and the reducer's log advises
// OPENBLAS_CORETYPE); it never changes the kernels.

#include <strings.h>

namespace ffr::preproc::detail {

/// The OPENBLAS_CORETYPE for this CPU's vector units, or null when OpenBLAS's own choice is
/// to be kept. Only Intel CPUs: there OpenBLAS's double-precision kernels for every AVX-512
/// model are the SkylakeX ones (Cooperlake and later add only bfloat16 routines), and for
/// every AVX2 model the Haswell ones. AMD's are chosen by family, which OpenBLAS knows.
inline const char* openblas_core_for_this_cpu() {
#if defined(__x86_64__) && defined(__GNUC__)
  __builtin_cpu_init();
  if (!__builtin_cpu_is("intel")) return nullptr;
  // __builtin_cpu_supports also checks that the OS saves the wider registers (XCR0).
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
      __builtin_cpu_supports("avx512vl"))
    return "SkylakeX";
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return "Haswell";
#endif
  return nullptr;
}

/// True when `in_use` (openblas_get_corename()) names one of OpenBLAS's x86-64 kernels from
/// before AVX2 (Intel's up to Sandy Bridge, AMD's up to Steamroller).
inline bool openblas_core_predates_avx2(const char* in_use) {
  if (!in_use) return false;
  static const char* const pre_avx2[] = {"Katmai", "Coppermine", "Northwood", "Prescott",  "Banias",    "Atom",
                                         "Core2",  "Penryn",     "Dunnington", "Nehalem",  "Sandybridge", "Opteron",
                                         "Barcelona", "Bobcat",  "Bulldozer", "Piledriver", "Steamroller"};
  for (const char* old : pre_avx2)
    if (strcasecmp(in_use, old) == 0) return true;
  return false;
}

/// True when `in_use` (openblas_get_corename()) is one of OpenBLAS's kernels older than AVX2,
/// while this CPU would run `suited` (from openblas_core_for_this_cpu, which names kernels for
/// Intel CPUs only).
inline bool openblas_core_falls_short(const char* in_use, const char* suited) {
  return suited && openblas_core_predates_avx2(in_use);
}

}  // namespace ffr::preproc::detail
