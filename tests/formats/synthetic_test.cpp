// The synthetic generator against references it did not compute:
//  - Newton's law for every point mass in a rotating, accelerating frame (the SID members must
//    reproduce the inertia forces of formats/SPEC.md section 6 term by term);
//  - Euler-Bernoulli beam frequencies (Blevins, "Formulas for Natural Frequency and Mode
//    Shape", 1979, table 8-1: lambda_1 = 1.87510 clamped-free, 4.73004 free-free;
//    omega = lambda^2 sqrt(EI / (rho A L^4))) and the free-free bar's first axial mode
//    omega = (pi / L) sqrt(EA / (rho A)).
#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/synthetic.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

using namespace ffr::formats;
using namespace ffr::formats::synthetic;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

namespace {

// A body of 5 points with rotary inertia and 3 arbitrary (non-orthogonal) shapes.
struct RandomBody {
  std::vector<PointMass> pts;
  MatrixXd Phi, Psi;
  VectorXd omega;
};

RandomBody random_body(std::uint32_t seed, int npts = 5, int nq = 3) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  RandomBody b;
  for (int p = 0; p < npts; ++p) {
    PointMass pm;
    pm.m = 1 + std::abs(u(rng));
    pm.c = Vector3d(u(rng), u(rng), u(rng));
    Eigen::Matrix3d A = Eigen::Matrix3d::NullaryExpr([&] { return u(rng); });
    pm.inertia = 0.1 * (A * A.transpose() + Eigen::Matrix3d::Identity());
    b.pts.push_back(pm);
  }
  b.Phi = MatrixXd::NullaryExpr(3 * npts, nq, [&] { return u(rng); });
  b.Psi = MatrixXd::NullaryExpr(3 * npts, nq, [&] { return u(rng); });
  b.omega = VectorXd::LinSpaced(nq, 10, 30);
  return b;
}

Eigen::Matrix<double, 6, 1> omega_bar(const Vector3d& w) {
  Eigen::Matrix<double, 6, 1> o;
  o << w.x() * w.x(), w.y() * w.y(), w.z() * w.z(), w.x() * w.y(), w.y() * w.z(), w.x() * w.z();
  return o;
}

}  // namespace

TEST(Synthetic, ModesAreMassOrthonormalIncludingRotaryInertia) {
  const auto b = random_body(1);
  const Sid s = from_shapes(b.pts, b.Phi, b.Psi, b.omega, {{"n0", 0}});
  EXPECT_LT((s.Me - MatrixXd::Identity(3, 3)).norm(), 1e-12);
  EXPECT_GT(s.rotary.PsiIPsi.norm(), 1e-3);  // the rotary part is really there
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(s.Ke(k, k), b.omega[k] * b.omega[k], 1e-9);
}

// Newton's law for each point, resolved in the moving frame K: the acceleration of point p is
//   a_p = a + alpha x x + w x (w x x) + 2 w x Phi_p qd + Phi_p qdd,  x = c_p + Phi_p q,
// and a point inertia I_p rotating with w + Psi_p qd adds I_p (alpha + Psi_p qdd) + gyroscopic
// terms. Projected with the virtual displacements of the frame and the modes, this must equal
// the left-hand side of the equations in formats/SPEC.md section 6 built from the SID members
// (at q = 0, where the rotary part enters only through J.M0, Cr.M0 and Me: SPEC.md).
TEST(Synthetic, MembersReproduceNewtonsLawOnThePoints) {
  const auto b = random_body(2);
  for (const bool rotary : {false, true}) {
    // One exported node per point gives the orthonormalised shapes the generator used.
    std::vector<ExportedNode> all;
    for (int p = 0; p < 5; ++p) all.push_back({"p" + std::to_string(p), p});
    const Sid s = from_shapes(b.pts, b.Phi, rotary ? b.Psi : MatrixXd(), b.omega, all);
    const Sid& sn = s;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    const Vector3d a(u(rng), u(rng), u(rng)), alpha(u(rng), u(rng), u(rng)), w(u(rng), u(rng), u(rng));
    const VectorXd qd = VectorXd::NullaryExpr(3, [&] { return u(rng); });
    const VectorXd qdd = VectorXd::NullaryExpr(3, [&] { return u(rng); });

    Vector3d F = Vector3d::Zero(), T = Vector3d::Zero();
    VectorXd Q = VectorXd::Zero(3);
    for (int p = 0; p < 5; ++p) {
      const auto& P = b.pts[p];
      const auto& node = sn.nodes[p];
      const Vector3d x = P.c;
      const Vector3d ap = a + alpha.cross(x) + w.cross(w.cross(x)) + 2 * w.cross(node.phi * qd) + node.phi * qdd;
      F += P.m * ap;
      T += P.m * x.cross(ap);
      Q += P.m * node.phi.transpose() * ap;
      // The point's own inertia turns with the frame (Euler), and with Psi_p it couples to
      // the modes; only the terms the SID keeps for the rotary part (SPEC.md).
      T += P.inertia * (alpha + node.psi * qdd) + w.cross(P.inertia * w);
      Q += node.psi.transpose() * P.inertia * (alpha + node.psi * qdd);
    }

    // The SID side: mass matrix times accelerations plus the velocity terms of section 3.
    const double m = s.refmod.mass;
    const Vector3d md = s.mdCM.M0;
    auto skew = [](const Vector3d& v) {
      Eigen::Matrix3d S;
      S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
      return S;
    };
    Eigen::Matrix3d Grq = Eigen::Matrix3d::Zero();
    MatrixXd Geq = MatrixXd::Zero(3, 3);
    for (int k = 0; k < 3; ++k) {
      Grq += qd[k] * s.Gr[k];
      Geq += qd[k] * s.Ge[k];
    }
    const Vector3d F_sid = m * a + skew(md).transpose() * alpha + s.Ct.M0.transpose() * qdd +
                           skew(w) * skew(w) * md + 2 * skew(w) * s.Ct.M0.transpose() * qd;
    const Vector3d T_sid = skew(md) * a + s.J.M0 * alpha + s.Cr.M0.transpose() * qdd + Grq * w + skew(w) * s.J.M0 * w;
    const VectorXd Q_sid = s.Ct.M0 * a + s.Cr.M0 * alpha + s.Me * qdd + Geq * w + s.Oe.M0 * omega_bar(w);
    EXPECT_LT((F - F_sid).norm(), 1e-12 * (1 + F.norm())) << "rotary " << rotary;
    EXPECT_LT((T - T_sid).norm(), 1e-12 * (1 + T.norm())) << "rotary " << rotary;
    EXPECT_LT((Q - Q_sid).norm(), 1e-12 * (1 + Q.norm())) << "rotary " << rotary;
  }
}

