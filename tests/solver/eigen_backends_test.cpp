// The three backends are independent implementations (Spectra's Lanczos, ARPACK's Lanczos,
// Eigen's dense QR-based solver): same eigenvalues and, after the sign convention, the same
// vectors on a problem with a simple spectrum.
#include "ffr/preproc/solver/eigen_solver.hpp"
#include "pencils.hpp"

#include <gtest/gtest.h>

using namespace ffr::preproc;
using ffr::test::Ends;

namespace {
EigenResult solve_with(EigenBackend b, const ffr::test::Pencil& p, EigenOptions o) {
  o.backend = b;
  EigenSolver s(o);
  EigenResult r = s.compute(p.K, p.M);
  EXPECT_EQ(s.info().backend_used, b);
  return r;
}
}  // namespace

TEST(EigenBackends, SpectraArpackAndDenseAgree) {
  // 13 x 11 x 9 elements, fixed faces: 12*10*8 = 960 DOF, unequal edges (simple spectrum).
  const auto p = ffr::test::box(13, 1.0, 11, 0.85, 9, 0.65, Ends::FixedFixed);
  EigenOptions o;
  o.nev = 20;
  o.sigma = -5.0;
  const EigenResult rs = solve_with(EigenBackend::Spectra, p, o);
  const EigenResult ra = solve_with(EigenBackend::Arpack, p, o);
  const EigenResult rd = solve_with(EigenBackend::Dense, p, o);
  const auto ref = ffr::test::box_eigenvalues(13, 1.0, 11, 0.85, 9, 0.65, Ends::FixedFixed, 20);
  for (int k = 0; k < 20; ++k) {
    EXPECT_NEAR(rs.lambda[k], ref[k], 1e-10 * ref[k]) << k;
    EXPECT_NEAR(ra.lambda[k], rs.lambda[k], 1e-11 * ref[k]) << k;
    EXPECT_NEAR(rd.lambda[k], rs.lambda[k], 1e-11 * ref[k]) << k;
  }
  // Same vectors (M-normalized, same sign convention): compare in the M-norm.
  for (int k = 0; k < 20; ++k) {
    const Eigen::VectorXd da = ra.X.col(k) - rs.X.col(k), dd = rd.X.col(k) - rs.X.col(k);
    EXPECT_LT(std::sqrt(da.dot(p.M * da)), 1e-8) << "ARPACK mode " << k;
    EXPECT_LT(std::sqrt(dd.dot(p.M * dd)), 1e-8) << "dense mode " << k;
  }
  EXPECT_LT(ra.max_relative_residual, 1e-10);
  EXPECT_LT(rd.max_relative_residual, 1e-10);
}

TEST(EigenBackends, ArpackFrequencyLimitAndDeflation) {
  const int n = 400;
  const auto p = ffr::test::rod(n, 1.0, Ends::FreeFree);
  const auto ref = ffr::test::rod_eigenvalues(n, 1.0, Ends::FreeFree);
  EigenOptions o;
  o.backend = EigenBackend::Arpack;
  o.nev = 3;
  o.sigma = -1.0;
  o.deflation = Eigen::MatrixXd::Ones(n + 1, 1);
  o.lambda_max = 0.5 * (ref[25] + ref[26]);  // elastic modes 1..25
  EigenSolver s(o);
  const EigenResult& r = s.compute(p.K, p.M);
  ASSERT_EQ(r.lambda.size(), 25);
  for (int k = 0; k < 25; ++k) EXPECT_NEAR(r.lambda[k], ref[k + 1], 1e-10 * ref[k + 1]) << k;
  EXPECT_LT(r.deflation_error, 1e-13);
}
