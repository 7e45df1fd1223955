// Modal checks of beam meshes against independent solutions of the continuous beam:
//  1. a slender cantilever (shear-rigid) in a skew 3D orientation with Iy != Iz against
//     Euler–Bernoulli (beta_n L = 1.8751, 4.6941, 7.8548, 10.9955, 14.1372; e.g. Blevins,
//     Formulas for Natural Frequency and Mode Shape, table 8-1), plus the first torsion and
//     axial modes ((2n-1) pi / 2L sqrt(GJ / rho Ip), sqrt(E / rho));
//  2. a stubby (L/h = 4) Timoshenko cantilever against the roots of Timoshenko's frequency
//     equation (Huang 1961; timoshenko_exact.hpp), where Euler–Bernoulli is far off;
//  3. a free–free Timoshenko beam carrying a rigid tip body with mass, an offset centre of mass
//     (along and across the beam) and rotary inertia, against the roots of the continuous
//     problem's 6 x 6 frequency determinant derived below.

#include "ffr/preproc/elements/attached_mass.hpp"
#include "ffr/preproc/elements/beam.hpp"

#include "fe_driver.hpp"
#include "timoshenko_exact.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

using namespace ffr::preproc;
using namespace ffr::test;

namespace {

constexpr double kPi = 3.14159265358979323846;
const Material kSteel{2.1e11, 0.3, 7850};

BeamSection rect(double b, double h, double k, const Eigen::Vector3d& y_axis) {
  BeamSection s;
  s.A = b * h;
  s.Iz = h * b * b * b / 12;
  s.Iy = b * h * h * h / 12;
  const double a = std::max(b, h), c = std::min(b, h);
  s.J = a * c * c * c * (1.0 / 3 - 0.21 * c / a * (1 - std::pow(c / a, 4) / 12));  // Roark
  s.ky = s.kz = k;
  s.y_axis = y_axis;
  s.material = kSteel;
  return s;
}

/// n elements from p0 to p1; returns the assembler (nodes 0..n).
Assembler beam_mesh(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, int n, const BeamSection& s) {
  Assembler as(n + 1);
  for (int e = 0; e < n; ++e) {
    Eigen::MatrixX3d xe(2, 3);
    xe.row(0) = (p0 + (p1 - p0) * double(e) / n).transpose();
    xe.row(1) = (p0 + (p1 - p0) * double(e + 1) / n).transpose();
    as.add({e, e + 1}, beam_element(xe, s));
  }
  return as;
}

/// In-plane (x–y) model along x: only u, v, rz move.
std::vector<bool> planar(int nodes, bool axial) {
  std::vector<bool> fixed(6 * nodes, true);
  for (int i = 0; i < nodes; ++i) {
    fixed[6 * i + 1] = fixed[6 * i + 5] = false;
    if (axial) fixed[6 * i] = false;
  }
  return fixed;
}

}  // namespace

TEST(BeamModal, SlenderCantileverMatchesEulerBernoulli) {
  const double L = 2.0, b = 0.04, h = 0.02;
  const Eigen::Vector3d dir = Eigen::Vector3d(1, -0.5, 0.8).normalized();
  const BeamSection s = rect(b, h, 0.0, Eigen::Vector3d(0.2, 1, 0.4));
  const int n = 20;
  Assembler as = beam_mesh(Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3d(0.1, 0.2, 0.3) + L * dir, n, s);
  std::vector<bool> fixed(as.size(), false);
  for (int k = 0; k < 6; ++k) fixed[k] = true;  // clamped at node 0
  const Eigen::VectorXd f = hertz(eigenvalues(as.K(), as.M(), fixed, 16, -1.0));

  const double bl[5] = {1.875104068711961, 4.694091132974175, 7.854757438237613, 10.99554073487547, 14.13716839104647};
  const double rhoA = kSteel.rho * s.A, E = kSteel.E, G = E / 2.6;
  std::vector<double> ref;
  for (int i = 0; i < 5; ++i) {
    ref.push_back(bl[i] * bl[i] / (L * L) * std::sqrt(E * s.Iy / rhoA) / (2 * kPi));  // x-z plane
    ref.push_back(bl[i] * bl[i] / (L * L) * std::sqrt(E * s.Iz / rhoA) / (2 * kPi));  // x-y plane
  }
  std::sort(ref.begin(), ref.end());
  ref.resize(8);  // all bending modes below the first torsion mode
  for (int i = 0; i < 8; ++i) {
    EXPECT_NEAR(f(i) / ref[i], 1.0, 0.003) << "bending mode " << i + 1;
  }
  const double torsion = kPi / (2 * L) * std::sqrt(G * s.J / (kSteel.rho * (s.Iy + s.Iz))) / (2 * kPi);
  const double axial = kPi / (2 * L) * std::sqrt(E / kSteel.rho) / (2 * kPi);
  for (double r : {torsion, axial}) {
    double best = 1e300;
    for (int i = 0; i < f.size(); ++i) best = std::min(best, std::abs(f(i) / r - 1));
    EXPECT_LT(best, 1e-3) << "no FE mode near " << r << " Hz";
  }
  std::printf("  slender cantilever, 20 elements: f1 %.4f Hz (EB %.4f), f8 %.3f (EB %.3f), torsion %.2f, axial %.2f\n",
              f(0), ref[0], f(7), ref[7], torsion, axial);
}

