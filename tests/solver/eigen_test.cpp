// EigenSolver (default Spectra backend) against closed-form eigenvalues of FE pencils (see
// pencils.hpp for the sources), the frequency-limit query, progress, sign convention and
// refusals.
#include "ffr/preproc/solver/eigen_solver.hpp"
#include "pencils.hpp"

#include <gtest/gtest.h>

using namespace ffr::preproc;
using ffr::test::Ends;

namespace {
void expect_eigenvalues(const Eigen::VectorXd& got, const std::vector<double>& ref, double rtol) {
  ASSERT_EQ(static_cast<size_t>(got.size()), ref.size());
  for (size_t i = 0; i < ref.size(); ++i)
    EXPECT_NEAR(got[i], ref[i], rtol * ref[i]) << "eigenvalue " << i;
}
}  // namespace

TEST(EigenSolver, FixedFixedRodMatchesClosedForm) {
  const int n = 400;
  const double EA = 2.1e11 * 1e-4, rhoA = 7850 * 1e-4;  // steel bar, 1 cm^2
  const auto p = ffr::test::rod(n, 2.0, Ends::FixedFixed, EA, rhoA);
  EigenOptions o;
  o.nev = 12;
  EigenSolver s(o);
  const EigenResult& r = s.compute(p.K, p.M);
  auto ref = ffr::test::rod_eigenvalues(n, 2.0, Ends::FixedFixed, EA, rhoA);
  ref.resize(12);
  expect_eigenvalues(r.lambda, ref, 1e-10);
  EXPECT_LT(r.max_relative_residual, 1e-10);
  EXPECT_LT(r.orthonormality_error, 1e-12);
  EXPECT_EQ(s.info().status, EigenStatus::Success);
  EXPECT_EQ(s.info().backend_used, EigenBackend::Block);
  EXPECT_EQ(s.info().factor.ordering, "METIS");
  // The reduced matrices handed back are X^T K X and X^T M X of the returned vectors: the
  // eigenvalues on the diagonal and the identity, as the products computed here.
  const Eigen::MatrixXd Kr = r.X.transpose() * (p.K * r.X), Mr = r.X.transpose() * (p.M * r.X);
  EXPECT_LT((r.XtKX - Kr).norm(), 1e-12 * Kr.norm());
  EXPECT_LT((r.XtMX - Mr).norm(), 1e-12);
  EXPECT_LT((Eigen::MatrixXd(r.lambda.asDiagonal()) - r.XtKX).norm(), 1e-10 * r.lambda.norm());
  // Mode k is sin(j k pi / n) up to scale (Toeplitz eigenvectors, pencils.hpp).
  for (int k = 1; k <= 3; ++k) {
    Eigen::VectorXd phi(n - 1);
    for (int j = 1; j < n; ++j) phi[j - 1] = std::sin(j * k * M_PI / n);
    const Eigen::VectorXd x = r.X.col(k - 1);
    const double c = x.dot(phi) / phi.dot(phi);
    EXPECT_LT((x - c * phi).norm(), 1e-8 * x.norm()) << "mode " << k;
  }
}

TEST(EigenSolver, FixedFreeRodAndUpperOnlyStorage) {
  const int n = 300;
  const auto p = ffr::test::rod(n, 1.0, Ends::FixedFree);
  auto ref = ffr::test::rod_eigenvalues(n, 1.0, Ends::FixedFree);
  ref.resize(8);
  EigenOptions o;
  o.nev = 8;
  EigenSolver full(o), up(o);
  expect_eigenvalues(full.compute(p.K, p.M).lambda, ref, 1e-10);
  const EigenResult& ru = up.compute(ffr::test::upper(p.K), ffr::test::upper(p.M));
  expect_eigenvalues(ru.lambda, ref, 1e-10);
  EXPECT_LT((ru.X - full.result().X).cwiseAbs().maxCoeff(), 1e-8);
}

TEST(EigenSolver, Box3DProductProblemMatchesSumsOfClosedForms) {
  // Unequal edges: simple spectrum. 11 x 9 x 7 elements, fixed faces: 10*8*6 = 480 DOF.
  const auto p = ffr::test::box(11, 1.0, 9, 0.8, 7, 0.6, Ends::FixedFixed);
  EigenOptions o;
  o.nev = 15;
  EigenSolver s(o);
  const auto ref = ffr::test::box_eigenvalues(11, 1.0, 9, 0.8, 7, 0.6, Ends::FixedFixed, 15);
  expect_eigenvalues(s.compute(p.K, p.M).lambda, ref, 1e-10);
}

TEST(EigenSolver, CubeWithMultipleEigenvalues) {
  // A cube: lambda_(1,1,2) has multiplicity 3. Rayleigh-Ritz keeps the basis M-orthonormal.
  const auto p = ffr::test::box(10, 1.0, 10, 1.0, 10, 1.0, Ends::FixedFixed);
  EigenOptions o;
  o.nev = 10;
  EigenSolver s(o);
  const EigenResult& r = s.compute(p.K, p.M);
  expect_eigenvalues(r.lambda, ffr::test::box_eigenvalues(10, 1, 10, 1, 10, 1, Ends::FixedFixed, 10),
                     1e-10);
  EXPECT_LT(r.orthonormality_error, 1e-12);
}

