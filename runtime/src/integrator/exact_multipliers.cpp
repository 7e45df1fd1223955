// The multipliers that make a correction satisfy the linearised constraints exactly, for the
// Newton direction and the projections when their augmented-Lagrangian passes stall.
//
// A correction T^-1 (g + Phi_a^T mu) meets Phi_a x = c exactly when S mu = c - Phi_a T^-1 g,
// S = Phi_a Y, Y = T^-1 Phi_a^T. The passes reach the same mu at a rate 1/(1 + kq alpha s) a pass
// along an eigenvector of S of eigenvalue s: slowly where the constraints are nearly redundant
// (two revolutes of a planar mechanism modelled in 3-D both holding the out-of-plane rotations
// of a flexible body whose nodes have no torsional rotation, FORMULATION.md 9). S is positive
// semi-definite and singular where rows are combinations of others, so it is factorised by
// Cholesky with diagonal pivoting (as LAPACK's dpstrf), stopped where the rows left are
// combinations of the others up to round-off: those rows keep a zero multiplier, their residual
// is whatever the others leave (the callers check it).
#include "ffr/runtime/integrator.hpp"
#include "dense_products.hpp"

#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace ffr::runtime {

int factor_exact_multipliers(Data& data) {
  const int na = data.na, nf = data.nf;
  // Y, column by column, with the factorised tangent (data.r and data.tmp as work).
  for (int i = 0; i < na; ++i) {
    data.r.head(nf) = data.Phiq.row(i).head(nf).transpose();
    solve_tangent(data, data.r, data.tmp);
    data.projY.col(i) = data.tmp;
  }
  auto S = data.projS.topLeftCorner(na, na);
  for (int i = 0; i < na; ++i)
    detail::times(data.Phiq.data(), data.Phiq.rows(), na, nf, data.projY.col(i).data(), &data.projS(0, i), false);
  data.proj_rank = pivoted_cholesky(S, data.proj_order, data.proj_mu);
  return data.proj_rank;
}

void solve_exact_multipliers(Data& data, const VectorXd& c) {
  const int na = data.na;
  pivoted_cholesky_solve(data.projS.topLeftCorner(na, na), data.proj_order, data.proj_rank, c, data.proj_w, data.proj_mu);
}

int pivoted_cholesky(Eigen::Ref<MatrixXd> S, std::vector<int>& p, VectorXd& own) {
  const int na = static_cast<int>(S.rows());
  // Pivoted Cholesky S(p, p) = L L^T in S's lower triangle; the trailing block is updated whole
  // (both triangles) so that its rows and columns can be swapped. The pivot is the row whose
  // remaining diagonal is the largest share of its own (the rows mix lengths and angles); a row
  // left with less than redundant_share of it is a combination of the rows before it up to
  // round-off, and so are all the rows left then.
  constexpr double redundant_share = 1e-9;
  for (int i = 0; i < na; ++i) {
    p[static_cast<std::size_t>(i)] = i;
    own(i) = S(i, i);
  }
  const auto share = [&](int i) {
    const double d = own(p[static_cast<std::size_t>(i)]);
    return d > 0 ? S(i, i) / d : 0.0;
  };
  int rank = 0;
  for (int k = 0; k < na; ++k) {
    int j = k;
    for (int i = k + 1; i < na; ++i)
      if (share(i) > share(j)) j = i;
    if (!(share(j) > redundant_share)) break;
    if (j != k) {
      S.row(k).swap(S.row(j));
      S.col(k).swap(S.col(j));
      std::swap(p[static_cast<std::size_t>(k)], p[static_cast<std::size_t>(j)]);
    }
    const double d = std::sqrt(S(k, k));
    S(k, k) = d;
    for (int i = k + 1; i < na; ++i) S(i, k) /= d;
    for (int col = k + 1; col < na; ++col)
      for (int i = k + 1; i < na; ++i) S(i, col) -= S(i, k) * S(col, k);
    rank = k + 1;
  }
  return rank;
}

void pivoted_cholesky_solve(const Eigen::Ref<const MatrixXd>& S, const std::vector<int>& p, int rank, const VectorXd& c, VectorXd& w,
                            VectorXd& mu) {
  // w = L11^-T L11^-1 c(p)_1, then mu(p) = [w; 0].
  for (int i = 0; i < rank; ++i) {
    double v = c(p[static_cast<std::size_t>(i)]);
    for (int k = 0; k < i; ++k) v -= S(i, k) * w(k);
    w(i) = v / S(i, i);
  }
  for (int i = rank - 1; i >= 0; --i) {
    double v = w(i);
    for (int k = i + 1; k < rank; ++k) v -= S(k, i) * w(k);
    w(i) = v / S(i, i);
  }
  mu.head(S.rows()).setZero();
  for (int i = 0; i < rank; ++i) mu(p[static_cast<std::size_t>(i)]) = w(i);
}

}  // namespace ffr::runtime
