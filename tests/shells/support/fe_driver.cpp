#include "fe_driver.hpp"

#include <Eigen/SparseCholesky>
#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ffr::test {

void Assembler::add(const std::vector<int>& nodes, const Eigen::MatrixXd& Ke, const Eigen::MatrixXd& Me) {
  const int ne = static_cast<int>(nodes.size()) * dpn_;
  if (Ke.rows() != ne || Me.rows() != ne) throw std::invalid_argument("Assembler::add: size mismatch");
  for (int a = 0; a < ne; ++a)
    for (int b = 0; b < ne; ++b) {
      const int i = nodes[a / dpn_] * dpn_ + a % dpn_, j = nodes[b / dpn_] * dpn_ + b % dpn_;
      if (Ke(a, b) != 0) k_.emplace_back(i, j, Ke(a, b));
      if (Me(a, b) != 0) m_.emplace_back(i, j, Me(a, b));
    }
}

SpMat Assembler::K() const {
  SpMat A(n_, n_);
  A.setFromTriplets(k_.begin(), k_.end());
  return A;
}

SpMat Assembler::M() const {
  SpMat A(n_, n_);
  A.setFromTriplets(m_.begin(), m_.end());
  return A;
}

namespace {

std::vector<int> free_map(const std::vector<bool>& fixed, int& nfree) {
  std::vector<int> map(fixed.size(), -1);
  nfree = 0;
  for (std::size_t i = 0; i < fixed.size(); ++i)
    if (!fixed[i]) map[i] = nfree++;
  return map;
}

SpMat restrict(const SpMat& A, const std::vector<int>& map, int nfree) {
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < A.outerSize(); ++k)
    for (SpMat::InnerIterator it(A, k); it; ++it) {
      const int i = map[it.row()], j = map[it.col()];
      if (i >= 0 && j >= 0) t.emplace_back(i, j, it.value());
    }
  SpMat R(nfree, nfree);
  R.setFromTriplets(t.begin(), t.end());
  return R;
}

/// (K - sigma M)^-1 by sparse LDLT, as Spectra's shift-invert operator.
class LdltShiftInvert {
 public:
  using Scalar = double;
  LdltShiftInvert(const SpMat& K, const SpMat& M) : K_(K), M_(M) {}
  Eigen::Index rows() const { return K_.rows(); }
  Eigen::Index cols() const { return K_.cols(); }
  void set_shift(double sigma) {
    ldlt_.compute(SpMat(K_ - sigma * M_));
    if (ldlt_.info() != Eigen::Success) throw std::runtime_error("shift-invert factorization failed");
  }
  void perform_op(const double* x, double* y) const {
    Eigen::Map<const Eigen::VectorXd> xin(x, rows());
    Eigen::Map<Eigen::VectorXd>(y, rows()) = ldlt_.solve(xin);
  }

 private:
  const SpMat& K_;
  const SpMat& M_;
  Eigen::SimplicialLDLT<SpMat> ldlt_;
};

}  // namespace

Eigen::VectorXd solve_static(const SpMat& K, const Eigen::VectorXd& f, const std::vector<bool>& fixed) {
  int nfree = 0;
  const auto map = free_map(fixed, nfree);
  const SpMat Kf = restrict(K, map, nfree);
  Eigen::VectorXd ff(nfree);
  for (std::size_t i = 0; i < map.size(); ++i)
    if (map[i] >= 0) ff(map[i]) = f(static_cast<Eigen::Index>(i));
  Eigen::SimplicialLDLT<SpMat> ldlt(Kf);
  if (ldlt.info() != Eigen::Success) throw std::runtime_error("static factorization failed");
  const Eigen::VectorXd uf = ldlt.solve(ff);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(K.rows());
  for (std::size_t i = 0; i < map.size(); ++i)
    if (map[i] >= 0) u(static_cast<Eigen::Index>(i)) = uf(map[i]);
  return u;
}

Eigen::VectorXd eigenvalues(const SpMat& K, const SpMat& M, const std::vector<bool>& fixed, int count, double sigma,
                            Eigen::MatrixXd* vectors) {
  int nfree = 0;
  const auto map = free_map(fixed, nfree);
  const SpMat Kf = restrict(K, map, nfree), Mf = restrict(M, map, nfree);
  LdltShiftInvert op(Kf, Mf);
  Spectra::SparseSymMatProd<double> bop(Mf);
  const int ncv = std::min(nfree, std::max(2 * count + 1, count + 20));
  Spectra::SymGEigsShiftSolver<LdltShiftInvert, Spectra::SparseSymMatProd<double>, Spectra::GEigsMode::ShiftInvert>
      solver(op, bop, count, ncv, sigma);
  solver.init();
  solver.compute(Spectra::SortRule::LargestMagn, 2000, 1e-12);
  if (solver.info() != Spectra::CompInfo::Successful) throw std::runtime_error("eigen-solve did not converge");
  Eigen::VectorXd lam = solver.eigenvalues();
  Eigen::MatrixXd vec = solver.eigenvectors();
  // Spectra returns them in descending order of 1/(lambda - sigma): ascending lambda.
  std::vector<int> order(lam.size());
  for (int i = 0; i < lam.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return lam(a) < lam(b); });
  Eigen::VectorXd out(lam.size());
  Eigen::MatrixXd full = Eigen::MatrixXd::Zero(K.rows(), lam.size());
  for (int k = 0; k < lam.size(); ++k) {
    out(k) = lam(order[k]);
    for (std::size_t i = 0; i < map.size(); ++i)
      if (map[i] >= 0) full(static_cast<Eigen::Index>(i), k) = vec(map[i], order[k]);
  }
  if (vectors) *vectors = full;
  return out;
}

Eigen::VectorXd hertz(const Eigen::VectorXd& lambda) {
  return lambda.unaryExpr([](double l) { return std::sqrt(std::max(l, 0.0)) / (2 * M_PI); });
}

std::vector<std::vector<int>> Grid::quads() const {
  std::vector<std::vector<int>> q;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) q.push_back({node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)});
  return q;
}

std::vector<std::vector<int>> Grid::triangles() const {
  std::vector<std::vector<int>> t;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int a = node(i, j), b = node(i + 1, j), c = node(i + 1, j + 1), d = node(i, j + 1);
      if ((i + j) % 2 == 0) {
        t.push_back({a, b, c});
        t.push_back({a, c, d});
      } else {
        t.push_back({a, b, d});
        t.push_back({b, c, d});
      }
    }
  return t;
}

Eigen::MatrixX3d Grid::coords(const std::vector<int>& nodes) const {
  Eigen::MatrixX3d xe(nodes.size(), 3);
  for (std::size_t k = 0; k < nodes.size(); ++k) xe.row(static_cast<Eigen::Index>(k)) = x.row(nodes[k]);
  return xe;
}

Grid make_grid(int nu, int nv, const std::function<Eigen::Vector3d(double, double)>& p) {
  Grid g;
  g.nu = nu;
  g.nv = nv;
  g.x.resize((nu + 1) * (nv + 1), 3);
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) g.x.row(g.node(i, j)) = p(double(i) / nu, double(j) / nv).transpose();
  return g;
}

}  // namespace ffr::test