// First-order members: J(q), Cr(q) and the centrifugal modal force Oe(q) w_bar of the points
// at a deformed configuration x = c + Phi q. J(q) and Oe(q) are exactly quadratic/linear in q,
// so central differences recover M1 exactly (to rounding).
TEST(Synthetic, FirstOrderMembersAreTheDerivativesOfTheDeformedPointSums) {
  const auto b = random_body(3);
  std::vector<ExportedNode> all;
  for (int p = 0; p < 5; ++p) all.push_back({"p" + std::to_string(p), p});
  const Sid s = from_shapes(b.pts, b.Phi, MatrixXd(), b.omega, all);
  const Vector3d w(0.3, -0.7, 0.5);
  auto J_of = [&](const VectorXd& q) {
    Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
    for (int p = 0; p < 5; ++p) {
      const Vector3d x = b.pts[p].c + s.nodes[p].phi * q;
      J += b.pts[p].m * (x.squaredNorm() * Eigen::Matrix3d::Identity() - x * x.transpose());
    }
    return J;
  };
  auto Cr_of = [&](const VectorXd& q) {
    MatrixXd C = MatrixXd::Zero(3, 3);
    for (int p = 0; p < 5; ++p)
      for (int i = 0; i < 3; ++i)
        C.row(i) += b.pts[p].m * (b.pts[p].c + s.nodes[p].phi * q).cross(Vector3d(s.nodes[p].phi.col(i))).transpose();
    return C;
  };
  auto Oe_of = [&](const VectorXd& q) {  // sum m Phi^T w x (w x x): the modal centrifugal force
    VectorXd f = VectorXd::Zero(3);
    for (int p = 0; p < 5; ++p) {
      const Vector3d x = b.pts[p].c + s.nodes[p].phi * q;
      f += b.pts[p].m * s.nodes[p].phi.transpose() * w.cross(w.cross(x));
    }
    return f;
  };
  for (int k = 0; k < 3; ++k) {
    const VectorXd e = VectorXd::Unit(3, k);
    const Eigen::Matrix3d dJ = (J_of(e) - J_of(-e)) / 2;
    EXPECT_LT((dJ - s.J.M1[k]).norm(), 1e-12) << k;
    const MatrixXd dCr = (Cr_of(e) - Cr_of(-e)) / 2;
    EXPECT_LT((dCr - s.Cr.M1[k]).norm(), 1e-12) << k;
    const VectorXd dOe = (Oe_of(e) - Oe_of(-e)) / 2;
    EXPECT_LT((dOe - s.Oe.M1[k] * omega_bar(w)).norm(), 1e-12) << k;
  }
}

