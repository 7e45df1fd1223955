// Single-element checks of the 3D Timoshenko beam:
//  - the closed-form stiffness equals the strain energy of the interpolation used for the mass,
//    and that interpolation solves the homogeneous Timoshenko equations;
//  - exact end-load response (Timoshenko cantilever: PL^3/3EI + PL/kGA, PL/EA, TL/GJ);
//  - Przemieniecki's consistent mass with rotary inertia (Theory of Matrix Structural Analysis,
//    1968, ch. 11) when shear-rigid; mass samples reproduce M, m, first and second moments;
//  - six rigid-body modes, rank 6; geometric stiffness against P/(30L)[36 3L ...];
//  - resultants and their sign convention; input errors.

#include "ffr/preproc/elements/beam.hpp"

#include "beam_shape.hpp"
#include "test_util.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>

using namespace ffr::preproc;
using ffr::test::rigid_modes;

namespace {

// A rectangular 0.04 x 0.02 steel section with Iy != Iz, along a skew direction.
BeamSection section(double ky, double kz) {
  BeamSection s;
  const double b = 0.04, h = 0.02;  // b along local y, h along local z
  s.A = b * h;
  s.Iz = h * b * b * b / 12;  // int y^2 dA
  s.Iy = b * h * h * h / 12;  // int z^2 dA
  s.J = 0.229 * b * h * h * h;
  s.ky = ky;
  s.kz = kz;
  s.y_axis = Eigen::Vector3d(0.3, 1.0, -0.2);
  s.material = {2.1e11, 0.3, 7850};
  return s;
}

Eigen::MatrixX3d skew_element(double L) {
  Eigen::MatrixX3d x(2, 3);
  const Eigen::Vector3d a(0.5, -0.2, 1.0), d = Eigen::Vector3d(1, 0.4, 0.3).normalized();
  x.row(0) = a.transpose();
  x.row(1) = (a + L * d).transpose();
  return x;
}

Eigen::Matrix<double, 12, 12> to_local(const Eigen::MatrixX3d& x, const BeamSection& s) {
  const Eigen::Matrix3d R = beam_frame(x, s.y_axis);
  Eigen::Matrix<double, 12, 12> T = Eigen::Matrix<double, 12, 12>::Zero();
  for (int b = 0; b < 4; ++b) T.block<3, 3>(3 * b, 3 * b) = R;
  return T;
}

}  // namespace

TEST(BeamElement, StiffnessIsTheEnergyOfTheInterpolation) {
  for (double k : {0.0, 5.0 / 6.0}) {
    const BeamSection s = section(k, 0.9 * k);
    const double L = 0.3;  // stubby: Phi is large
    const Eigen::MatrixX3d x = skew_element(L);
    const auto T = to_local(x, s);
    const Eigen::MatrixXd Kl = T * beam_element(x, s).K * T.transpose();
    const double E = s.material.E, G = E / 2.6;
    beam::ShapeParams p{L, k > 0 ? 12 * E * s.Iz / (G * s.ky * s.A * L * L) : 0,
                        k > 0 ? 12 * E * s.Iy / (G * s.kz * s.A * L * L) : 0};
    // Independent energy: EA u'^2 + GJ rx'^2 + EIy ry'^2 + EIz rz'^2 + shear terms, 6-point Gauss.
    const double gx[6] = {0.033765242898424, 0.169395306766868, 0.380690406958402,
                          0.619309593041598, 0.830604693233132, 0.966234757101576};
    const double gw[6] = {0.085662246189585, 0.180380786524069, 0.233956967286346,
                          0.233956967286346, 0.180380786524069, 0.085662246189585};
    Eigen::MatrixXd Ke = Eigen::MatrixXd::Zero(12, 12);
    for (int g = 0; g < 6; ++g) {
      const auto H = beam::interpolation(p, gx[g]);
      const auto D = beam::interpolation_ds(p, gx[g]);
      auto add = [&](const Eigen::Matrix<double, 1, 12>& r, double c) { Ke += c * gw[g] * L * r.transpose() * r; };
      add(D.row(0), E * s.A);
      add(D.row(3), G * s.J);
      add(D.row(4), E * s.Iy);
      add(D.row(5), E * s.Iz);
      if (k > 0) {
        add(D.row(1) - H.row(5), G * s.ky * s.A);  // gamma_xy = v' - rz
        add(D.row(2) + H.row(4), G * s.kz * s.A);  // gamma_xz = w' + ry
      } else {  // shear-rigid: the interpolation is Kirchhoff
        EXPECT_LT((D.row(1) - H.row(5)).norm(), 1e-12 * D.row(1).norm());
        EXPECT_LT((D.row(2) + H.row(4)).norm(), 1e-12 * D.row(2).norm());
      }
      // Homogeneous Timoshenko equations: v' - rz + (Phi L^2 / 12) rz'' = 0 in each plane.
      const double h = 1e-4;
      const auto Dp = beam::interpolation_ds(p, gx[g] + h), Dm = beam::interpolation_ds(p, gx[g] - h);
      const Eigen::Matrix<double, 1, 12> rz2 = (Dp.row(5) - Dm.row(5)) / (2 * h * L);
      const Eigen::Matrix<double, 1, 12> ry2 = (Dp.row(4) - Dm.row(4)) / (2 * h * L);
      EXPECT_LT((D.row(1) - H.row(5) + p.phi_y * L * L / 12 * rz2).norm(), 1e-6 * D.row(1).norm());
      EXPECT_LT((D.row(2) + H.row(4) - p.phi_z * L * L / 12 * ry2).norm(), 1e-6 * D.row(2).norm());
    }
    EXPECT_LT((Kl - Ke).norm(), 1e-10 * Kl.norm()) << "k = " << k;
  }
}

