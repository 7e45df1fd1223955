// What happens to every backend's eigenvectors before they are returned:
//  1. X <- P X: removes the round-off component along the deflation basis R;
//  2. Rayleigh-Ritz on span(X): solve (X^T K X) Y = (X^T M X) Y diag(l) and X <- X Y. This
//     makes X M-orthonormal to round-off, turns each eigenvalue into its Rayleigh quotient
//     (the best estimate from the subspace), and resolves the arbitrary basis a backend
//     returns inside a multiple eigenvalue (e.g. the symmetric modes of a cube);
//  3. selection, sign convention;
//  4. checks of the returned vectors: their residuals K x - l M x, X^T M X and X^T K X.
// K X and M X are formed once, kChunk columns at a time, and rotated with X (K (X Y) = (K X) Y):
// a second pass over K and M for the checks took 40-60 ms of the 100k-DOF plate's run. The
// rotated products differ from fresh ones by rounding in the rotation, of the order of
// eps |K X| |Y|, below the rounding of a fresh product itself (eps |K| |X|): the residuals
// checked are those of the returned vectors. X and the products are rotated in place: whole
// new n x m matrices, with the products' temporaries, put 85 MB on top of the factor at the end
// of the eigen-solve (100k-DOF plate, 20 modes), the run's peak at one thread then.

#include "eigen_backends.hpp"
#include "tall_skinny.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace ffr::preproc::detail {
namespace {

// Columns per product of K or M with X: one pass over the matrix each, vectorized at widths
// 4, 8 and 16 (sparse_types.cpp).
constexpr Eigen::Index kChunk = 8;

// K X and M X, kChunk columns per product.
void products(const SparseRef& K, SymmetricStorage sK, const SparseRef& M, SymmetricStorage sM, const Eigen::MatrixXd& X,
              Eigen::MatrixXd& KX, Eigen::MatrixXd& MX) {
  KX.resize(X.rows(), X.cols());
  MX.resize(X.rows(), X.cols());
  for (Eigen::Index c0 = 0; c0 < X.cols(); c0 += kChunk) {
    const Eigen::Index w = std::min(kChunk, X.cols() - c0);
    KX.middleCols(c0, w) = sym_multiply(K, sK, X.middleCols(c0, w));
    MX.middleCols(c0, w) = sym_multiply(M, sM, X.middleCols(c0, w));
  }
}

}  // namespace

Eigen::VectorXd normalize_signs(Eigen::MatrixXd& X) {
  Eigen::VectorXd signs = Eigen::VectorXd::Ones(X.cols());
  for (Eigen::Index j = 0; j < X.cols(); ++j) {
    auto x = X.col(j);
    const double amax = x.cwiseAbs().maxCoeff();
    if (!(amax > 0)) continue;
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      if (std::abs(x[i]) >= kSignThreshold * amax) {
        if (x[i] < 0) {
          x = -x;
          signs[j] = -1.0;
        }
        break;
      }
    }
  }
  return signs;
}

void finish_eigenpairs(const SparseRef& K, SymmetricStorage sK, const SparseRef& M,
                       SymmetricStorage sM, const Deflation& deflation, Eigen::MatrixXd X,
                       int keep, double lambda_max, EigenResult& out) {
  for (Eigen::Index j = 0; j < X.cols(); ++j) deflation.project(X.col(j).data());

  // Rayleigh-Ritz. Scaling the columns first keeps the small pencil well balanced.
  for (Eigen::Index j = 0; j < X.cols(); ++j) {
    const double nrm = X.col(j).norm();
    if (nrm > 0) X.col(j) /= nrm;
  }
  Eigen::MatrixXd KX, MX;
  products(K, sK, M, sM, X, KX, MX);
  {
    const Eigen::Index k = X.cols();
    Eigen::MatrixXd Ks = transposed_product(X, KX), Ms = transposed_product(X, MX);
    Ks = 0.5 * (Ks + Ks.transpose());
    Ms = 0.5 * (Ms + Ms.transpose());
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> rr(Ks, Ms);
    out.lambda = rr.eigenvalues();  // ascending
    // M-orthonormal: Y^T Ms Y = I.
    for (Eigen::MatrixXd* Z : {&X, &KX, &MX}) rotate_columns_in_place(*Z, k, rr.eigenvectors());
  }

  // Selection: the `keep` lowest, and those not above lambda_max.
  Eigen::Index m = out.lambda.size();
  if (keep > 0) m = std::min<Eigen::Index>(m, keep);
  if (std::isfinite(lambda_max))
    while (m > 0 && out.lambda[m - 1] > lambda_max) --m;
  out.lambda.conservativeResize(m);
  for (Eigen::MatrixXd* Z : {&X, &KX, &MX}) Z->conservativeResize(Eigen::NoChange, m);
  const Eigen::VectorXd signs = normalize_signs(X);
  for (Eigen::Index j = 0; j < m; ++j)
    if (signs[j] < 0) {
      KX.col(j) = -KX.col(j);
      MX.col(j) = -MX.col(j);
    }

  const double nK = sym_norm1(K, sK), nM = sym_norm1(M, sM);
  out.relative_residual.resize(m);
  out.backward_error.resize(m);
  for (Eigen::Index j = 0; j < m; ++j) {
    const double l = out.lambda[j];
    const double r = (KX.col(j) - l * MX.col(j)).norm();
    const double denom = KX.col(j).norm() + std::abs(l) * MX.col(j).norm();
    out.relative_residual[j] = denom > 0 ? r / denom : r;
    const double bden = (nK + std::abs(l) * nM) * X.col(j).norm();
    out.backward_error[j] = bden > 0 ? r / bden : r;
  }
  // The reduced matrices come with the checks' products: a caller needs them and would
  // otherwise multiply K and M by X once more.
  out.XtKX = transposed_product(X, KX);
  out.XtMX = transposed_product(X, MX);
  out.max_relative_residual = m > 0 ? out.relative_residual.maxCoeff() : 0.0;
  out.orthonormality_error = m > 0 ? (out.XtMX - Eigen::MatrixXd::Identity(m, m)).cwiseAbs().maxCoeff() : 0.0;
  out.deflation_error =
      (m > 0 && !deflation.empty()) ? (deflation.MR.transpose() * X).cwiseAbs().maxCoeff() : 0.0;
  out.X = std::move(X);
}

std::string check_eigenpairs(const EigenResult& r, const EigenOptions& o) {
  std::ostringstream why;
  for (Eigen::Index j = 0; j < r.lambda.size(); ++j) {
    if (!(r.relative_residual[j] <= o.residual_tol) &&
        !(r.backward_error[j] <= kRoundoffBackwardError)) {
      why << "eigenpair " << j << " (lambda = " << r.lambda[j] << ") has relative residual "
          << r.relative_residual[j] << " > " << o.residual_tol << " and backward error "
          << r.backward_error[j] << " above the rounding level " << kRoundoffBackwardError;
      return why.str();
    }
    if (!(r.lambda[j] > o.sigma)) {
      why << "eigenvalue " << r.lambda[j] << " is not above the shift " << o.sigma;
      return why.str();
    }
  }
  if (!(r.orthonormality_error <= o.orthonormality_tol))
    why << "M-orthonormality error max|X^T M X - I| = " << r.orthonormality_error << " > "
        << o.orthonormality_tol;
  else if (!(r.deflation_error <= o.orthonormality_tol))
    why << "M-orthogonality to the deflation basis max|R^T M X| = " << r.deflation_error << " > "
        << o.orthonormality_tol;
  return why.str();
}

}  // namespace ffr::preproc::detail
