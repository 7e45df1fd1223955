// members_from_integrals() against the synthetic generator, which computes every SID member
// directly by sums over point masses (formats/synthetic: an independent oracle).
#include "ffr/formats/synthetic.hpp"
#include "ffr/preproc/reduce/invariants.hpp"

#include <gtest/gtest.h>

using namespace ffr;

namespace {
template <class A>
double diff(const A& a, const A& b) { return (a - b).cwiseAbs().maxCoeff(); }
template <class A>
double diff(const std::vector<A>& a, const std::vector<A>& b) {
  double d = 0;
  for (std::size_t k = 0; k < a.size(); ++k) d = std::max(d, diff(a[k], b[k]));
  return d;
}
}  // namespace

TEST(Members, FromIntegralsEqualDirectPointMassSums) {
  // Point masses at irregular positions with random mode shapes (no symmetry to hide a sign).
  std::vector<formats::synthetic::PointMass> pm;
  Eigen::MatrixXd Phi(3 * 5, 4);
  std::srand(3);
  for (int i = 0; i < 5; ++i) pm.push_back({0.5 + i, Eigen::Vector3d::Random(), Eigen::Matrix3d::Zero()});
  Phi.setRandom();
  const Eigen::VectorXd omega = Eigen::VectorXd::LinSpaced(4, 10, 40);
  const formats::Sid ref = formats::synthetic::from_shapes(pm, Phi, Eigen::MatrixXd(), omega, {}, "free", 0.0);

  formats::Sid s = ref;  // keep integrals, recompute every member from them
  s.resize(ref.nq());
  s.refmod = ref.refmod;
  s.integrals = ref.integrals;
  s.rotary = ref.rotary;
  preproc::members_from_integrals(s);
  const double tol = 1e-12 * (1 + ref.J.M0.norm());
  EXPECT_LT(diff(s.mdCM.M0, ref.mdCM.M0), tol);
  EXPECT_LT(diff(s.mdCM.M1, ref.mdCM.M1), tol);
  EXPECT_LT(diff(s.J.M0, ref.J.M0), tol);
  EXPECT_LT(diff(s.J.M1, ref.J.M1), tol);
  EXPECT_LT(diff(s.Ct.M0, ref.Ct.M0), tol);
  EXPECT_LT(diff(s.Cr.M0, ref.Cr.M0), tol);
  EXPECT_LT(diff(s.Cr.M1, ref.Cr.M1), tol);
  EXPECT_LT(diff(s.Me, ref.Me), tol);
  EXPECT_LT(diff(s.Gr, ref.Gr), tol);
  EXPECT_LT(diff(s.Ge, ref.Ge), tol);
  EXPECT_LT(diff(s.Oe.M0, ref.Oe.M0), tol);
  EXPECT_LT(diff(s.Oe.M1, ref.Oe.M1), tol);
}