TEST(BeamElement, ExactForEndLoads) {
  const BeamSection s = section(5.0 / 6.0, 0.7);
  const double L = 0.5, E = s.material.E, G = E / 2.6;
  const Eigen::MatrixX3d x = skew_element(L);
  const Eigen::Matrix3d R = beam_frame(x, s.y_axis);
  const Eigen::MatrixXd K = beam_element(x, s).K;
  // Clamp node 1, load node 2 with (N, Py, Pz, T) in local axes; solve the 6 x 6 tip block.
  const Eigen::MatrixXd Ktip = K.bottomRightCorner(6, 6);
  const Eigen::Vector4d load(1e3, 200, -150, 30);
  Eigen::VectorXd f(6);
  f << R.transpose() * Eigen::Vector3d(load(0), load(1), load(2)), R.transpose() * Eigen::Vector3d(load(3), 0, 0);
  const Eigen::VectorXd d = Ktip.ldlt().solve(f);
  const Eigen::Vector3d u = R * d.head<3>(), th = R * d.tail<3>();
  EXPECT_NEAR(u(0), load(0) * L / (E * s.A), 1e-12);
  EXPECT_NEAR(u(1), load(1) * L * L * L / (3 * E * s.Iz) + load(1) * L / (G * s.ky * s.A), 1e-12);
  EXPECT_NEAR(u(2), load(2) * L * L * L / (3 * E * s.Iy) + load(2) * L / (G * s.kz * s.A), 1e-12);
  EXPECT_NEAR(th(0), load(3) * L / (G * s.J), 1e-12);
  EXPECT_NEAR(th(2), load(1) * L * L / (2 * E * s.Iz), 1e-12);   // rz = v' at a free end
  EXPECT_NEAR(th(1), -load(2) * L * L / (2 * E * s.Iy), 1e-12);  // ry = -w'
  // Resultants at the root: N, Vy, Vz = the loads, T, and My, Mz from the lever arm.
  Eigen::VectorXd de = Eigen::VectorXd::Zero(12);
  de.tail(6) = d;
  const BeamResultants r = beam_resultants(x, s, de);
  const double tol = 1e-9 * load.norm();
  EXPECT_NEAR(r.at1(0), load(0), tol);
  EXPECT_NEAR(r.at1(1), load(1), tol);
  EXPECT_NEAR(r.at1(2), load(2), tol);
  EXPECT_NEAR(r.at1(3), load(3), tol);
  EXPECT_NEAR(r.at1(5), load(1) * L, tol);   // Mz(0) = Py L
  EXPECT_NEAR(r.at1(4), -load(2) * L, tol);  // My(0) = -Pz L
  EXPECT_NEAR(r.at2(5), 0, tol);
  EXPECT_NEAR(r.at2(4), 0, tol);
  EXPECT_NEAR(r.axial(), load(0), tol);
}