TEST(BeamModal, StubbyCantileverMatchesTimoshenko) {
  const double L = 1.0, h = 0.25, k = 5.0 / 6.0;
  const BeamSection s = rect(h, h, k, Eigen::Vector3d::UnitY());
  const int n = 40;
  Assembler as = beam_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d(L, 0, 0), n, s);
  std::vector<bool> fixed = planar(n + 1, false);
  fixed[1] = fixed[5] = true;  // clamped
  const Eigen::VectorXd w = eigenvalues(as.K(), as.M(), fixed, 4, -1.0).cwiseSqrt();

  const TimoshenkoBeam tb{kSteel.E * s.Iz, k * kSteel.E / 2.6 * s.A, kSteel.rho * s.A, kSteel.rho * s.Iz};
  auto det = [&](double om) {
    const Eigen::Matrix4d B0 = timoshenko_basis(tb, om, 0), BL = timoshenko_basis(tb, om, L);
    Eigen::Matrix4d D;
    D.row(0) = B0.row(0);              // v(0) = 0
    D.row(1) = B0.row(2);              // theta(0) = 0
    D.row(2) = BL.row(3);              // M(L) = 0
    D.row(3) = BL.row(1) - BL.row(2);  // V(L) = 0
    return D.determinant();
  };
  const double cutoff = std::sqrt(tb.kGA / tb.rhoI);
  const std::vector<double> r = roots(det, 1.0, 0.999 * cutoff);
  ASSERT_GE(r.size(), 4u);
  const double bl[4] = {1.875104068711961, 4.694091132974175, 7.854757438237613, 10.99554073487547};
  for (int i = 0; i < 4; ++i) {
    const double eb = bl[i] * bl[i] / (L * L) * std::sqrt(tb.EI / tb.rhoA);
    std::printf("  stubby cantilever mode %d: FE %.2f rad/s, Timoshenko %.2f (%+.3f %%), Euler-Bernoulli %.2f (%+.1f %%)\n",
                i + 1, w(i), r[i], 100 * (w(i) / r[i] - 1), eb, 100 * (eb / r[i] - 1));
    EXPECT_NEAR(w(i) / r[i], 1.0, 0.002) << "mode " << i + 1;
    EXPECT_GT(eb / r[i], 1.02);  // the check has teeth: shear and rotary inertia matter here
  }
}

