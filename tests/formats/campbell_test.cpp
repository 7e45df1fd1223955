// Campbell frequencies from the SID alone, against references computed elsewhere:
//  1. A point mass on an isotropic planar spring (natural frequency w0) spinning at Omega
//     about the plane's normal: in the rotating frame the equations are
//       x'' - 2 Omega y' + (w0^2 - Omega^2) x = 0,   y'' + 2 Omega x' + (w0^2 - Omega^2) y = 0
//     (Coriolis and centrifugal softening), with frequencies |w0 - Omega| and w0 + Omega
//     (the rotating-frame whirl frequencies of the isotropic Jeffcott rotor; G. Genta,
//     "Dynamics of Rotating Systems", Springer 2005, ch. 4). The out-of-plane mode keeps w0.
//  2. Anisotropic spring (wx < wy): substituting exp(i mu t) in the same equations gives
//       mu^4 - mu^2 (wx^2 + wy^2 + 2 Omega^2) + (wx^2 - Omega^2)(wy^2 - Omega^2) = 0,
//     divergent (a real pair) for wx < Omega < wy.
//  3. Rotating uniform cantilever, zero hub radius, spun about an axis normal to it: the
//     flapwise fundamental frequency, nondimensional w sqrt(rho A L^4 / EI) = 3.6816, 4.1373,
//     4.7973, 5.5850, 6.4495 at Omega sqrt(rho A L^4 / EI) = 1..5 (D. H. Hodges and M. J.
//     Rutkowski, AIAA J. 19(11), 1981, table 1; also A. D. Wright et al., J. Appl. Mech. 49,
//     1982). This needs the geometric stiffening K0om; in-plane the frequency is
//     sqrt(w_flap^2 - Omega^2) (centrifugal softening, same references).
//  4. The unreduced chain's own rotating-frame eigenproblem, assembled independently from
//     the point masses (ChainModel), with all modes kept: identical frequencies.
#include "ffr/formats/campbell.hpp"
#include "ffr/formats/synthetic.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

using namespace ffr::formats;
using namespace ffr::formats::synthetic;

namespace {

constexpr double kTwoPi = 2 * M_PI;

// One point mass m at c with three spring modes along x, y, z.
Sid spring_mass(double wx, double wy, double wz) {
  PointMass p;
  p.m = 2.5;
  p.c = Eigen::Vector3d(0.4, -0.2, 0.3);
  return from_shapes({p}, Eigen::MatrixXd::Identity(3, 3), Eigen::MatrixXd(), Eigen::Vector3d(wx, wy, wz), {{"P", 0}},
                     "clamped:P");
}

std::vector<double> sorted(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v;
}

}  // namespace

TEST(Campbell, SpinningPointMassOnIsotropicSpring) {
  const double w0 = 10.0, wz = 13.0;
  const Sid s = spring_mass(w0, w0, wz);
  for (double W : {0.0, 2.0, 5.0, 10.0, 17.0, 30.0}) {
    const auto f = campbell(s, 2, {W}).frequency_hz[0];
    const auto expect = sorted({std::abs(w0 - W) / kTwoPi, (w0 + W) / kTwoPi, wz / kTwoPi});
    ASSERT_EQ(f.size(), 3u);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(f[k], expect[k], 1e-9 * (w0 + W)) << "Omega " << W << " mode " << k;
  }
  // Spin about x: the mode along the axis keeps w0; the (y, z) pair is the anisotropic case
  // (w0, wz) of the next test.
  const double W = 4.0, b = w0 * w0 + wz * wz + 2 * W * W, c = (w0 * w0 - W * W) * (wz * wz - W * W);
  const double d = std::sqrt(b * b - 4 * c);
  const auto expect = sorted({w0 / kTwoPi, std::sqrt((b - d) / 2) / kTwoPi, std::sqrt((b + d) / 2) / kTwoPi});
  const auto fx = campbell(s, 0, {W}).frequency_hz[0];
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(fx[k], expect[k], 1e-9 * wz) << "spin about x, mode " << k;
}

TEST(Campbell, SpinningPointMassOnAnisotropicSpring) {
  const double wx = 8.0, wy = 12.0, wz = 30.0;
  const Sid s = spring_mass(wx, wy, wz);
  for (double W : {0.0, 3.0, 7.5, 12.5, 20.0}) {
    const double b = wx * wx + wy * wy + 2 * W * W, c = (wx * wx - W * W) * (wy * wy - W * W);
    const double d = std::sqrt(b * b - 4 * c);
    const auto expect = sorted({std::sqrt((b - d) / 2) / kTwoPi, std::sqrt((b + d) / 2) / kTwoPi, wz / kTwoPi});
    const auto f = campbell(s, 2, {W}).frequency_hz[0];
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(f[k], expect[k], 1e-9 * (wy + W)) << "Omega " << W << " mode " << k;
  }
  // Inside (wx, wy) one pair diverges: frequency 0 and a positive growth rate.
  Eigen::VectorXd growth;
  const Eigen::VectorXd f = spinning_frequencies_hz(spinning_system(s, 2, 10.0), &growth);
  EXPECT_NEAR(f[0], 0.0, 1e-12);
  const double b = wx * wx + wy * wy + 200, c = (wx * wx - 100) * (wy * wy - 100);
  EXPECT_NEAR(growth[0], std::sqrt(-(b - std::sqrt(b * b - 4 * c)) / 2), 1e-9);
}

