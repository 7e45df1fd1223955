// Deflation: free bodies with a negative shift and the rigid-body null space excluded
// exactly; closed-form elastic eigenvalues from pencils.hpp.
#include "ffr/preproc/solver/eigen_solver.hpp"
#include "ffr/preproc/solver/shift_invert_ops.hpp"
#include "pencils.hpp"

#include <gtest/gtest.h>

using namespace ffr::preproc;
using ffr::test::Ends;

TEST(EigenDeflation, FreeRodReturnsElasticModesOnly) {
  const int n = 300;
  const double EA = 2.1e7, rhoA = 0.785;  // steel, 1 cm^2
  const auto p = ffr::test::rod(n, 1.5, Ends::FreeFree, EA, rhoA);
  const auto ref = ffr::test::rod_eigenvalues(n, 1.5, Ends::FreeFree, EA, rhoA);  // ref[0] = 0
  EigenOptions o;
  o.nev = 10;
  o.sigma = -0.1 * ref[1];  // negative: K - sigma M is positive definite for a free body
  o.deflation = Eigen::MatrixXd::Constant(n + 1, 1, 3.0);  // rigid translation, unnormalized
  EigenSolver s(o);
  const EigenResult& r = s.compute(p.K, p.M);
  ASSERT_EQ(r.lambda.size(), 10);
  for (int k = 0; k < 10; ++k) EXPECT_NEAR(r.lambda[k], ref[k + 1], 1e-10 * ref[k + 1]) << k;
  // Exactly M-orthogonal to the rigid translation: |1^T M x| relative to |1|_M |x|_M = |1|_M.
  const double mass = Eigen::VectorXd::Ones(n + 1).dot(p.M * Eigen::VectorXd::Ones(n + 1));
  const Eigen::RowVectorXd rt = Eigen::RowVectorXd::Ones(n + 1) * p.M * r.X / std::sqrt(mass);
  EXPECT_LT(rt.cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_LT(r.deflation_error, 1e-13);
  EXPECT_LT(r.max_relative_residual, 1e-10);
}

TEST(EigenDeflation, FreeBoxNeumannLaplacian) {
  // Q1 Laplacian on a free (Neumann) box: the constant is the null space. 7x6x5 elements,
  // 8*7*6 = 336 DOF.
  const auto p = ffr::test::box(7, 1.0, 6, 0.9, 5, 0.7, Ends::FreeFree);
  const auto ref = ffr::test::box_eigenvalues(7, 1.0, 6, 0.9, 5, 0.7, Ends::FreeFree, 13);
  ASSERT_NEAR(ref[0], 0.0, 1e-12);
  EigenOptions o;
  o.nev = 12;
  o.sigma = -1.0;
  o.deflation = Eigen::MatrixXd::Ones(p.K.rows(), 1);
  for (EigenBackend b : {EigenBackend::Spectra, EigenBackend::Arpack, EigenBackend::Dense}) {
    o.backend = b;
    EigenSolver s(o);
    const EigenResult& r = s.compute(p.K, p.M);
    ASSERT_EQ(r.lambda.size(), 12) << to_string(b);
    for (int k = 0; k < 12; ++k)
      EXPECT_NEAR(r.lambda[k], ref[k + 1], 1e-10 * ref[k + 1]) << to_string(b) << " " << k;
    EXPECT_LT(r.deflation_error, 1e-12) << to_string(b);
  }
}

TEST(EigenDeflation, KnownElasticModesAreExcludedExactly) {
  // Deflate the first two fixed-fixed modes (sin(j k pi / n), k = 1, 2): the solver must
  // return modes 3, 4, ... as its lowest.
  const int n = 200;
  const auto p = ffr::test::rod(n, 1.0, Ends::FixedFixed);
  const auto ref = ffr::test::rod_eigenvalues(n, 1.0, Ends::FixedFixed);
  Eigen::MatrixXd R(n - 1, 2);
  for (int k = 1; k <= 2; ++k)
    for (int j = 1; j < n; ++j) R(j - 1, k - 1) = std::sin(j * k * M_PI / n);
  EigenOptions o;
  o.nev = 5;
  o.deflation = R;
  EigenSolver s(o);
  const EigenResult& r = s.compute(p.K, p.M);
  for (int k = 0; k < 5; ++k) EXPECT_NEAR(r.lambda[k], ref[k + 2], 1e-10 * ref[k + 2]) << k;
  EXPECT_LT(r.deflation_error, 1e-13);
}

TEST(EigenDeflation, DependentBasisIsRefused) {
  const auto p = ffr::test::rod(50, 1.0, Ends::FreeFree);
  Eigen::MatrixXd R(51, 2);
  R.col(0).setOnes();
  R.col(1).setConstant(2.0);
  EigenOptions o;
  o.sigma = -1.0;
  o.deflation = R;
  try {
    EigenSolver(o).compute(p.K, p.M);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("linearly dependent"), std::string::npos) << e.what();
  }
  o.deflation = Eigen::MatrixXd::Ones(50, 1);  // wrong row count
  EXPECT_THROW(EigenSolver(o).compute(p.K, p.M), std::invalid_argument);
}