// Free-free beam on x in [0, L] with a rigid body at x = L: mass m, centre at the end node + e
// (e = (ex, ey) in the plane), inertia Jc about its centre. With N = EA u', V = kGA (v' - theta),
// M = EI theta', the body's d'Alembert force -m a_c at the centre c, a_c = -omega^2 r_c,
// r_c = (u - ey theta, v + ex theta), and Jc theta'' give the end conditions
//   N = m omega^2 (u - ey theta),  V = m omega^2 (v + ex theta),
//   M = Jc omega^2 theta + ex V - ey N,
// and x = 0 is free: u' = 0, V = 0, M = 0. Axial u = A cos(kx) + B sin(kx), k = omega sqrt(rho/E).
TEST(BeamModal, FreeFreeBeamWithOffsetTipBodyMatchesContinuousSolution) {
  const double L = 1.0, b = 0.05, h = 0.02, k = 5.0 / 6.0;
  const BeamSection s = rect(b, h, k, Eigen::Vector3d::UnitY());  // bending in x-y uses Iz
  const double m = 4.0, ex = 0.06, ey = 0.04, Jc = 0.003;
  Eigen::Matrix3d Ic = Eigen::Vector3d(0.002, 0.0015, Jc).asDiagonal();
  const int n = 40;
  Assembler as = beam_mesh(Eigen::Vector3d::Zero(), Eigen::Vector3d(L, 0, 0), n, s);
  const ElementMatrices tip = attached_mass(Eigen::Vector3d(L, 0, 0), m, Eigen::Vector3d(ex, ey, 0), Ic);
  as.add({n}, tip);
  const Eigen::VectorXd lam = eigenvalues(as.K(), as.M(), planar(n + 1, true), 8, -1.0);
  for (int i = 0; i < 3; ++i) EXPECT_LT(std::abs(lam(i)), 1e-6 * lam(3)) << "rigid mode " << i;

  const TimoshenkoBeam tb{kSteel.E * s.Iz, k * kSteel.E / 2.6 * s.A, kSteel.rho * s.A, kSteel.rho * s.Iz};
  const double EA = kSteel.E * s.A;
  auto det_for = [&](double ex, double ey, double Jc, double om) {
    const double w2 = om * om, ka = om * std::sqrt(kSteel.rho / kSteel.E);
    const Eigen::Matrix4d B0 = timoshenko_basis(tb, om, 0), BL = timoshenko_basis(tb, om, L);
    const Eigen::RowVector4d v = BL.row(0), th = BL.row(2), dth = BL.row(3), V = tb.kGA * (BL.row(1) - BL.row(2));
    const Eigen::RowVector2d u(std::cos(ka * L), std::sin(ka * L));
    const Eigen::RowVector2d N = EA * Eigen::RowVector2d(-ka * std::sin(ka * L), ka * std::cos(ka * L));
    Eigen::Matrix<double, 6, 6> D = Eigen::Matrix<double, 6, 6>::Zero();
    D.block<1, 4>(0, 0) = B0.row(3);              // M(0) = 0
    D.block<1, 4>(1, 0) = B0.row(1) - B0.row(2);  // V(0) = 0
    D(2, 5) = ka;                                 // u'(0) = 0
    D.block<1, 4>(3, 0) = m * w2 * ey * th;       // N - m w2 (u - ey theta) = 0
    D.block<1, 2>(3, 4) = N - m * w2 * u;
    D.block<1, 4>(4, 0) = V - m * w2 * (v + ex * th);  // V - m w2 (v + ex theta) = 0
    D.block<1, 4>(5, 0) = tb.EI * dth - Jc * w2 * th - ex * V;  // M - Jc w2 theta - ex V + ey N = 0
    D.block<1, 2>(5, 4) = ey * N;
    return D.determinant();
  };
  auto det = [&](double om) { return det_for(ex, ey, Jc, om); };
  const std::vector<double> r = roots(det, 0.05 * std::sqrt(lam(3)), 1.2 * std::sqrt(lam(7)), 40000);
  ASSERT_GE(r.size(), 5u);
  for (int i = 0; i < 5; ++i) {
    const double w = std::sqrt(lam(3 + i));
    std::printf("  free-free + tip body mode %d: FE %.3f rad/s, continuous %.3f (%+.4f %%)\n", i + 1, w, r[i],
                100 * (w / r[i] - 1));
    EXPECT_NEAR(w / r[i], 1.0, 1e-3) << "elastic mode " << i + 1;
  }
  // The check has teeth: without the offset or the body's inertia the spectrum moves.
  const auto r0 = roots([&](double om) { return det_for(0, 0, Jc, om); }, 0.05 * r[0], 1.2 * r[4], 20000);
  const auto rJ = roots([&](double om) { return det_for(ex, ey, 0, om); }, 0.05 * r[0], 1.2 * r[4], 20000);
  EXPECT_GT(std::abs(r0[0] / r[0] - 1), 0.01);
  EXPECT_GT(std::abs(rJ[0] / r[0] - 1), 0.002);
}

// Pinned–pinned slender beam under an axial force N from the resultants of a stretch:
// rho A omega_1^2 = EI (pi/L)^4 + N (pi/L)^2 (string-beam; e.g. Blevins, table 8-1 with axial
// load), so the shift tests the geometric stiffness, and omega_1 -> 0 at Euler's load.
TEST(BeamModal, AxialForceShiftsFrequencyAndBuckles) {
  const double L = 2.0;
  const BeamSection s = rect(0.03, 0.02, 0.0, Eigen::Vector3d::UnitY());
  const double EI = kSteel.E * s.Iz, rhoA = kSteel.rho * s.A, k2 = kPi * kPi / (L * L);
  const int n = 30;
  auto omega2 = [&](double eps, double* N_out) {
    Assembler as(n + 1);
    for (int e = 0; e < n; ++e) {
      Eigen::MatrixX3d xe(2, 3);
      xe << L * e / n, 0, 0, L * (e + 1) / n, 0, 0;
      Eigen::VectorXd d = Eigen::VectorXd::Zero(12);
      d(0) = eps * xe(0, 0), d(6) = eps * xe(1, 0);  // uniform stretch
      const double N = beam_resultants(xe, s, d).axial();
      if (N_out) *N_out = N;
      const ElementMatrices em = beam_element(xe, s);
      as.add({e, e + 1}, em.K + beam_geometric_stiffness(xe, s, d), em.M);
    }
    std::vector<bool> fixed = planar(n + 1, false);
    fixed[6 * 0 + 1] = fixed[6 * n + 1] = true;  // v = 0 at both ends, rotations free
    return eigenvalues(as.K(), as.M(), fixed, 2, -1.0)(0);
  };
  double N = 0;
  const double l0 = omega2(0, nullptr), lt = omega2(1e-4, &N);
  EXPECT_NEAR(N, kSteel.E * s.A * 1e-4, 1e-9 * N);
  EXPECT_NEAR(rhoA * l0 / (EI * k2 * k2), 1.0, 2e-3);
  EXPECT_NEAR(rhoA * (lt - l0) / (N * k2), 1.0, 2e-3);
  const double eps_cr = -EI * k2 / (kSteel.E * s.A);
  EXPECT_LT(std::abs(omega2(eps_cr, nullptr)) / l0, 2e-3);
}
