#pragma once
// Test pencils with eigenvalues known in closed form.
//
// 1D: the rod (or string) of n equal linear elements of length h, stiffness
// K_e = (EA/h) [1 -1; -1 1] and consistent mass M_e = (rho A h/6) [2 1; 1 2]. Away from the
// ends both assembled matrices are tridiagonal Toeplitz, k tridiag(-1, 2, -1) and
// m tridiag(1, 4, 1), which share the eigenvectors sin(j theta) / cos(j theta) (eigenpairs
// of tridiagonal Toeplitz matrices: C. D. Meyer, "Matrix Analysis and Applied Linear
// Algebra", SIAM 2000, Example 7.2.5). The pencil eigenvalue is therefore
//     lambda(theta) = (6 E / (rho h^2)) (1 - cos theta) / (2 + cos theta),
// the discrete dispersion relation of the consistent-mass two-node bar (C. A. Felippa,
// "Introduction to Finite Element Methods", Ch. 32 "Customized mass matrices of 1D
// elements", Sec. 32.4.2, Fourier analysis of the bar mass template), with
//     fixed-fixed:  theta_k = k pi / n,        k = 1 .. n-1   (x_j = sin(j theta))
//     free-free:    theta_k = k pi / n,        k = 0 .. n     (x_j = cos(j theta); k = 0 is
//                                                              the rigid translation)
//     fixed-free:   theta_k = (2k-1) pi / (2n), k = 1 .. n     (mirror condition at the
//                                                              free end: cos(n theta) = 0)
// The end rows satisfy the same relation (checked by substitution: a free end is the
// symmetry plane x_{n+1} = x_{n-1} of the interior stencil).
//
// 2D/3D: bilinear/trilinear (Q1) elements of the Laplacian on a box are tensor products:
// K = Kx (x) My (x) Mz + Mx (x) Ky (x) Mz + Mx (x) My (x) Kz, M = Mx (x) My (x) Mz, whose
// eigenvalues are the sums lambda_x + lambda_y + lambda_z of the 1D ones (Kronecker sum of
// commuting pencils: R. A. Horn, C. R. Johnson, "Topics in Matrix Analysis", CUP 1991,
// Thm. 4.4.5). With unequal edge lengths the spectrum is simple; a cube gives multiplicities.

#include "ffr/preproc/solver/sparse_types.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace ffr::test {

using ffr::preproc::SparseMatrix;

enum class Ends { FixedFixed, FreeFree, FixedFree };

struct Pencil {
  SparseMatrix K, M;
};

/// Rod of n elements over length L (EA = 1, rho A = 1 unless given), with the given ends.
inline Pencil rod(int n, double L, Ends ends, double EA = 1.0, double rhoA = 1.0) {
  const double h = L / n, k = EA / h, m = rhoA * h / 6.0;
  const int first = (ends == Ends::FreeFree) ? 0 : 1;  // drop node 0 if it is fixed
  const int last = (ends == Ends::FixedFixed) ? n - 1 : n;
  const int ndof = last - first + 1;
  std::vector<Eigen::Triplet<double, std::int64_t>> tk, tm;
  for (int e = 0; e < n; ++e) {
    const int a = e - first, b = e + 1 - first;
    const bool ia = a >= 0 && a < ndof, ib = b >= 0 && b < ndof;
    if (ia) { tk.emplace_back(a, a, k); tm.emplace_back(a, a, 2 * m); }
    if (ib) { tk.emplace_back(b, b, k); tm.emplace_back(b, b, 2 * m); }
    if (ia && ib) {
      tk.emplace_back(a, b, -k); tk.emplace_back(b, a, -k);
      tm.emplace_back(a, b, m); tm.emplace_back(b, a, m);
    }
  }
  Pencil p{SparseMatrix(ndof, ndof), SparseMatrix(ndof, ndof)};
  p.K.setFromTriplets(tk.begin(), tk.end());
  p.M.setFromTriplets(tm.begin(), tm.end());
  return p;
}

/// Closed-form eigenvalues of rod(n, L, ends, EA, rhoA), ascending.
inline std::vector<double> rod_eigenvalues(int n, double L, Ends ends, double EA = 1.0,
                                           double rhoA = 1.0) {
  const double h = L / n, c = 6.0 * EA / (rhoA * h * h);
  std::vector<double> l;
  // 1 - cos(th) written as 2 sin^2(th/2): no cancellation for the small th of fine meshes.
  auto add = [&](double th) {
    const double s = std::sin(0.5 * th);
    l.push_back(c * 2 * s * s / (2 + std::cos(th)));
  };
  if (ends == Ends::FixedFixed)
    for (int k = 1; k <= n - 1; ++k) add(k * M_PI / n);
  else if (ends == Ends::FreeFree)
    for (int k = 0; k <= n; ++k) add(k * M_PI / n);
  else
    for (int k = 1; k <= n; ++k) add((2 * k - 1) * M_PI / (2.0 * n));
  std::sort(l.begin(), l.end());
  return l;
}

inline SparseMatrix kron(const SparseMatrix& A, const SparseMatrix& B) {
  std::vector<Eigen::Triplet<double, std::int64_t>> t;
  t.reserve(static_cast<size_t>(A.nonZeros() * B.nonZeros()));
  for (Eigen::Index ja = 0; ja < A.outerSize(); ++ja)
    for (SparseMatrix::InnerIterator a(A, ja); a; ++a)
      for (Eigen::Index jb = 0; jb < B.outerSize(); ++jb)
        for (SparseMatrix::InnerIterator b(B, jb); b; ++b)
          t.emplace_back(a.row() * B.rows() + b.row(), a.col() * B.cols() + b.col(),
                         a.value() * b.value());
  SparseMatrix C(A.rows() * B.rows(), A.cols() * B.cols());
  C.setFromTriplets(t.begin(), t.end());
  return C;
}

/// Q1 Laplacian on a box [0,Lx]x[0,Ly]x[0,Lz] with nx x ny x nz elements (nz = 0: 2D).
inline Pencil box(int nx, double Lx, int ny, double Ly, int nz, double Lz, Ends ends) {
  const Pencil x = rod(nx, Lx, ends), y = rod(ny, Ly, ends);
  if (nz == 0) return {kron(x.K, y.M) + kron(x.M, y.K), kron(x.M, y.M)};
  const Pencil z = rod(nz, Lz, ends);
  const SparseMatrix Mxy = kron(x.M, y.M);
  return {kron(kron(x.K, y.M) + kron(x.M, y.K), z.M) + kron(Mxy, z.K), kron(Mxy, z.M)};
}

/// The `count` lowest sums of the 1D closed forms, matching box(...).
inline std::vector<double> box_eigenvalues(int nx, double Lx, int ny, double Ly, int nz,
                                           double Lz, Ends ends, size_t count) {
  const auto lx = rod_eigenvalues(nx, Lx, ends), ly = rod_eigenvalues(ny, Ly, ends);
  const auto lz = nz > 0 ? rod_eigenvalues(nz, Lz, ends) : std::vector<double>{0.0};
  std::vector<double> all;
  for (double a : lx)
    for (double b : ly)
      for (double c : lz) all.push_back(a + b + c);
  std::sort(all.begin(), all.end());
  all.resize(std::min(count, all.size()));
  return all;
}

/// Upper triangle (row <= col) of a full-storage matrix.
inline SparseMatrix upper(const SparseMatrix& A) {
  return SparseMatrix(A.triangularView<Eigen::Upper>());
}

}  // namespace ffr::test