TEST(EigenSolver, Square2DWithPositiveShift) {
  // 2D, positive shift just below lambda_1 (K - sigma M stays positive definite).
  const auto p = ffr::test::box(30, 1.0, 20, 0.5, 0, 0, Ends::FixedFixed);
  const auto all = ffr::test::box_eigenvalues(30, 1.0, 20, 0.5, 0, 0, Ends::FixedFixed, 40);
  EigenOptions o;
  o.nev = 6;
  o.sigma = 0.9 * all[0];
  EigenSolver s(o);
  const std::vector<double> ref(all.begin(), all.begin() + 6);
  expect_eigenvalues(s.compute(p.K, p.M).lambda, ref, 1e-10);
}

TEST(EigenSolver, FrequencyLimitReturnsExactlyTheEigenvaluesBelow) {
  const int n = 500;
  const auto p = ffr::test::rod(n, 1.0, Ends::FixedFixed);
  const auto ref = ffr::test::rod_eigenvalues(n, 1.0, Ends::FixedFixed);
  // Limit halfway between the 37th and 38th eigenvalue: 37 modes, found from nev = 4 by
  // growing the request.
  EigenOptions o;
  o.nev = 4;
  o.lambda_max = 0.5 * (ref[36] + ref[37]);
  EigenSolver s(o);
  const EigenResult& r = s.compute(p.K, p.M);
  ASSERT_EQ(r.lambda.size(), 37);
  expect_eigenvalues(r.lambda, std::vector<double>(ref.begin(), ref.begin() + 37), 1e-10);
  EXPECT_GT(s.info().rounds, 1);
  // The limit below the first eigenvalue: nothing.
  o.lambda_max = 0.5 * ref[0];
  EigenSolver none(o);
  EXPECT_EQ(none.compute(p.K, p.M).lambda.size(), 0);
  // Too many below the limit: refused, not truncated.
  o.lambda_max = ref[100];
  o.max_modes = 50;
  EigenSolver capped(o);
  EXPECT_THROW(capped.compute(p.K, p.M), EigenSolverError);
}

TEST(EigenSolver, ProgressCallbackSeesStagesAndCounts) {
  const auto p = ffr::test::rod(200, 1.0, Ends::FixedFixed);
  EigenOptions o;
  o.nev = 5;
  EigenSolver s(o);
  std::vector<std::string> stages;
  std::int64_t last_ops = 0;
  int converged = -1;
  s.set_progress([&](const EigenProgress& pr) {
    if (stages.empty() || stages.back() != pr.stage) stages.push_back(pr.stage);
    EXPECT_GE(pr.operator_applications, last_ops);
    last_ops = pr.operator_applications;
    if (pr.converged >= 0) converged = pr.converged;
  });
  s.compute(p.K, p.M);
  EXPECT_EQ(stages, (std::vector<std::string>{"factorize", "lanczos", "verify", "done"}));
  EXPECT_EQ(converged, 5);
  EXPECT_EQ(last_ops, s.info().operator_applications);
  EXPECT_GT(last_ops, 5);
}

TEST(EigenSolver, SignConventionIsDeterministic) {
  const auto p = ffr::test::box(9, 1.0, 7, 0.9, 5, 0.8, Ends::FixedFixed);
  EigenOptions o;
  o.nev = 8;
  EigenSolver a(o), b(o);
  const Eigen::MatrixXd& Xa = a.compute(p.K, p.M).X;
  EXPECT_EQ(Xa, b.compute(p.K, p.M).X);  // bitwise identical runs
  for (Eigen::Index j = 0; j < Xa.cols(); ++j) {
    const double amax = Xa.col(j).cwiseAbs().maxCoeff();
    Eigen::Index i = 0;
    while (std::abs(Xa(i, j)) < kSignThreshold * amax) ++i;
    EXPECT_GT(Xa(i, j), 0.0) << "mode " << j;
  }
}

