// Third Lanczos backend: block shift-invert Lanczos in the M inner product, with full
// reorthogonalization and thick (Krylov-Schur-like) restarts.
//
// Why a block method: single-vector Lanczos applies (K - sigma M)^{-1} one vector at a
// time, and each application streams the whole Cholesky factor through memory twice
// (forward and backward substitution). For the factors of 10^5..10^6-DOF parts that is
// bandwidth-bound and dominated the reduction (measured: tools/bench/reduce/RESULTS.md). A
// block of p vectors streams the factor once for all p (the substitutions apply each factor
// entry to the p interleaved vectors at once, supernodal_solve.hpp), so the cost per vector
// drops several-fold, while the block Krylov space needs only slightly more vectors than the
// single-vector one.
//
// Operator A = P (K - sigma M)^{-1} P^T M, self-adjoint in the M inner product, with
// eigenvalues theta = 1 / (lambda - sigma) > 0 (sigma below the wanted spectrum). With an
// M-orthonormal basis Q_k and A Q_k = Q_k T_k + Q_{k+1} B e_k^T (block Lanczos relation),
// the Ritz pairs (theta_i, Q_k s_i) of T_k have residual norms ||B s_i(last block)||_M
// (Golub & Van Loan, "Matrix Computations", 4th ed., sec. 10.3.6, block Lanczos), which is
// the convergence test: ||r_i|| <= tol * theta_i, as in Spectra and ARPACK.
//
// Numerics: every new block is M-orthogonalized against the whole basis twice (classical
// Gram-Schmidt twice, "twice is enough") and normalized by Cholesky QR done twice
// (CholQR2). A breakdown (a block without full rank after orthogonalization) is reported as
// a failure; the caller then falls back to Spectra, so the backend never has to handle it.

#include "eigen_backends.hpp"
#include "../run_parts.hpp"
#include "tall_skinny.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

namespace ffr::preproc::detail {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

// W <- W R^{-1} and MW <- MW R^{-1} with W^T MW = R^T R. False if the block is (nearly)
// rank-deficient in the M norm.
bool cholesky_qr(MatrixXd& W, MatrixXd& MW, MatrixXd& R) {
  MatrixXd G = transposed_product(W, MW);
  G = 0.5 * (G + G.transpose());
  Eigen::LLT<MatrixXd> llt(G);
  if (llt.info() != Eigen::Success) return false;
  R = llt.matrixU();
  const VectorXd d = R.diagonal().cwiseAbs();
  if (!(d.minCoeff() > 1e-7 * d.maxCoeff())) return false;  // condition of G above ~1e14
  solve_upper_on_right(R, W);
  solve_upper_on_right(R, MW);
  return true;
}

// One classical Gram-Schmidt pass in the M inner product: c = Q^T MW, W <- W - Q c; returns c.
// Both products run over row parts (tall_skinny.hpp), the partial c summed between them.
MatrixXd project_out(const Eigen::Ref<const MatrixXd>& Q, const MatrixXd& MW, MatrixXd& W) {
  const Index n = Q.rows(), k = Q.cols(), p = W.cols();
  const unsigned parts = parts_for(n * k, Index{1} << 18);
  const auto split = [&](unsigned part) { return n * static_cast<Index>(part) / static_cast<Index>(parts); };
  std::vector<MatrixXd> partial(parts, MatrixXd::Zero(k, p));
  run_parts(parts, split, [&](unsigned part, Index r0, Index r1) {
    add_transposed_product(Q.data(), Q.outerStride(), k, MW.data(), MW.outerStride(), p, r0, r1, partial[part].data());
  });
  MatrixXd c = partial[0];
  for (unsigned part = 1; part < parts; ++part) c += partial[part];
  run_parts(parts, split, [&](unsigned, Index r0, Index r1) {
    subtract_product(Q.data(), Q.outerStride(), k, c.data(), p, r0, r1, W.data(), W.outerStride());
  });
  return c;
}

}  // namespace

int count_converged_ritz_pairs(const Eigen::VectorXd& theta, const Eigen::MatrixXd& coupling, int nev, double tol) {
  // The basis holds k = theta.size() Ritz pairs, fewer than nev while it is still small (k
  // starts at one block, and a block may be narrower than nev): only those exist to test.
  const Index pairs = std::min<Index>({Index{nev}, theta.size(), coupling.cols()});
  int converged = 0;
  for (Index i = 0; i < pairs; ++i)
    if (theta[i] > 0 && coupling.col(i).norm() <= tol * theta[i]) ++converged;
  return converged;
}

