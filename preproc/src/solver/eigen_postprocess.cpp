// What happens to every backend's eigenvectors before they are returned:
//  1. X <- P X: removes the round-off component along the deflation basis R;
//  2. Rayleigh-Ritz on span(X): solve (X^T K X) Y = (X^T M X) Y diag(l) and X <- X Y. This
//     makes X M-orthonormal to round-off, turns each eigenvalue into its Rayleigh quotient
//     (the best estimate from the subspace), and resolves the arbitrary basis a backend
//     returns inside a multiple eigenvalue (e.g. the symmetric modes of a cube);
//  3. selection, sign convention;
//  4. checks with freshly computed K X and M X (not the transformed ones), so the reported
//     residuals are those of the vectors actually returned.
// K X and M X are formed kChunk columns at a time, and X is rotated in place: whole n x m
// products (with the new X of the Rayleigh-Ritz step and the products' own temporaries) put
// 85 MB on top of the factor at the end of the eigen-solve, which set the peak of the 100k-DOF
// plate's reduction at one thread (tools/bench/reduce, 20 modes).

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

// Calls f(c0, KXc, MXc) for the column chunks [c0, c0 + w) of X with KXc = K X(:, c0:c0+w)
// and MXc = M X(:, c0:c0+w).
template <class F>
void for_product_chunks(const SparseRef& K, SymmetricStorage sK, const SparseRef& M, SymmetricStorage sM,
                        const Eigen::MatrixXd& X, F&& f) {
  for (Eigen::Index c0 = 0; c0 < X.cols(); c0 += kChunk) {
    const Eigen::Index w = std::min(kChunk, X.cols() - c0);
    const Eigen::MatrixXd KXc = sym_multiply(K, sK, X.middleCols(c0, w));
    const Eigen::MatrixXd MXc = sym_multiply(M, sM, X.middleCols(c0, w));
    f(c0, KXc, MXc);
  }
}

}  // namespace

void normalize_signs(Eigen::MatrixXd& X) {
  for (Eigen::Index j = 0; j < X.cols(); ++j) {
    auto x = X.col(j);
    const double amax = x.cwiseAbs().maxCoeff();
    if (!(amax > 0)) continue;
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      if (std::abs(x[i]) >= kSignThreshold * amax) {
        if (x[i] < 0) x = -x;
        break;
      }
    }
  }
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
  {
    const Eigen::Index k = X.cols();
    Eigen::MatrixXd Ks(k, k), Ms(k, k);
    for_product_chunks(K, sK, M, sM, X, [&](Eigen::Index c0, const Eigen::MatrixXd& KXc, const Eigen::MatrixXd& MXc) {
      Ks.middleCols(c0, KXc.cols()) = transposed_product(X, KXc);
      Ms.middleCols(c0, MXc.cols()) = transposed_product(X, MXc);
    });
    Ks = 0.5 * (Ks + Ks.transpose());
    Ms = 0.5 * (Ms + Ms.transpose());
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> rr(Ks, Ms);
    out.lambda = rr.eigenvalues();                     // ascending
    rotate_columns_in_place(X, k, rr.eigenvectors());  // M-orthonormal: Y^T Ms Y = I
  }

  // Selection: the `keep` lowest, and those not above lambda_max.
  Eigen::Index m = out.lambda.size();
  if (keep > 0) m = std::min<Eigen::Index>(m, keep);
  if (std::isfinite(lambda_max))
    while (m > 0 && out.lambda[m - 1] > lambda_max) --m;
  out.lambda.conservativeResize(m);
  X.conservativeResize(Eigen::NoChange, m);
  normalize_signs(X);

  const double nK = sym_norm1(K, sK), nM = sym_norm1(M, sM);
  out.relative_residual.resize(m);
  out.backward_error.resize(m);
  // The reduced matrices come with the checks' products: a caller needs them and would
  // otherwise multiply K and M by X once more.
  out.XtKX.resize(m, m);
  out.XtMX.resize(m, m);
  for_product_chunks(K, sK, M, sM, X, [&](Eigen::Index c0, const Eigen::MatrixXd& KXc, const Eigen::MatrixXd& MXc) {
    for (Eigen::Index c = 0; c < KXc.cols(); ++c) {
      const Eigen::Index j = c0 + c;
      const double l = out.lambda[j];
      const double r = (KXc.col(c) - l * MXc.col(c)).norm();
      const double denom = KXc.col(c).norm() + std::abs(l) * MXc.col(c).norm();
      out.relative_residual[j] = denom > 0 ? r / denom : r;
      const double bden = (nK + std::abs(l) * nM) * X.col(j).norm();
      out.backward_error[j] = bden > 0 ? r / bden : r;
    }
    out.XtKX.middleCols(c0, KXc.cols()) = transposed_product(X, KXc);
    out.XtMX.middleCols(c0, MXc.cols()) = transposed_product(X, MXc);
  });
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
