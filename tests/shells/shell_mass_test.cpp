// Mass properties of a plate meshed with shells against the analytic properties of the
// rectangular box a x b x t (thickness terms included), for QUAD4 and TRI3, in a tilted plane:
//   m = rho a b t,  int c dm,  int c c^T dm  from the mass samples, and the rigid-body
// projection of M (mass, first moment, inertia tensor about the origin) from the matrices.

#include "ffr/preproc/elements/shell.hpp"

#include "fe_driver.hpp"
#include "test_util.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

using namespace ffr::preproc;
using namespace ffr::test;

namespace {

struct BoxMoments {
  double m;
  Eigen::Vector3d first;
  Eigen::Matrix3d second;  // int c c^T dm
};

/// Box [0,a] x [0,b] x [-t/2,t/2] in its own axes, then c = R p + o.
BoxMoments box(double a, double b, double t, double rho, const Eigen::Matrix3d& R, const Eigen::Vector3d& o) {
  const double m = rho * a * b * t;
  const Eigen::Vector3d s(m * a / 2, m * b / 2, 0);
  Eigen::Matrix3d S;
  S << m * a * a / 3, m * a * b / 4, 0, m * a * b / 4, m * b * b / 3, 0, 0, 0, m * t * t / 12;
  BoxMoments r;
  r.m = m;
  r.first = R * s + m * o;
  r.second = R * S * R.transpose() + R * s * o.transpose() + o * s.transpose() * R.transpose() + m * o * o.transpose();
  return r;
}

Eigen::Matrix3d inertia_about_origin(const Eigen::Matrix3d& second) {
  return second.trace() * Eigen::Matrix3d::Identity() - second;
}

}  // namespace

class PlateMass : public ::testing::TestWithParam<ElementType> {};

TEST_P(PlateMass, MatchesBoxMomentsIncludingThickness) {
  const double a = 2.0, b = 1.2, t = 0.15, rho = 2700;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.9, Eigen::Vector3d(0.2, -1, 0.7).normalized()).toRotationMatrix();
  const Eigen::Vector3d o(0.4, 1.5, -0.8);
  // A non-uniform grid, so that the elements are general rectangles/triangles.
  Grid g = make_grid(3, 4, [&](double u, double v) {
    return Eigen::Vector3d(R * Eigen::Vector3d(a * (u + 0.1 * u * (1 - u)), b * v * v * 0.5 + 0.5 * b * v, 0) + o);
  });
  const ShellSection s{t, {7e10, 0.33, rho}};
  Assembler as(static_cast<int>(g.x.rows()));
  double m = 0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  Eigen::MatrixXd Mrot_rigid = Eigen::MatrixXd::Zero(6, 6);
  for (const auto& e : GetParam() == ElementType::Quad4 ? g.quads() : g.triangles()) {
    const ElementMatrices em = shell_element(GetParam(), g.coords(e), s);
    as.add(e, em.K, em.M - em.M_rotary);
    for (const auto& smp : em.samples) {
      m += smp.w;
      first += smp.w * smp.c;
      second += smp.w * smp.c * smp.c.transpose();
    }
  }
  const BoxMoments ref = box(a, b, t, rho, R, o);
  EXPECT_NEAR(m, ref.m, 1e-12 * ref.m);
  EXPECT_LT((first - ref.first).norm(), 1e-12 * ref.first.norm());
  EXPECT_LT((second - ref.second).norm(), 1e-12 * ref.second.norm());

  // The consistent mass (without the fictitious drilling part) seen by the rigid-body motions:
  // [[m 1, -m c_G~], [m c_G~, J_O]] with J_O the box's inertia tensor about the origin.
  const Eigen::MatrixXd Rb = rigid_modes(g.x);
  const Eigen::MatrixXd MR = Rb.transpose() * (as.M() * Rb);
  Eigen::MatrixXd ref6 = Eigen::MatrixXd::Zero(6, 6);
  ref6.topLeftCorner<3, 3>() = ref.m * Eigen::Matrix3d::Identity();
  Eigen::Matrix3d cG;
  const Eigen::Vector3d f = ref.first;
  cG << 0, -f.z(), f.y(), f.z(), 0, -f.x(), -f.y(), f.x(), 0;
  ref6.topRightCorner<3, 3>() = -cG;
  ref6.bottomLeftCorner<3, 3>() = cG;
  ref6.bottomRightCorner<3, 3>() = inertia_about_origin(ref.second);
  EXPECT_LT((MR - ref6).norm(), 1e-11 * ref6.norm()) << MR << "\n\n" << ref6;
}

INSTANTIATE_TEST_SUITE_P(Shells, PlateMass, ::testing::Values(ElementType::Quad4, ElementType::Tri3),
                         [](const auto& info) { return std::string(name(info.param)); });