TEST(Campbell, GyroscopicMatrixIsAntisymmetricAndStiffnessSymmetric) {
  ChainParams p;
  p.clamped = true;
  p.stiffening = true;
  p.start = Eigen::Vector3d(0.2, 0.1, 0);
  p.modes = 6;
  const Sid s = spring_chain(p).sid;
  for (int axis = 0; axis < 3; ++axis) {
    const SpinningSystem sys = spinning_system(s, axis, 7.0);
    EXPECT_LT((sys.C + sys.C.transpose()).norm(), 1e-12 * (1 + sys.C.norm()));
    EXPECT_LT((sys.K - sys.K.transpose()).norm(), 1e-10 * sys.K.norm());
  }
}

TEST(Campbell, RotatingCantileverFollowsSouthwellWithStiffening) {
  ChainParams p;
  p.points = 41;
  p.clamped = true;
  p.length = 1.0;
  p.mass = 1.0;
  p.EIy = p.EIz = 1.0;  // so Omega and w are already nondimensional
  p.EA = 1e9;           // inextensible, as the references assume
  p.modes = 4;
  p.stiffening = true;
  const Sid s = spring_chain(p).sid;
  const double flap[] = {3.6816, 4.1373, 4.7973, 5.5850, 6.4495};  // Hodges & Rutkowski 1981
  for (int i = 0; i < 5; ++i) {
    const double W = i + 1;
    const SpinningSystem sys = spinning_system(s, 2, W);  // spin about z; the beam lies along x
    const Eigen::VectorXd f = spinning_frequencies_hz(sys) * kTwoPi;
    // Lowest two: in-plane (y) sqrt(flap^2 - W^2) and flapwise (z).
    EXPECT_NEAR(f[1], flap[i], 2e-3 * flap[i]) << "Omega " << W;
    EXPECT_NEAR(f[0], std::sqrt(flap[i] * flap[i] - W * W), 3e-3 * flap[i]) << "Omega " << W;
  }
  // Without the stiffening terms the flapwise frequency does not rise at all (Oe.M1 has no
  // out-of-plane part) and the in-plane one softens: the divergence of Kane et al. 1987.
  CampbellOptions off;
  off.stiffening = false;
  const Eigen::VectorXd f0 = spinning_frequencies_hz(spinning_system(s, 2, 0.0)) * kTwoPi;
  const Eigen::VectorXd f3 = spinning_frequencies_hz(spinning_system(s, 2, 3.0, off)) * kTwoPi;
  EXPECT_NEAR(f3[1], f0[1], 1e-9 * f0[1]);
  EXPECT_NEAR(f3[0], std::sqrt(f0[0] * f0[0] - 9), 1e-3 * f0[0]);
}

// With every elastic mode kept, the reduced system is an exact change of basis of the full
// chain, whose rotating-frame equations we assemble from the points directly:
//   M u'' + G u' + (K + K_cf + Omega^2 K_G) u = 0,  G = blockdiag(2 m_p W~),
//   K_cf = blockdiag(m_p W~ W~)  (W~ the skew matrix of Omega e_axis).
TEST(Campbell, EqualsTheUnreducedChainInTheRotatingFrame) {
  ChainParams p;
  p.points = 9;
  p.clamped = true;
  p.EIy = 1.0;
  p.EIz = 2.5;
  p.EA = 400;
  p.start = Eigen::Vector3d(0.3, 0.0, 0.1);
  p.stiffening = true;
  p.modes = 24;  // all: 8 free points x 3
  const Chain c = spring_chain(p);
  const auto& m = c.model;
  const auto& fr = m.free_dofs;
  const auto n = static_cast<Eigen::Index>(fr.size());
  for (int axis = 0; axis < 3; ++axis) {
    const double W = 3.0;
    Eigen::Vector3d w = Eigen::Vector3d::Zero();
    w[axis] = W;
    Eigen::Matrix3d Wx;
    Wx << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
    const Eigen::MatrixXd KG = m.geometric_stiffness(m.axial_forces(m.static_deflection(m.centrifugal_load(axis)))) * W * W;
    Eigen::MatrixXd M(n, n), G(n, n), K(n, n);
    for (Eigen::Index i = 0; i < n; ++i)
      for (Eigen::Index j = 0; j < n; ++j) {
        const Index a = fr[i], b = fr[j];
        const bool same_point = a / 3 == b / 3;
        const double mp = m.points[static_cast<std::size_t>(a / 3)].m;
        M(i, j) = m.M(a, b);
        G(i, j) = same_point ? 2 * mp * Wx(a % 3, b % 3) : 0.0;
        K(i, j) = m.K(a, b) + KG(a, b) + (same_point ? mp * (Wx * Wx)(a % 3, b % 3) : 0.0);
      }
    Eigen::VectorXd full = spinning_frequencies_hz({M, G, K});
    const auto red = campbell(c.sid, axis, {W}).frequency_hz[0];
    ASSERT_EQ(static_cast<Eigen::Index>(red.size()), n);
    for (Eigen::Index k = 0; k < n; ++k) EXPECT_NEAR(red[k], full[k], 1e-8 * full[n - 1]) << "axis " << axis << " mode " << k;
  }
}

TEST(Campbell, BadArgumentsAreRefused) {
  const Sid s = spring_mass(1, 2, 3);
  EXPECT_THROW(spin_axis_from_string("w"), std::invalid_argument);
  EXPECT_EQ(spin_axis_from_string("y"), 1);
  EXPECT_THROW(campbell(s, 3, {1.0}), std::invalid_argument);
  EXPECT_THROW(campbell(s, 0, {NAN}), std::invalid_argument);
  // omega^2 overflows: the speed is named, not Eigen's eigen-solver failing on infinities.
  for (int axis = 0; axis < 3; ++axis) {
    try {
      campbell(s, axis, {1.0, 1e300});
      ADD_FAILURE() << "axis " << axis << ": 1e300 rad/s accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_STREQ(e.what(), "spin speed 1e+300 rad/s is too large: the spinning system's matrices overflow");
    }
  }
}