TEST(BeamElement, ShearRigidMassIsPrzemieniecki) {
  const BeamSection s = section(0, 0);
  const double L = 0.7, rho = s.material.rho, A = s.A;
  const Eigen::MatrixX3d x = skew_element(L);
  const auto T = to_local(x, s);
  const ElementMatrices em = beam_element(x, s);
  const Eigen::MatrixXd Ml = T * em.M * T.transpose();
  Eigen::MatrixXd ref = Eigen::MatrixXd::Zero(12, 12);
  auto bar = [&](int a, int b, double c) {
    ref(a, a) += 2 * c, ref(b, b) += 2 * c, ref(a, b) += c, ref(b, a) += c;
  };
  bar(0, 6, rho * A * L / 6);
  bar(3, 9, rho * (s.Iy + s.Iz) * L / 6);
  const double mt[4][4] = {{156, 22 * L, 54, -13 * L},
                           {22 * L, 4 * L * L, 13 * L, -3 * L * L},
                           {54, 13 * L, 156, -22 * L},
                           {-13 * L, -3 * L * L, -22 * L, 4 * L * L}};
  const double mr[4][4] = {{36, 3 * L, -36, 3 * L},
                           {3 * L, 4 * L * L, -3 * L, -L * L},
                           {-36, -3 * L, 36, -3 * L},
                           {3 * L, -L * L, -3 * L, 4 * L * L}};
  auto plane = [&](const int (&c)[4], double I, double sg) {
    const double sgn[4] = {1, sg, 1, sg};
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        ref(c[i], c[j]) += sgn[i] * sgn[j] * (rho * A * L / 420 * mt[i][j] + rho * I / (30 * L) * mr[i][j]);
  };
  plane({1, 5, 7, 11}, s.Iz, 1);
  plane({2, 4, 8, 10}, s.Iy, -1);
  EXPECT_LT((Ml - ref).norm(), 1e-12 * ref.norm());
}

TEST(BeamElement, MassSamplesAndRigidBodyProperties) {
  const BeamSection s = section(5.0 / 6.0, 5.0 / 6.0);
  const double L = 0.6, rho = s.material.rho;
  const Eigen::MatrixX3d x = skew_element(L);
  const ElementMatrices em = beam_element(x, s);
  EXPECT_EQ(em.dofs_per_node, 6);
  EXPECT_EQ(em.M_rotary.size(), 0);
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(12, 12);
  double m = 0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (const auto& smp : em.samples) {
    S += smp.w * smp.N.transpose() * smp.N;
    m += smp.w;
    first += smp.w * smp.c;
    second += smp.w * smp.c * smp.c.transpose();
  }
  EXPECT_LT((S - em.M).norm(), 1e-13 * em.M.norm());
  const double mref = rho * s.A * L;
  EXPECT_NEAR(m, mref, 1e-12 * mref);
  const Eigen::Vector3d x1 = x.row(0).transpose(), x2 = x.row(1).transpose();
  EXPECT_LT((first - mref * 0.5 * (x1 + x2)).norm(), 1e-12 * first.norm());
  // int c c^T dm: the line's second moment plus the section's rho L (Iz e_y e_y^T + Iy e_z e_z^T).
  const Eigen::Matrix3d R = beam_frame(x, s.y_axis);
  const Eigen::Vector3d ey = R.row(1).transpose(), ez = R.row(2).transpose();
  const Eigen::Matrix3d line =
      mref * (x1 * x1.transpose() + 0.5 * (x1 * (x2 - x1).transpose() + (x2 - x1) * x1.transpose()) +
              (x2 - x1) * (x2 - x1).transpose() / 3);
  const Eigen::Matrix3d ref = line + rho * L * (s.Iz * ey * ey.transpose() + s.Iy * ez * ez.transpose());
  EXPECT_LT((second - ref).norm(), 1e-12 * ref.norm());
  // The rigid-body projection of M: mass, first moment and inertia about the origin.
  const Eigen::MatrixXd Rb = rigid_modes(x);
  const Eigen::MatrixXd MR = Rb.transpose() * em.M * Rb;
  EXPECT_LT((MR.bottomRightCorner<3, 3>() - (second.trace() * Eigen::Matrix3d::Identity() - second)).norm(),
            1e-12 * second.norm());
  // Stiffness: symmetric, rigid modes exact, rank 6.
  EXPECT_LT((em.K - em.K.transpose()).norm(), 1e-12 * em.K.norm());
  EXPECT_LT((em.K * Rb).norm(), 1e-12 * em.K.norm() * Rb.norm());
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(em.K).eigenvalues();
  for (int i = 0; i < 6; ++i) EXPECT_LT(std::abs(ev(i)), 1e-11 * ev.maxCoeff());
  EXPECT_GT(ev(6), 1e-9 * ev.maxCoeff());
}

