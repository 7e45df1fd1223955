#pragma once
// A small, self-contained static/modal finite-element driver for the structural-kernel tests:
// assembly of element matrices on 6-DOF nodes, elimination of fixed DOFs, a sparse LDLT static
// solve and a Spectra shift-invert generalized eigen-solve. Test support only: the production
// assembly and solvers live elsewhere and are deliberately not used here.

#include "ffr/preproc/elements/element.hpp"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <functional>
#include <vector>

namespace ffr::test {

using SpMat = Eigen::SparseMatrix<double>;

class Assembler {
 public:
  Assembler(int num_nodes, int dofs_per_node = 6) : n_(num_nodes * dofs_per_node), dpn_(dofs_per_node) {}
  /// Adds element matrices acting on `nodes` (dofs_per_node each, in order).
  void add(const std::vector<int>& nodes, const Eigen::MatrixXd& Ke, const Eigen::MatrixXd& Me);
  void add(const std::vector<int>& nodes, const preproc::ElementMatrices& em) { add(nodes, em.K, em.M); }
  SpMat K() const;
  SpMat M() const;
  int size() const { return n_; }
  int dofs_per_node() const { return dpn_; }

 private:
  int n_, dpn_;
  std::vector<Eigen::Triplet<double>> k_, m_;
};

/// Solves K u = f with u = 0 on the fixed DOFs.
Eigen::VectorXd solve_static(const SpMat& K, const Eigen::VectorXd& f, const std::vector<bool>& fixed);

/// The `count` smallest eigenvalues lambda = omega^2 of K x = lambda M x on the free DOFs,
/// ascending (shift-invert about sigma < 0, so singular K with rigid-body modes is fine).
Eigen::VectorXd eigenvalues(const SpMat& K, const SpMat& M, const std::vector<bool>& fixed, int count,
                            double sigma = -1.0, Eigen::MatrixXd* vectors = nullptr);

/// Frequencies in Hz from eigenvalues (negative round-off clamped to 0).
Eigen::VectorXd hertz(const Eigen::VectorXd& lambda);

/// A structured grid of (nu + 1) x (nv + 1) nodes mapped by p(u, v), u, v in [0, 1].
struct Grid {
  int nu = 0, nv = 0;
  Eigen::MatrixX3d x;
  int node(int i, int j) const { return j * (nu + 1) + i; }
  /// Counter-clockwise in (u, v): (i,j), (i+1,j), (i+1,j+1), (i,j+1).
  std::vector<std::vector<int>> quads() const;
  /// Each quad split in two along alternating diagonals.
  std::vector<std::vector<int>> triangles() const;
  Eigen::MatrixX3d coords(const std::vector<int>& nodes) const;
};
Grid make_grid(int nu, int nv, const std::function<Eigen::Vector3d(double, double)>& p);

}  // namespace ffr::test