TEST(EigenSolver, ShiftAboveAnEigenvalueIsRefusedWithTheColumn) {
  const auto p = ffr::test::rod(100, 1.0, Ends::FixedFixed);
  const auto ref = ffr::test::rod_eigenvalues(100, 1.0, Ends::FixedFixed);
  EigenOptions o;
  o.sigma = 0.5 * (ref[0] + ref[1]);
  EigenSolver s(o);
  try {
    s.compute(p.K, p.M);
    FAIL();
  } catch (const NotPositiveDefiniteError& e) {
    EXPECT_NE(std::string(e.what()).find("sigma"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("column " + std::to_string(e.column)), std::string::npos);
  }
  EXPECT_EQ(s.info().status, EigenStatus::FactorizationFailed);
}

TEST(EigenSolver, BadRequestsAreRefused) {
  const auto p = ffr::test::rod(20, 1.0, Ends::FixedFixed);
  EigenOptions o;
  o.nev = 0;
  EXPECT_THROW(EigenSolver(o).compute(p.K, p.M), std::invalid_argument);
  o.nev = 25;  // only 19 DOF
  EXPECT_THROW(EigenSolver(o).compute(p.K, p.M), std::invalid_argument);
  o.nev = 3;
  const auto q = ffr::test::rod(21, 1.0, Ends::FixedFixed);
  EXPECT_THROW(EigenSolver(o).compute(p.K, q.M), std::invalid_argument);
  o.lambda_max = -1.0;  // below sigma = 0
  EXPECT_THROW(EigenSolver(o).compute(p.K, p.M), std::invalid_argument);
}

TEST(EigenSolver, SmallProblemsFallBackToDense) {
  // 19 DOF, all 19 modes wanted: Lanczos cannot (nev < ncv <= n), the dense path can.
  const auto p = ffr::test::rod(20, 1.0, Ends::FixedFixed);
  EigenOptions o;
  o.nev = 19;
  EigenSolver s(o);
  expect_eigenvalues(s.compute(p.K, p.M).lambda, ffr::test::rod_eigenvalues(20, 1.0, Ends::FixedFixed),
                     1e-12);
  EXPECT_EQ(s.info().backend_used, EigenBackend::Dense);
}

TEST(EigenSolver, ReusesACallerFactorOfTheShiftedMatrix) {
  // Craig-Bampton style: the caller factorized K once (static solves) and reuses it.
  const auto p = ffr::test::rod(300, 1.0, Ends::FixedFixed);
  CholmodFactor f;
  f.factorize_shifted(p.K, p.M, 0.0);
  EigenOptions o;
  o.nev = 6;
  EigenSolver s(o);
  auto ref = ffr::test::rod_eigenvalues(300, 1.0, Ends::FixedFixed);
  ref.resize(6);
  expect_eigenvalues(s.compute(p.K, p.M, f).lambda, ref, 1e-10);
  EXPECT_EQ(s.info().factor.factorize_seconds, f.info().stats.factorize_seconds);
  // A factor of another shift is refused.
  o.sigma = -1.0;
  EigenSolver t(o);
  EXPECT_THROW(t.compute(p.K, p.M, f), std::invalid_argument);
  EXPECT_EQ(t.info().status, EigenStatus::BadInput);
}

TEST(EigenSolver, FailedChecksAndNonConvergenceAreReported) {
  const auto p = ffr::test::box(11, 1.0, 9, 0.8, 7, 0.6, Ends::FixedFixed);
  EigenOptions o;
  o.nev = 6;
  o.lanczos_tol = 0.1;  // Ritz pairs accepted far too early: residuals ~1e-6
  EigenSolver s(o);
  try {
    s.compute(p.K, p.M);
    FAIL() << "max relative residual " << s.result().max_relative_residual;
  } catch (const EigenSolverError& e) {
    EXPECT_NE(std::string(e.what()).find("relative residual"), std::string::npos) << e.what();
  }
  EXPECT_EQ(s.info().status, EigenStatus::CheckFailed);
  EXPECT_EQ(s.result().lambda.size(), 6);  // still readable for diagnosis
  // Minimal Krylov space and a single restart: neither backend can converge 20 pairs.
  for (EigenBackend b : {EigenBackend::Spectra, EigenBackend::Arpack}) {
    EigenOptions q;
    q.nev = 20;
    q.ncv = 21;
    q.max_restarts = 1;
    q.backend = b;
    EigenSolver t(q);
    EXPECT_THROW(t.compute(p.K, p.M), EigenSolverError) << to_string(b);
    EXPECT_EQ(t.info().status, EigenStatus::NotConverged) << to_string(b);
  }
}

TEST(EigenSolver, IllConditionedPartPassesAtTheRoundingLevel) {
  // Steel rod, 50000 elements, clamped-free: lambda_max / lambda_1 ~ 3e9, so computing K x
  // for the first mode already carries a relative error ~ eps * 3e9 ~ 1e-7. The relative
  // residual cannot go below that; the backward error shows the pair is exact to rounding,
  // and the eigenvalues agree with the closed form to ~1e-11.
  const int n = 50000;
  const auto p = ffr::test::rod(n, 1.0, Ends::FixedFree, 2.1e7, 0.785);
  EigenOptions o;
  o.nev = 5;
  EigenSolver s(o);
  const EigenResult& r = s.compute(p.K, p.M);
  auto ref = ffr::test::rod_eigenvalues(n, 1.0, Ends::FixedFree, 2.1e7, 0.785);
  ref.resize(5);
  expect_eigenvalues(r.lambda, ref, 1e-10);
  EXPECT_GT(r.relative_residual[0], o.residual_tol);  // the rounding floor of the product
  EXPECT_LT(r.backward_error.maxCoeff(), kRoundoffBackwardError);
}