BackendOutcome run_block_lanczos(ShiftInvertOp& op, const SparseRef& M, SymmetricStorage sM,
                                 const Deflation& deflation, const BlockRequest& req) {
  BackendOutcome out;
  const Index n = op.rows();
  const int nev = req.nev, p = req.block;
  const Index m_max = req.max_basis;
  auto fail = [&](const std::string& why) {
    out.success = false;
    out.message = "block Lanczos: " + why;
    return out;
  };
  if (nev < 1 || p < 1 || m_max < nev + 2 * p || 2 * m_max > n)
    return fail("basis size " + std::to_string(m_max) + " does not fit nev = " + std::to_string(nev) + ", block " +
                std::to_string(p) + ", n = " + std::to_string(n));

  const auto mass = [&](const MatrixXd& X, MatrixXd& Y) {
    if (req.mass_product) req.mass_product(X, Y);
    else sym_multiply(M, sM, X, Y);
  };
  MatrixXd Q(n, m_max);                    // M-orthonormal basis, columns [0, k)
  MatrixXd T = MatrixXd::Zero(m_max, m_max);  // Q^T M A Q, filled block column by block column
  MatrixXd W(n, p), MW(n, p), R;

  // Start block: deterministic pseudo-random columns, outside the deflation space, then put
  // into the range of the operator by one block solve (as ARPACK's dgetv0 does in shift-invert
  // mode). Why: the Ritz vectors keep the start block's components at the level of the
  // Lanczos tolerance, and a random block is all high-frequency content, which K amplifies by
  // ||K|| / lambda in the residual K x - lambda M x. On the 100k-DOF plate (20 modes) the
  // Ritz vectors of a random start had relative residuals up to 2.1e-9 and needed one more
  // block solve of every vector (20 solves) to pass the checks comfortably; from a solved
  // start they have 4.9e-10 for 4 solves.
  std::mt19937_64 rng(req.seed);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (Index j = 0; j < p; ++j) {
    for (Index i = 0; i < n; ++i) W(i, j) = u(rng);
    deflation.project(W.col(j).data());
  }
  // The blocks W, MW and MV are written in place from here on: new n x p results at every
  // step put 10 MB more on the 100k-DOF plate's peak, at the end of this stage.
  op.apply_block(W, W);
  for (int pass = 0; pass < 2; ++pass) {
    mass(W, MW);
    if (!cholesky_qr(W, MW, R)) return fail("the start block has no full rank");
  }
  Q.leftCols(p) = W;
  Index k = p;         // basis size
  MatrixXd MV = MW;    // M times the last block of the basis

  Eigen::SelfAdjointEigenSolver<MatrixXd> es;
  for (;;) {
    // Expand: W = A V for the last block V = Q(:, k-p:k).
    op.apply_block(MV, W);
    auto basis = Q.leftCols(k);
    MatrixXd h = MatrixXd::Zero(k, p);
    for (int pass = 0; pass < 2; ++pass) {
      mass(W, MW);
      h += project_out(basis, MW, W);
    }
    // MW is now M W up to M basis c of the second pass, which is at the rounding level.
    T.block(0, k - p, k, p) = h;
    MatrixXd B;  // W_old = W_new B
    if (!cholesky_qr(W, MW, B)) return fail("breakdown (the Krylov space became invariant)");
    MatrixXd R2;
    if (!cholesky_qr(W, MW, R2)) return fail("breakdown in the second orthogonalization");
    B = R2 * B;

    // Ritz values of the symmetrized projection (largest theta first).
    const MatrixXd Tk = 0.5 * (T.topLeftCorner(k, k) + T.topLeftCorner(k, k).transpose());
    es.compute(Tk);
    if (es.info() != Eigen::Success) return fail("Ritz eigen-decomposition failed");
    const VectorXd theta = es.eigenvalues().reverse();
    const MatrixXd S = es.eigenvectors().rowwise().reverse();
    const MatrixXd coupling = B * S.bottomRows(p);  // residual of Ritz pair i: column i, M-norm
    const int converged = count_converged_ritz_pairs(theta, coupling, nev, req.tol);
    out.converged = converged;
    if (converged == nev) {
      rotate_columns_in_place(Q, k, S.leftCols(nev));
      Q.conservativeResize(Eigen::NoChange, nev);  // column-major: keeps the leading columns, frees the rest
      out.X = std::move(Q);
      out.lambda.resize(nev);
      for (int i = 0; i < nev; ++i) out.lambda[i] = req.sigma + 1.0 / theta[i];
      out.success = true;
      return out;
    }
    if (k + p <= m_max) {  // room left: append the new block (and B below the diagonal)
      Q.middleCols(k, p) = W;
      T.block(k, k - p, p, p) = B;
      k += p;
      MV = MW;
      continue;
    }
    // Thick restart: keep the leading Ritz vectors, then the new block; T becomes the arrow
    // matrix [diag(theta); coupling] in the kept columns (A y_i = theta_i y_i + W B s_i,last).
    if (++out.iterations > req.max_restarts)
      return fail("not converged after " + std::to_string(req.max_restarts) + " restarts (" +
                  std::to_string(converged) + " of " + std::to_string(nev) + " pairs)");
    const Index keep = std::min<Index>(k - p, nev + p);
    rotate_columns_in_place(Q, k, S.leftCols(keep));
    Q.middleCols(keep, p) = W;
    T.setZero();
    for (Index i = 0; i < keep; ++i) T(i, i) = theta[i];
    T.block(keep, 0, p, keep) = coupling.leftCols(keep);
    T.block(0, keep, keep, p) = coupling.leftCols(keep).transpose();
    k = keep + p;
    MV = MW;
  }
}

}  // namespace ffr::preproc::detail
