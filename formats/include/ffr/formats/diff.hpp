#pragma once
// Comparing two SIDs member by member, after aligning B's modes to A's.
//
// A mode's sign and a rotation of modes inside a repeated eigenvalue are not differences
// (docs/contract.md). So B's modal basis is first changed, Phi_B' = Phi_B T, with T block-diagonal
// over the groups of (nearly) equal frequencies of A, each block the orthogonal matrix that
// best maps B's modes onto A's (orthogonal Procrustes: T_g = U V^T from the SVD of
// S_B,g^T S_A,g). S is a matrix of *linear* data of every mode, each block scaled to its
// natural size: the exported node slices phi and psi, the first-order integrals Pdm and rPdm,
// and the visual mode shapes when both files have the same surface. Orthogonal T is the right
// family because mass-orthonormal bases of one subspace differ by an orthogonal matrix; a
// rescaled mode is not excused and shows as a difference. A rotation that none of this data
// sees (modes that move no exported node, no visual vertex and no first-order integral)
// cannot be resolved: such a group (its features at the rounding level) is compared as written,
// T = I on it, so that a sign or rotation there is reported as a difference -- never one taken
// from the rounding noise of its features.
//
// Then every mode-dependent member of B is transformed consistently (transform_modes):
// first-order members (one mode index: mdCM.M1, J.M1, Ct.M0, Cr.M0, Gr, Oe.M0, Pdm, rPdm,
// rotary.PsiI, ksigma.M0, node phi/psi, visual modes) linearly, X'_k = sum_j T_jk X_j;
// second-order members (two mode indices: Me, Ke, De, PPdm, rotary.PsiIPsi, Cr.M1, Ge,
// Oe.M1, ksigma.M1, every /stiffening member) bilinearly, X'_ki = sum_jl T_jk T_li X_jl;
// Ke.M1 (three mode indices) trilinearly, X'_kij = sum_jlm T_jk T_li T_mj X_jlm.
// Frequencies and mode types are per-mode labels and are compared as they are.

#include "ffr/formats/sid.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace ffr::formats {

struct DiffOptions {
  double rtol = 1e-6;  ///< relative to each dataset's largest |entry| (max over A and B)
  double atol = 0.0;   ///< absolute, added to the relative tolerance
  /// Modes whose frequencies differ by less than this (relative) form one group.
  double group_rtol = 1e-6;
  bool align = true;
  int max_reported = 10;
};

struct ModeAlignment {
  Eigen::MatrixXd T;                       ///< [nq,nq]: Phi_B' = Phi_B T
  std::vector<std::vector<Index>> groups;  ///< groups of A's mode indices
  std::vector<Index> flipped;              ///< single modes whose sign was flipped
  std::vector<Index> rotated_groups;       ///< indices into groups of those that were rotated
};

/// Requires equal nq. Throws std::invalid_argument otherwise.
ModeAlignment align_modes(const Sid& a, const Sid& b, const DiffOptions& options = {});

/// The same body in the modal basis Phi' = Phi T (T is nq x nq, any invertible matrix).
Sid transform_modes(const Sid& s, const Eigen::MatrixXd& T);

struct Difference {
  std::string dataset;  ///< HDF5 path, e.g. "/sid/Gr/M0"
  std::string index;    ///< C-order index, e.g. "[1,0,2]"
  double a = 0, b = 0;
  double abs = 0;
  double rel = 0;       ///< abs / the dataset's scale
  double allowed = 0;   ///< atol + rtol * scale
};

struct DiffReport {
  bool equivalent = true;
  std::vector<std::string> structural;  ///< differences of shape, names, labels
  std::vector<Difference> worst;        ///< the worst entries (by abs / allowed), worst first
  int datasets_compared = 0;
  int datasets_different = 0;
  ModeAlignment alignment;
};

DiffReport diff(const Sid& a, const Sid& b, const DiffOptions& options = {});

}  // namespace ffr::formats