TEST(BeamElement, GeometricStiffness) {
  const BeamSection s = section(0, 0);
  const double L = 0.8, N = 1234.5;
  const Eigen::MatrixX3d x = skew_element(L);
  const auto T = to_local(x, s);
  const Eigen::MatrixXd Kg = T * beam_geometric_stiffness(x, s, N) * T.transpose();
  // Przemieniecki's geometric stiffness, each bending plane, plus the torsional (Wagner) term.
  Eigen::MatrixXd ref = Eigen::MatrixXd::Zero(12, 12);
  const double g[4][4] = {{36, 3 * L, -36, 3 * L},
                          {3 * L, 4 * L * L, -3 * L, -L * L},
                          {-36, -3 * L, 36, -3 * L},
                          {3 * L, -L * L, -3 * L, 4 * L * L}};
  auto plane = [&](const int (&c)[4], double sg) {
    const double sgn[4] = {1, sg, 1, sg};
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) ref(c[i], c[j]) += sgn[i] * sgn[j] * N / (30 * L) * g[i][j];
  };
  plane({1, 5, 7, 11}, 1);
  plane({2, 4, 8, 10}, -1);
  const double tw = N * (s.Iy + s.Iz) / (s.A * L);
  ref(3, 3) += tw, ref(9, 9) += tw, ref(3, 9) -= tw, ref(9, 3) -= tw;
  EXPECT_LT((Kg - ref).norm(), 1e-12 * ref.norm());
  // From a displacement: the axial force of a stretch.
  Eigen::VectorXd d = Eigen::VectorXd::Zero(12);
  const Eigen::Vector3d ex = beam_frame(x, s.y_axis).row(0).transpose();
  d.segment<3>(6) = 1e-5 * ex;
  const double Nd = s.material.E * s.A * 1e-5 / L;
  EXPECT_NEAR(beam_resultants(x, s, d).axial(), Nd, 1e-9 * Nd);
  EXPECT_LT((beam_geometric_stiffness(x, s, d) - beam_geometric_stiffness(x, s, Nd)).norm(), 1e-12 * Kg.norm());
}

TEST(BeamElement, RefusesBadInput) {
  const Eigen::MatrixX3d x = skew_element(1.0);
  BeamSection s = section(0, 0);
  s.y_axis = (x.row(1) - x.row(0)).transpose() * 3.0;
  EXPECT_THROW_MSG(beam_element(x, s), ElementError, "y_axis is parallel to the element axis");
  s.y_axis.setZero();
  EXPECT_THROW_MSG(beam_element(x, s), ElementError, "y_axis must be a non-zero vector");
  auto bad = [&](auto setter, const char* msg) {
    BeamSection b = section(0, 0);
    setter(b);
    EXPECT_THROW_MSG(beam_element(x, b), ElementError, msg);
  };
  bad([](BeamSection& b) { b.A = -1e-4; }, "section A must be > 0");
  bad([](BeamSection& b) { b.A = 0; }, "section A must be > 0");
  bad([](BeamSection& b) { b.Iy = -1e-9; }, "section Iy must be > 0");
  bad([](BeamSection& b) { b.Iz = 0; }, "section Iz must be > 0");
  bad([](BeamSection& b) { b.J = -1; }, "section J must be > 0");
  bad([](BeamSection& b) { b.ky = -0.5; }, "shear factor ky must be >= 0");
  bad([](BeamSection& b) { b.kz = -0.5; }, "shear factor kz must be >= 0");
  bad([](BeamSection& b) { b.material.E = -1; }, "E must be > 0");
  bad([](BeamSection& b) { b.material.rho = -1; }, "rho must be >= 0");
  bad([](BeamSection& b) { b.A = std::nan(""); }, "section A must be > 0");
  Eigen::MatrixX3d same(2, 3);
  same << 1, 2, 3, 1, 2, 3;
  EXPECT_THROW_MSG(beam_element(same, section(0, 0)), ElementError, "zero length");
  EXPECT_THROW_MSG(beam_element(Eigen::MatrixX3d::Zero(3, 3), section(0, 0)), ElementError, "expected 2 node rows");
  EXPECT_THROW_MSG(beam_resultants(x, section(0, 0), Eigen::VectorXd::Zero(6)), ElementError, "expected 12");
}
