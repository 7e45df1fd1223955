#pragma once
// Which dense kernels the supernodal factorization and the block Gram-Schmidt call (the part
// file's reduction.dense_kernels).

#include <optional>
#include <string>

namespace ffr::preproc {

enum class DenseKernelChoice {
  /// Eigen's, compiled for this CPU's vector units, where the BLAS's kernels fall short of the
  /// CPU (OpenBLAS running kernels from before AVX2 on a CPU with AVX2 and FMA, as Debian 12's
  /// OpenBLAS does on CPUs newer than its release); else the BLAS.
  Auto,
  /// The BLAS (dgemm, dsyrk, dtrsm, dpotrf), whatever its kernels.
  Blas,
  /// Eigen's, for the widest of x86-64-v4, -v3 or the baseline that this CPU runs.
  Eigen,
};
inline const char* to_string(DenseKernelChoice c) {
  switch (c) {
    case DenseKernelChoice::Auto: return "auto";
    case DenseKernelChoice::Blas: return "blas";
    case DenseKernelChoice::Eigen: return "eigen";
  }
  return "?";
}

/// "auto", "blas" or "eigen"; nullopt for anything else.
inline std::optional<DenseKernelChoice> dense_kernel_choice_from_string(const std::string& name) {
  if (name == "auto") return DenseKernelChoice::Auto;
  if (name == "blas") return DenseKernelChoice::Blas;
  if (name == "eigen") return DenseKernelChoice::Eigen;
  return std::nullopt;
}

}  // namespace ffr::preproc
