#pragma once
// Generated 3D test pencils for the eigen benchmark, with closed-form eigenvalues.
//
// A box of nx x ny x nz trilinear (Q1) elements, clamped on the face x = 0 and free
// elsewhere. Scalar case: the Q1 Laplacian, K = Kx(x)My(x)Mz + Mx(x)Ky(x)Mz + Mx(x)My(x)Kz,
// M = Mx(x)My(x)Mz (1D linear elements, consistent mass). "Elasticity-like" case (3 DOF per
// node): K3 = K (x) D with a fixed SPD 3x3 D and M3 = M (x) I3 -- the sparsity of a 3D
// hexahedral elasticity matrix (3x3 dense blocks, 81 entries per row), eigenvalues
// lambda_Laplacian * mu_D. 1D eigenvalues: see tests/solver/pencils.hpp (fixed-free and
// free-free rods, consistent mass).
//
// Assembled straight into compressed column storage (no triplets), so the generator's peak
// memory is the two matrices themselves.

#include "ffr/preproc/solver/sparse_types.hpp"

#include <vector>

namespace ffr::bench {

struct GridPencil {
  preproc::SparseMatrix K, M;
  int nx = 0, ny = 0, nz = 0, dofs_per_node = 1;
};

/// Elements per direction chosen so the DOF count is close to target_dofs (box 2 x 1 x 1).
GridPencil make_grid_pencil(std::int64_t target_dofs, int dofs_per_node);

/// The `count` smallest closed-form eigenvalues of make_grid_pencil's output, ascending.
std::vector<double> grid_eigenvalues(const GridPencil& g, int count);

}  // namespace ffr::bench