TEST(Synthetic, FreeChainMatchesEulerBernoulliAndHasNoRigidCoupling) {
  ChainParams p;
  p.points = 61;
  p.length = 2.0;
  p.mass = 3.0;
  p.EA = 100.0;  // soft, so the first axial mode is among the 6 lowest
  p.EIy = 2.0;
  p.EIz = 5.0;
  p.modes = 6;
  p.start = Vector3d(0.3, -0.2, 0.1);
  const Chain c = spring_chain(p);
  const Sid& s = c.sid;
  const double rhoA = p.mass / p.length;
  auto bending = [&](double lambda, double EI) { return lambda * lambda * std::sqrt(EI / (rhoA * std::pow(p.length, 4))); };
  const double fy = bending(4.73004, p.EIy) / (2 * M_PI), fz = bending(4.73004, p.EIz) / (2 * M_PI);
  const double fa = M_PI / p.length * std::sqrt(p.EA / rhoA) / (2 * M_PI);
  // Lumped-mass discretisation error with 60 segments is O(h^2): well below 0.2 %.
  EXPECT_NEAR(s.refmod.frequency_hz[0], fy, 2e-3 * fy);
  EXPECT_NEAR(s.refmod.frequency_hz[1], fz, 2e-3 * fz);
  bool axial_found = false;
  for (int k = 0; k < 6; ++k) axial_found |= std::abs(s.refmod.frequency_hz[k] - fa) < 2e-3 * fa;
  EXPECT_TRUE(axial_found) << "first axial mode at " << fa << " Hz";
  EXPECT_LT(s.Ct.M0.norm(), 1e-12);
  EXPECT_LT(s.Cr.M0.norm(), 1e-12);
  EXPECT_LT((s.Me - MatrixXd::Identity(6, 6)).norm(), 1e-12);
  EXPECT_EQ(s.refmod.reference, "free");
  ASSERT_EQ(s.num_nodes(), 2);
  EXPECT_EQ(s.nodes[1].name, "B");
  EXPECT_LT((s.nodes[1].origin - Vector3d(2.3, -0.2, 0.1)).norm(), 1e-14);
  // The unreduced model is consistent with the reduced one: K Phi = M Phi Omega^2.
  const MatrixXd& Phi = c.model.Phi;
  const MatrixXd res = c.model.K * Phi - c.model.M * Phi * c.model.omega.cwiseAbs2().asDiagonal();
  EXPECT_LT(res.norm(), 1e-8 * (c.model.K * Phi).norm());
}

TEST(Synthetic, ClampedChainMatchesEulerBernoulliAndHasRepeatedPairs) {
  ChainParams p;
  p.points = 61;
  p.clamped = true;
  p.EIy = p.EIz = 3.0;
  p.modes = 4;
  const Chain c = spring_chain(p);
  const double rhoA = p.mass / p.length;
  const double f1 = 1.87510 * 1.87510 * std::sqrt(p.EIy / (rhoA * std::pow(p.length, 4))) / (2 * M_PI);
  const double f2 = 4.69409 * 4.69409 * std::sqrt(p.EIy / (rhoA * std::pow(p.length, 4))) / (2 * M_PI);
  EXPECT_NEAR(c.sid.refmod.frequency_hz[0], f1, 2e-3 * f1);
  EXPECT_NEAR(c.sid.refmod.frequency_hz[1], f1, 2e-3 * f1);
  EXPECT_NEAR(c.sid.refmod.frequency_hz[2], f2, 3e-3 * f2);
  EXPECT_EQ(c.sid.refmod.reference, "clamped:A");
  EXPECT_LT(c.sid.nodes[0].phi.norm(), 1e-15);
  // Tip rotation of the first mode: theta = dv/dx of the mode shape, close to the beam's
  // finite-difference slope at the tip.
  const auto& B = c.sid.nodes[1];
  const int n = p.points;
  const double h = p.length / (n - 1);
  for (int k = 0; k < 2; ++k) {
    const Vector3d d = (c.model.Phi.block(3 * (n - 1), k, 3, 1) - c.model.Phi.block(3 * (n - 2), k, 3, 1)) / h;
    EXPECT_NEAR(B.psi(2, k), d.y(), 0.02 * d.norm());
    EXPECT_NEAR(B.psi(1, k), -d.z(), 0.02 * d.norm());
  }
}

TEST(Synthetic, ChainRoundTripsThroughTheFile) {
  ChainParams p;
  p.stiffening = true;
  p.damping_ratio = 0.02;
  const Chain c = spring_chain(p);
  const auto path = std::filesystem::temp_directory_path() / ("ffr_synth_" + std::to_string(::getpid()) + ".sid.h5");
  write_sid(c.sid, path);
  const Sid r = read_sid(path);
  std::filesystem::remove(path);
  EXPECT_EQ(r.nq(), 4);
  EXPECT_EQ(r.Ge[2], c.sid.Ge[2]);
  ASSERT_TRUE(r.stiffening.has_value());
  EXPECT_EQ(r.stiffening->K0om[1], c.sid.stiffening->K0om[1]);
  ASSERT_EQ(r.stiffening->interfaces.size(), 2u);
  EXPECT_EQ(r.provenance.damping_model, "ratio 0.02");
}

TEST(Synthetic, BadParametersAreRefused) {
  ChainParams p;
  p.points = 1;
  EXPECT_THROW(spring_chain(p), std::invalid_argument);
  p = ChainParams{};
  p.modes = 1000;
  EXPECT_THROW(spring_chain(p), std::invalid_argument);
  const auto b = random_body(4);
  auto pts = b.pts;
  pts[0].m = -1;
  EXPECT_THROW(from_shapes(pts, b.Phi, b.Psi, b.omega, {}), std::invalid_argument);
  EXPECT_THROW(from_shapes(b.pts, b.Phi.topRows(6), MatrixXd(), b.omega, {}), std::invalid_argument);
}