TEST(EigenDeflation, MakeDeflationIsMOrthonormal) {
  const auto p = ffr::test::box(6, 1.0, 5, 1.0, 4, 1.0, Ends::FreeFree);
  Eigen::MatrixXd R = Eigen::MatrixXd::Random(p.K.rows(), 6);
  const Deflation d = make_deflation(p.M, SymmetricStorage::Full, R);
  EXPECT_LT((d.R.transpose() * p.M * d.R - Eigen::MatrixXd::Identity(6, 6)).cwiseAbs().maxCoeff(),
            1e-14);
  // Projection removes the M-component along R and is idempotent.
  Eigen::VectorXd x = Eigen::VectorXd::Random(p.K.rows());
  d.project(x.data());
  EXPECT_LT((d.R.transpose() * p.M * x).cwiseAbs().maxCoeff(), 1e-13 * x.norm());
  Eigen::VectorXd y = x;
  d.project(y.data());
  EXPECT_LT((y - x).norm(), 1e-14 * x.norm());
}

TEST(EigenDeflation, FreeRodWithoutDeflationFindsTheZeroMode) {
  // Negative shift alone (no deflation): the rigid translation comes back as lambda ~ 0.
  const int n = 100;
  const auto p = ffr::test::rod(n, 1.0, Ends::FreeFree);
  const auto ref = ffr::test::rod_eigenvalues(n, 1.0, Ends::FreeFree);
  EigenOptions o;
  o.nev = 4;
  o.sigma = -0.5 * ref[1];
  EigenSolver s(o);
  const EigenResult& r = s.compute(p.K, p.M);
  EXPECT_LT(std::abs(r.lambda[0]), 1e-10 * ref[1]);
  // Its relative residual is rounding noise (both terms ~ 0); the backward error is tiny.
  EXPECT_LT(r.backward_error[0], 1e-14);
  const Eigen::VectorXd x0 = r.X.col(0);  // the rigid translation, M-normalized
  EXPECT_LT((x0 - Eigen::VectorXd::Constant(n + 1, x0[0])).norm(), 1e-10 * x0.norm());
  for (int k = 1; k < 4; ++k) EXPECT_NEAR(r.lambda[k], ref[k], 1e-10 * ref[k]);
}

TEST(EigenDeflation, TinyNegativeShiftIsAcceptedAndAccurate) {
  // sigma = -1e-6 lambda_1: K - sigma M is definite but its pivot along the rigid
  // translation is ~1e-12 of its diagonal -- a "mechanism" by the MAXRATIO test, which the
  // solver therefore skips for negative shifts. Deflation keeps the solves accurate.
  const int n = 300;
  const auto p = ffr::test::rod(n, 1.5, Ends::FreeFree, 2.1e7, 0.785);
  const auto ref = ffr::test::rod_eigenvalues(n, 1.5, Ends::FreeFree, 2.1e7, 0.785);
  EigenOptions o;
  o.nev = 8;
  o.sigma = -1e-6 * ref[1];
  o.deflation = Eigen::MatrixXd::Ones(n + 1, 1);
  EigenSolver s(o);
  const EigenResult& r = s.compute(p.K, p.M);
  for (int k = 0; k < 8; ++k) EXPECT_NEAR(r.lambda[k], ref[k + 1], 1e-10 * ref[k + 1]) << k;
  EXPECT_LT(s.info().factor.min_pivot_ratio, 1e-7);  // would have been refused at sigma >= 0
  EXPECT_LT(r.deflation_error, 1e-12);
}
