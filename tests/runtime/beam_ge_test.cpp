// The geometrically exact beam in directors (FORMULATION.md 17) against references nobody here
// computed (its elastica, buckling, pendulum and hung-body checks run with the ancf beam's in
// beam_elastica_test.cpp):
// - the element's forces against finite differences of its energy, its tangent against finite
//   differences of its forces (directors neither unit nor orthogonal: the element is defined off
//   the constraint manifold too, where Newton's iterates are);
// - the clamped beam's first bending frequencies against Euler-Bernoulli (beta L = 1.8751,
//   4.6941: the roots of cos(bL) cosh(bL) = -1) for a slender beam, and against Timoshenko's
//   beam theory (S. P. Timoshenko, "On the correction for shear of the differential equation for
//   transverse vibrations of prismatic bars", Phil. Mag. 41 (1921)) for a thick one: an
//   independent oracle written here shoots the clamped-free Timoshenko equations by RK4 and finds
//   the roots of the free end's determinant; the first torsion frequency against the rod's
//   (pi/2) sqrt(G J / (rho Ip)) / L;
// - a tip torque twists the cantilever by T L / (G J) (Saint-Venant torsion), also far beyond
//   small angles;
// - a tip moment M = 2 pi EI / L rolls the cantilever into a full circle (the exact solution of
//   the elastica under an end moment: constant curvature M / EI), its tip back at the clamp;
// - a flexible pendulum (pinned, released horizontal under gravity) against the independent planar
//   Reissner beam oracle of the tests (reissner_beam.hpp: its own strains, consistent mass, its own
//   trapezoidal integrator) on a fine mesh;
// - bad input refused naming the file and field.
#include "reissner_beam.hpp"
#include "support.hpp"

#include "ffr/runtime/beam.hpp"
#include "ffr/runtime/dynamics.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace ffr::runtime;

namespace {

using Vec24 = Eigen::Matrix<double, 24, 1>;
using Mat24 = Eigen::Matrix<double, 24, 24>;

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

constexpr double kE = 2.1e11, kNu = 0.3, kRho = 7850;
const double kG = kE / (2 * (1 + kNu));

// A steel cantilever of square side a along x from the origin, clamped at its start; `loads` the
// forces list's entries (at node "end").
std::string cantilever(double L, double a, int elements, const std::string& loads, const std::string& solver,
                       double j = 0.1406) {
  const double A = a * a, I = a * a * a * a / 12, J = j * a * a * a * a;
  return R"({"bodies": [{"name": "beam", "type": "beam", "formulation": "geometrically_exact", "start": [0, 0, 0],
      "end": [)" + num(L) + R"(, 0, 0], "y_axis": [0, 1, 0], "elements": )" + std::to_string(elements) +
         R"(, "E": 2.1e11, "nu": 0.3, "rho": 7850,
      "section": {"A": )" + num(A) + R"(, "Iy": )" + num(I) + R"(, "Iz": )" + num(I) + R"(, "J": )" + num(J) + R"(}}],
    "joints": [{"name": "clamp", "type": "fixed", "body1": "ground", "body2": "beam", "node2": "start"}],
    "forces": [)" + loads + R"(],
    "solver": )" + solver + R"(,
    "outputs": [{"name": "tip", "type": "node_position", "body": "beam", "node": "end"},
                {"name": "mid", "type": "node_position", "body": "beam", "node": "n8"}]})";
}

std::string tip_load(const std::string& type, const Eigen::Vector3d& v) {
  const std::string val = "[" + num(v(0)) + ", " + num(v(1)) + ", " + num(v(2)) + "]";
  return R"({"name": "load", "type": ")" + type + R"(", "body": "beam", "node": "end", "table": {"t": [0, 1], "value": [)" + val +
         ", " + val + "]}}";
}

// The rotation of a node body's frame (its directors) from its reference frame A0.
Eigen::Matrix3d node_rotation(const Model& m, const Data& d, int body) {
  const Body& b = m.bodies[static_cast<std::size_t>(body)];
  Eigen::Matrix3d A;
  for (int c = 0; c < 3; ++c) A.col(c) = d.state.q.segment<3>(b.offset + 3 + 3 * c);
  return A * b.A0.transpose();
}

// Small vibrations about the straight, unstressed beam clamped at node 0: per node the
// translation and the small rotation theta (d_i -> d_i + theta x d_i), the element tangents and
// the node bodies' masses mapped to them. Returns the circular frequencies, ascending.
Eigen::VectorXd clamped_frequencies(const Model& m) {
  const GeBeam& g = m.ge_beams.at(0);
  const int n = g.elements + 1, nd = 6 * n;
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(nd, nd), M = Eigen::MatrixXd::Zero(nd, nd);
  std::vector<Eigen::Matrix<double, 12, 6>> T(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const Body& b = m.bodies[static_cast<std::size_t>(g.node_bodies[static_cast<std::size_t>(k)])];
    auto& t = T[static_cast<std::size_t>(k)];
    t.setZero();
    t.block<3, 3>(0, 0).setIdentity();
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d d = b.A0.col(i);
      Eigen::Matrix3d dx;
      dx << 0, -d(2), d(1), d(2), 0, -d(0), -d(1), d(0), 0;
      t.block<3, 3>(3 + 3 * i, 3) = -dx;  // theta x d = -[d]x theta
    }
    // Kinetic energy 1/2 m |r_dot|^2 + 1/2 sum_i J0_ii |d_i_dot|^2 (the body's natural coordinates).
    Eigen::Matrix<double, 12, 12> Mb = Eigen::Matrix<double, 12, 12>::Zero();
    Mb.block<3, 3>(0, 0).diagonal().setConstant(b.mass);
    for (int i = 0; i < 3; ++i) Mb.block<3, 3>(3 + 3 * i, 3 + 3 * i).diagonal().setConstant(b.J0(i, i));
    M.block<6, 6>(6 * k, 6 * k) = t.transpose() * Mb * t;
  }
  for (int e = 0; e < g.elements; ++e) {
    const Body& a = m.bodies[static_cast<std::size_t>(g.node_bodies[static_cast<std::size_t>(e)])];
    const Body& b = m.bodies[static_cast<std::size_t>(g.node_bodies[static_cast<std::size_t>(e + 1)])];
    Vec24 q, f = Vec24::Zero();
    q << a.r0, a.A0.col(0), a.A0.col(1), a.A0.col(2), b.r0, b.A0.col(0), b.A0.col(1), b.A0.col(2);
    Mat24 Ke = Mat24::Zero();
    ge_beam_element(g, e, q, Vec24::Zero(), f, &Ke, nullptr);
    Eigen::Matrix<double, 24, 12> Te = Eigen::Matrix<double, 24, 12>::Zero();
    Te.block<12, 6>(0, 0) = T[static_cast<std::size_t>(e)];
    Te.block<12, 6>(12, 6) = T[static_cast<std::size_t>(e + 1)];
    K.block<12, 12>(6 * e, 6 * e) += Te.transpose() * Ke * Te;
  }
  const int nf = nd - 6;  // node 0 clamped
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ge(K.bottomRightCorner(nf, nf), M.bottomRightCorner(nf, nf));
  return ge.eigenvalues().cwiseMax(0.0).cwiseSqrt();
}

// Independent oracle: the clamped-free Timoshenko beam, w the deflection, psi the section's
// rotation: kGA (w'' - psi') + rho A omega^2 w = 0, EI psi'' + kGA (w' - psi) + rho I omega^2 psi = 0;
// w = psi = 0 at x = 0, EI psi' = 0 and kGA (w' - psi) = 0 at x = L. Two shots from the clamp
// (w'(0) = 1 or psi'(0) = 1) by RK4 with 2000 steps; omega is a root of the free end's 2 x 2
// determinant, bracketed by scanning and refined by bisection. Returns the first `count` roots.
std::vector<double> timoshenko_oracle(double L, double EI, double kGA, double rhoA, double rhoI, int count, double wmax) {
  const auto det = [&](double w) {
    const auto f = [&](const Eigen::Vector4d& s) {  // w, w', psi, psi'
      const double wpp = s(3) - rhoA * w * w * s(0) / kGA;
      const double psipp = -(kGA * (s(1) - s(2)) + rhoI * w * w * s(2)) / EI;
      return Eigen::Vector4d(s(1), wpp, s(3), psipp);
    };
    Eigen::Matrix2d D;
    for (int shot = 0; shot < 2; ++shot) {
      Eigen::Vector4d y(0, shot == 0 ? 1 : 0, 0, shot == 1 ? 1 : 0);
      const int n = 2000;
      const double h = L / n;
      for (int i = 0; i < n; ++i) {
        const Eigen::Vector4d k1 = f(y), k2 = f(y + h / 2 * k1), k3 = f(y + h / 2 * k2), k4 = f(y + h * k3);
        y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
      }
      D(0, shot) = y(3);         // moment / EI
      D(1, shot) = y(1) - y(2);  // shear / kGA
    }
    return D.determinant();
  };
  std::vector<double> roots;
  const int scan = 4000;
  double w0 = wmax / scan, d0 = det(w0);
  for (int i = 2; i <= scan && static_cast<int>(roots.size()) < count; ++i) {
    const double w1 = wmax * i / scan, d1 = det(w1);
    if ((d0 < 0) != (d1 < 0)) {
      double lo = w0, hi = w1, dlo = d0;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi), dm = det(mid);
        if ((dm < 0) == (dlo < 0)) {
          lo = mid;
          dlo = dm;
        } else {
          hi = mid;
        }
      }
      roots.push_back(0.5 * (lo + hi));
    }
    w0 = w1;
    d0 = d1;
  }
  return roots;
}

}  // namespace

// The element's forces are the gradient of its energy, its tangent the derivative of its forces
// (central differences), at a bent, twisted, sheared and stretched state whose directors are
// perturbed off orthonormality.
TEST(BeamGeometricallyExact, ElementForcesAndTangentMatchFiniteDifferences) {
  std::vector<Body> nodes;
  const GeBeam g = make_ge_beam(nodes, "b", Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0.2, -0.1), Eigen::Vector3d(0, 0, 1), 3,
                                1e7, 4e6, 1000, 1e-3, 2e-7, 3e-7, 4e-7, 5.0 / 6, 0.0, "f", "bodies[0]");
  Vec24 q;
  q << nodes[1].r0, nodes[1].A0.col(0), nodes[1].A0.col(1), nodes[1].A0.col(2), nodes[2].r0, nodes[2].A0.col(0),
      nodes[2].A0.col(1), nodes[2].A0.col(2);
  // Node b turned by 0.9 rad about a skew axis (a large element rotation), then everything perturbed.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.9, Eigen::Vector3d(0.3, -0.5, 0.8).normalized()).toRotationMatrix();
  for (int i = 0; i < 3; ++i) q.segment<3>(15 + 3 * i) = R * q.segment<3>(15 + 3 * i);
  for (int i = 0; i < 24; ++i) q(i) += 0.03 * std::sin(1.7 * i + 0.3);
  const auto forces = [&](const Vec24& x, Mat24* K) {
    Vec24 f = Vec24::Zero();
    ge_beam_element(g, 1, x, Vec24::Zero(), f, K, nullptr);
    return f;
  };
  const auto energy = [&](const Vec24& x) {
    Vec24 f = Vec24::Zero();
    return ge_beam_element(g, 1, x, Vec24::Zero(), f, nullptr, nullptr);
  };
  Mat24 K = Mat24::Zero();
  const Vec24 f = forces(q, &K);
  double ef = 0, ek = 0;
  const double h = 1e-6;
  for (int j = 0; j < 24; ++j) {
    Vec24 qp = q, qm = q;
    qp(j) += h;
    qm(j) -= h;
    ef = std::max(ef, std::abs(f(j) - (energy(qp) - energy(qm)) / (2 * h)));
    ek = std::max(ek, ((forces(qp, nullptr) - forces(qm, nullptr)) / (2 * h) - K.col(j)).cwiseAbs().maxCoeff());
  }
  std::printf("forces vs energy gradient %.3e of %.3e; tangent vs force differences %.3e of %.3e\n", ef, f.cwiseAbs().maxCoeff(), ek,
              K.cwiseAbs().maxCoeff());
  EXPECT_LT(ef, 1e-6 * f.cwiseAbs().maxCoeff());
  EXPECT_LT(ek, 1e-6 * K.cwiseAbs().maxCoeff());
  EXPECT_LT((K - K.transpose()).cwiseAbs().maxCoeff(), 1e-9 * K.cwiseAbs().maxCoeff());
  // Rigid motions cost nothing: the energy of the reference turned and moved is zero.
  Vec24 q0, qr;
  q0 << nodes[1].r0, nodes[1].A0.col(0), nodes[1].A0.col(1), nodes[1].A0.col(2), nodes[2].r0, nodes[2].A0.col(0),
      nodes[2].A0.col(1), nodes[2].A0.col(2);
  for (int v = 0; v < 8; ++v) qr.segment<3>(3 * v) = R * q0.segment<3>(3 * v) + (v % 4 == 0 ? Eigen::Vector3d(0.3, -1, 2) : Eigen::Vector3d::Zero());
  std::printf("energy of a rigid motion %.3e (bent state %.3e)\n", energy(qr), energy(q));
  EXPECT_LT(energy(qr), 1e-12 * energy(q));
}

// A slender clamped beam (1 m, 10 mm square, 16, 32 and 64 elements): the first bending pair against
// Euler-Bernoulli, the second against Euler-Bernoulli within the rotary inertia and shear it
// leaves out, and the discretisation error shrinking as h^2 (the linear element's order).
TEST(BeamGeometricallyExact, SlenderClampedBeamFrequenciesMatchEulerBernoulli) {
  const double L = 1, a = 0.01, EI = kE * a * a * a * a / 12, rhoA = kRho * a * a;
  const double base = std::sqrt(EI / (rhoA * L * L * L * L));
  const double w1 = 1.8751040687 * 1.8751040687 * base, w2 = 4.6940911330 * 4.6940911330 * base;
  double err[3] = {0, 0, 0};
  for (int r = 0; r < 3; ++r) {
    const int n = 16 << r;
    const Eigen::VectorXd w = clamped_frequencies(test::model_from(cantilever(L, a, n, "", R"({"analysis": "static"})")));
    std::printf("%d elements: omega %.5f %.5f %.5f %.5f rad/s; Euler-Bernoulli %.5f, %.5f (%.3e, %.3e relative)\n", n, w(0), w(1),
                w(2), w(3), w1, w2, w(0) / w1 - 1, w(2) / w2 - 1);
    EXPECT_NEAR(w(1) / w(0), 1.0, 1e-7);  // the square bends alike in both planes
    EXPECT_NEAR(w(3) / w(2), 1.0, 1e-7);
    err[r] = w(0) / w1 - 1;
    if (n == 16) {
      EXPECT_NEAR(w(0) / w1, 1.0, 2e-3);
      EXPECT_NEAR(w(2) / w2, 1.0, 1e-2);
    }
  }
  // Against Euler-Bernoulli the error also holds the continuum's shear and rotary inertia
  // (about 3e-5 here), which no mesh removes: the ratio of successive differences is the order.
  const double ratio = (err[0] - err[1]) / (err[1] - err[2]);
  std::printf("first frequency's change ratio 16-32 / 32-64 elements: %.3f (h^2: 4)\n", ratio);
  EXPECT_NEAR(ratio, 4.0, 0.3);
}

// A thick clamped beam (0.5 m, 0.1 m square: L / a = 5) against the Timoshenko oracle with the
// same shear factor 5/6, 32 elements: the first three bending frequencies within 0.5 %, and
// visibly below Euler-Bernoulli's (shear and rotary inertia); the first torsion frequency against
// the rod's (pi / 2) sqrt(G J / (rho Ip)) / L.
TEST(BeamGeometricallyExact, ThickClampedBeamFrequenciesMatchTimoshenko) {
  const double L = 0.5, a = 0.1, A = a * a, I = a * a * a * a / 12, J = 0.1406 * a * a * a * a;
  const Eigen::VectorXd w = clamped_frequencies(test::model_from(cantilever(L, a, 32, "", R"({"analysis": "static"})")));
  const std::vector<double> t = timoshenko_oracle(L, kE * I, 5.0 / 6 * kG * A, kRho * A, kRho * I, 3, 4e5);
  ASSERT_EQ(t.size(), 3u);
  const double eb1 = 1.8751040687 * 1.8751040687 * std::sqrt(kE * I / (kRho * A * L * L * L * L));
  const double tors = M_PI / 2 * std::sqrt(kG * J / (kRho * 2 * I)) / L;
  // Bending pairs: w(0) = w(1), ...; the torsion mode falls among them.
  std::vector<double> bend, other;
  for (int i = 0; i + 1 < w.size() && bend.size() < 3; ++i) {
    if (std::abs(w(i + 1) / w(i) - 1) < 1e-8) {
      bend.push_back(w(i));
      ++i;
    } else {
      other.push_back(w(i));
    }
  }
  ASSERT_EQ(bend.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    std::printf("bending %d: %.3f rad/s, Timoshenko %.3f (%.3e relative)\n", i + 1, bend[static_cast<std::size_t>(i)],
                t[static_cast<std::size_t>(i)], bend[static_cast<std::size_t>(i)] / t[static_cast<std::size_t>(i)] - 1);
    EXPECT_NEAR(bend[static_cast<std::size_t>(i)] / t[static_cast<std::size_t>(i)], 1.0, 5e-3);
  }
  std::printf("Euler-Bernoulli's first %.3f (Timoshenko %.3e below it)\n", eb1, 1 - t[0] / eb1);
  EXPECT_LT(t[0] / eb1, 0.99);
  ASSERT_FALSE(other.empty());
  std::printf("torsion: %.3f rad/s, rod %.3f (%.3e relative)\n", other[0], tors, other[0] / tors - 1);
  EXPECT_NEAR(other[0] / tors, 1.0, 5e-3);
}

// Saint-Venant torsion: a tip torque T about the axis twists the tip by T L / (G J), at 0.05 rad
// with the square's J (0.1406 a^4: Roark) and at 2 rad with a torsionally soft section (J =
// 0.002 a^4, an open thin-walled one's order): a large rotation, for which the element's curvature
// is the relative rotation's angle. (With the square's J, 2 rad would need T = 2.6 EI / L, beyond
// where a dead axial torque leaves the straight cantilever stable: Greenhill, Ziegler.)
TEST(BeamGeometricallyExact, TipTorqueTwistsByTLOverGJ) {
  const double L = 1, a = 0.01;
  for (const double phi : {0.05, 2.0}) {
    const double j = phi < 1 ? 0.1406 : 0.002, GJ = kG * j * a * a * a * a;
    const double T = phi * GJ / L;
    const Model m = test::model_from(
        cantilever(L, a, 16, tip_load("point_torque", Eigen::Vector3d(T, 0, 0)), R"({"analysis": "static"})", j));
    Data d(m);
    for (const auto& n : initialize(m, d)) std::printf("note: %s\n", n.c_str());
    const Eigen::Matrix3d R = node_rotation(m, d, m.find_body("beam:n16"));
    const Eigen::AngleAxisd aa(R);
    const double twist = aa.angle() * aa.axis()(0);
    const auto tip = test::output(m, d, "tip");
    std::printf("torque %.4f N m: twist %.9f rad, T L / (G J) %.9f (%.2e relative); tip (%.3e, %.3e, %.3e)\n", T, twist, phi,
                twist / phi - 1, tip[0] - L, tip[1], tip[2]);
    EXPECT_NEAR(twist / phi, 1.0, 1e-6);
    EXPECT_NEAR(aa.axis()(0) * (aa.angle() > 0 ? 1 : -1), 1.0, 1e-9);
    EXPECT_NEAR(tip[1], 0.0, 1e-9);
    EXPECT_NEAR(tip[2], 0.0, 1e-9);
  }
}

// A tip moment M = 2 pi EI / L about y bends the cantilever to the constant curvature M / EI: a
// full circle, the tip back at the clamp and turned by 2 pi (to its reference orientation). A
// moment of fixed direction is not conservative in space, and a beam rolled up by it buckles
// sideways unless it is much stiffer out of its plane: the section here has Iz = 100 Iy and
// J = 50 Iy (a deep one: lateral buckling of the straight beam near 90 EIy / L, far above M).
// The static analysis needs load stepping here (Newton from the straight beam does not converge).
// The nodes lie on the polygon of 16 equal chords (the element's chord keeps its length), so the
// middle node is a chord polygon's diameter L / (16 sin(pi / 16)) from the clamp, not the
// circle's L / pi (0.65 % apart).
TEST(BeamGeometricallyExact, TipMomentRollsTheCantileverIntoACircle) {
  const double L = 1, a = 0.01, EI = kE * a * a * a * a / 12;
  const double M = 2 * M_PI * EI / L;
  std::string json = cantilever(L, a, 16, tip_load("point_torque", Eigen::Vector3d(0, -M, 0)), R"({"analysis": "static"})", 50.0 / 12);
  const std::string iz = "\"Iz\": " + num(a * a * a * a / 12);
  json.replace(json.find(iz), iz.size(), "\"Iz\": " + num(100 * a * a * a * a / 12));
  const Model m = test::model_from(json);
  Data d(m);
  for (const auto& n : initialize(m, d)) std::printf("note: %s\n", n.c_str());
  const auto tip = test::output(m, d, "tip"), mid = test::output(m, d, "mid");
  const Eigen::Matrix3d R = node_rotation(m, d, m.find_body("beam:n16"));
  const double diameter = Eigen::Vector3d(mid[0], mid[1], mid[2]).norm();
  std::printf("rolled: tip (%.3e, %.3e, %.3e) m, tip rotation from identity %.3e; middle node %.6f m from the clamp "
              "(chord polygon %.6f, circle %.6f)\n",
              tip[0], tip[1], tip[2], (R - Eigen::Matrix3d::Identity()).norm(), diameter, L / (16 * std::sin(M_PI / 16)), L / M_PI);
  EXPECT_LT(Eigen::Vector3d(tip[0], tip[1], tip[2]).norm(), 1e-6 * L);
  EXPECT_LT((R - Eigen::Matrix3d::Identity()).norm(), 1e-6);
  EXPECT_NEAR(diameter, L / (16 * std::sin(M_PI / 16)), 1e-5 * L);
  EXPECT_NEAR(mid[2] > 0 ? 1 : -1, 1, 0);  // bent toward +z by a moment about -y
}

// An element's relative rotation (the angle between its nodes' director frames) against frames
// set by hand: node k turned about y by phi_k from the reference (nodes 0, 1 by 0, phi1, the
// rest by phi2), so element 1 turns by phi2 - phi1 and the others by phi1 or not at all. A failing step names an element turned by more than 120 degrees (its
// curvature theta / sin(theta) singular at 180) and asks for more elements; below, nothing.
TEST(BeamGeometricallyExact, LargestElementTurnIsTheAngleBetweenItsNodesFrames) {
  const Model m = test::model_from(cantilever(1, 0.01, 8, tip_load("point_force", Eigen::Vector3d(0, 0, -1)), R"({"end": 0.01, "step": 0.001})"));
  ASSERT_EQ(m.ge_beams.size(), 1u);
  const GeBeam& beam = m.ge_beams[0];
  const auto turned = [&](double phi1, double phi2) {
    Eigen::VectorXd q = Data(m).state.q;
    for (int k = 0; k <= beam.elements; ++k) {
      const Body& b = m.bodies[static_cast<std::size_t>(beam.node_bodies[static_cast<std::size_t>(k)])];
      const double phi = k == 0 ? 0.0 : k == 1 ? phi1 : phi2;
      const Eigen::Matrix3d A = Eigen::AngleAxisd(phi, Eigen::Vector3d::UnitY()).toRotationMatrix() * b.A0;
      for (int c = 0; c < 3; ++c) q.segment<3>(b.offset + 3 + 3 * c) = A.col(c);
    }
    return q;
  };
  const Eigen::VectorXd q = turned(0.4, 0.4 + 2.3), calm = turned(0.4, 0.4 + 1.9);
  const ElementTurn t = ge_beam_largest_turn(m, beam, q);
  EXPECT_EQ(t.element, 1);
  EXPECT_NEAR(t.angle, 2.3, 1e-12);
  EXPECT_NEAR(ge_beam_largest_turn(m, beam, turned(3.0, 3.1)).angle, 3.0, 1e-12);
  Eigen::VectorXd broken = q;
  broken(m.bodies[static_cast<std::size_t>(beam.node_bodies[2])].offset + 4) = std::nan("");
  EXPECT_EQ(ge_beam_largest_turn(m, beam, broken).element, 0);  // element 1 is not finite: skipped
  const std::string hint = ge_beam_failure_hint(m, calm, q);
  EXPECT_NE(hint.find("Element 1 of beam 'beam' (nodes n1, n2) turns by 132 degrees in the last iterate"), std::string::npos) << hint;
  EXPECT_NE(hint.find("(\"elements\": 16"), std::string::npos) << hint;
  EXPECT_NE(ge_beam_failure_hint(m, q, calm).find("at the step's start"), std::string::npos);
  EXPECT_EQ(ge_beam_failure_hint(m, calm, calm), "");  // 109 degrees: not suspect
}

// Twice the rolling moment, M = 4 pi EI / L, rolls the cantilever twice round (the elastica under
// an end moment: constant curvature M / EI, the tip back at the clamp). Four elements would each
// have to turn by half a revolution, where the element's curvature is singular: the static
// solve fails and must name the element and ask for eight, with which the tip closes on the
// clamp (constant curvature is exact in the element).
TEST(BeamGeometricallyExact, RollingTwiceRoundNeedsMoreThanHalfATurnPerElement) {
  const double L = 1, a = 0.01, EI = kE * a * a * a * a / 12;
  const double M = 4 * M_PI * EI / L;
  const auto rolled = [&](int elements) {
    std::string json = cantilever(L, a, elements, tip_load("point_torque", Eigen::Vector3d(0, -M, 0)), R"({"analysis": "static"})",
                                  50.0 / 12);
    const std::string iz = "\"Iz\": " + num(a * a * a * a / 12);
    json.replace(json.find(iz), iz.size(), "\"Iz\": " + num(100 * a * a * a * a / 12));
    const std::string mid = "\"node\": \"n8\"";
    json.replace(json.find(mid), mid.size(), "\"node\": \"n" + std::to_string(elements / 2) + "\"");
    return test::model_from(json);
  };
  const std::string message = test::initialize_refusal(rolled(4));
  std::printf("4 elements: %s\n", message.c_str());
  EXPECT_NE(message.find("of beam 'beam' (nodes n"), std::string::npos) << message;
  EXPECT_NE(message.find("(\"elements\": 8"), std::string::npos) << message;
  const Model m = rolled(8);
  Data d(m);
  initialize(m, d);
  const auto tip = test::output(m, d, "tip");
  std::printf("8 elements: tip (%.3e, %.3e, %.3e) m\n", tip[0], tip[1], tip[2]);
  EXPECT_LT(Eigen::Vector3d(tip[0], tip[1], tip[2]).norm(), 1e-6 * L);
}

TEST(BeamGeometricallyExact, BadInputIsRefusedNamingTheField) {
  const std::string good = cantilever(1, 0.01, 4, tip_load("point_force", Eigen::Vector3d(0, 0, -1)), R"({"analysis": "static"})");
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    const auto at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return s.replace(at, from.size(), to);
  };
  test::expect_error(with("\"elements\": 4", "\"elements\": 0"), "bodies[0].elements", "at least 1");
  // Node bodies beyond the model's coordinates: refused before they are made (100 000 elements
  // ended in "std::bad_alloc" after 36 s; 2 000 spent minutes zeroing 10 GB).
  test::expect_error(with("\"elements\": 4", "\"elements\": 416"), "bodies[0].elements", "at most 415 elements");
  test::expect_error(with("\"elements\": 4", "\"elements\": 100000"), "bodies[0].elements", "1200012 coordinates");
  test::expect_error(with("\"end\": [1, 0, 0]", "\"end\": [0, 0, 0]"), "bodies[0].end", "zero length");
  test::expect_error(with("\"y_axis\": [0, 1, 0]", "\"y_axis\": [2, 0, 0]"), "bodies[0].y_axis", "along the beam");
  test::expect_error(with("\"nu\": 0.3, ", ""), "bodies[0]", "nu");
  test::expect_error(with("\"nu\": 0.3", "\"nu\": 0.5"), "bodies[0].nu", "(-1, 0.5)");
  test::expect_error(with("\"node\": \"end\"", "\"node\": \"n5\""), "node", "has no node 'n5'");
  test::expect_error(with("\"node2\": \"start\"", "\"node2\": \"n-1\""), "node2", "has no node 'n-1'");
  test::expect_error(with("\"node2\": \"start\"", "\"at\": [0, 0, 0]"), "joints[0]", "without a node");
  test::expect_error(with("\"formulation\": \"geometrically_exact\"", "\"formulation\": \"simo\""), "formulation", "unknown beam formulation");
}

// A flexible pendulum (1 m, 10 x 10 mm, E = 2.1e9 Pa: it bends visibly), pinned at its start by a
// revolute joint about y and released horizontal: the runtime's 16-element beam against the planar
// Reissner oracle with 64 elements (the converged reference) over 0.5 s at h = 1 ms: the tip
// within 1 % of the length (lumped mass and 16 elements against 64 consistent ones).
// The same with the generalized-alpha scheme (rho_inf = 0.9: its numerical damping of the
// highest modes leaves the swing within the same bound).
TEST(BeamGeometricallyExact, PendulumMatchesThePlanarReissnerOracle) {
  for (const std::string solver : {R"({"end": 0.5, "step": 1e-3})",
                                   R"({"end": 0.5, "step": 1e-3, "integrator": "generalized_alpha", "spectral_radius": 0.9})"}) {
  SCOPED_TRACE(solver);
  const double L = 1, a = 0.01, E = 2.1e9, A = a * a, I = a * a * a * a / 12, g = 9.81, h = 1e-3, end = 0.5;
  std::string json = cantilever(L, a, 16, "", solver);
  json.replace(json.find("\"E\": 2.1e11"), 11, "\"E\": 2.1e9");
  json.replace(json.find("\"type\": \"fixed\""), 15, "\"type\": \"revolute\", \"axis\": [0, 1, 0]");
  json.replace(json.find("{\"bodies\""), 9, "{\"gravity\": [0, 0, -9.81], \"bodies\"");
  const Model m = test::model_from(json);
  Data d(m);
  initialize(m, d);
  // The oracle in its (x, y) plane: y is the runtime's z, gravity along -y.
  test::ReissnerBeam b;
  b.EA = E * A;
  b.GA = 5.0 / 6 * E / 2.6 * A;
  b.EI = E * I;
  b.rhoA = kRho * A;
  b.rhoI = kRho * I;
  b.L = L;
  b.n = 64;
  test::BeamIntegrator in(b);
  const auto fixed = [](double) { return Eigen::Vector3d::Zero(); };
  in.prescribed = {{0, fixed}, {1, fixed}};
  in.load = [&](double) {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(b.ndof());
    for (int i = 0; i <= b.n; ++i) f(3 * i + 1) = -b.rhoA * g * L / b.n * ((i == 0 || i == b.n) ? 0.5 : 1.0);
    return f;
  };
  in.start(0, b.reference(), Eigen::VectorXd::Zero(b.ndof()));
  double worst = 0, lowest = 0;
  while (d.state.t < end - 1e-9) {
    step(m, d);
    in.step(h);
    const auto tip = test::output(m, d, "tip");
    const double dx = tip[0] - in.u(3 * b.n), dz = tip[2] - in.u(3 * b.n + 1);
    worst = std::max(worst, std::hypot(dx, dz));
    lowest = std::min(lowest, tip[2]);
  }
  const auto tip = test::output(m, d, "tip");
  std::printf("%s, pendulum at %.2f s: tip (%.7f, %.7f), oracle (%.5f, %.5f); largest distance %.3e m; lowest tip z %.3f m\n",
              m.settings.integrator == Integrator::GeneralizedAlpha ? "generalized-alpha" : "trapezoidal", end, tip[0], tip[2], in.u(3 * b.n), in.u(3 * b.n + 1), worst, lowest);
  EXPECT_LT(lowest, -0.5);  // a large swing
  EXPECT_LT(worst, 1e-2 * L);
  }
}

// Newton stops at the default newton_tolerance (1e-10, scaled) on the node frames' constraints as
// on the slider-crank (SliderCrank.NewtonToleranceBoundsTheAcceptedState): on the oracle test's
// pendulum, pinned by a spherical joint, the accepted states must be those of Newton run to
// round-off (newton_tolerance 1e-15) to within what the tolerance allows, with the constraints at
// round-off. What this guards: the second update's error estimate, from the contraction of the
// first two increments, is below 1e-12 there while the third increment (the tangent's constraint
// terms built at the predictor: contracting by only ~0.02) is 1e-10 to 2e-10; accepting the second
// iterate on its estimate and its measured violation alone put the states 4.4e-8 apart over these
// 0.2 s (ali3p.cpp, the acceptance).
TEST(BeamGeometricallyExact, NewtonToleranceBoundsTheAcceptedState) {
  const double a = 0.01;
  std::string json = cantilever(1.0, a, 16, "", R"({"end": 0.2, "step": 1e-3})");
  json.replace(json.find("\"E\": 2.1e11"), 11, "\"E\": 2.1e9");
  json.replace(json.find("\"type\": \"fixed\""), 15, "\"type\": \"spherical\"");
  json.replace(json.find("{\"bodies\""), 9, "{\"gravity\": [0, 0, -9.81], \"bodies\"");
  const Model loose = test::model_from(json);
  Model tight = loose;
  tight.settings.newton_tolerance = 1e-15;
  const test::SideBySide r = test::step_side_by_side(loose, tight);
  std::printf("states apart by %.2e at most (scaled); %.2f against %.2f Newton iterations a step; violation %.2e\n", r.apart,
              r.iterations_a, r.iterations_b, r.violation);
  EXPECT_LT(r.iterations_a, r.iterations_b - 0.5);  // the default does stop earlier
  EXPECT_LT(r.apart, 1e-8);
  EXPECT_LT(r.violation, 1e-12);
}

// A rigid body welded to the tip by a fixed joint (a node that turns carries it), its centre of
// mass at the node: statically it loads the tip with its weight alone, as the weight applied as
// a point force does (statics of a rigid attachment with no lever arm).
TEST(BeamGeometricallyExact, RigidBodyWeldedToTheTipLoadsItWithItsWeight) {
  const double m = 0.5, g = 9.81;
  const std::string solver = R"({"analysis": "static"})";
  std::string welded = cantilever(1, 0.01, 16, "", solver);
  welded.replace(welded.find("{\"bodies\""), 9, "{\"gravity\": [0, 0, -9.81], \"bodies\"");
  welded.replace(welded.find("}}],"), 4, R"(}}, {"name": "bob", "type": "rigid", "mass": 0.5, "com": [1, 0, 0],
      "inertia": [[1e-4, 0, 0], [0, 2e-4, 0], [0, 0, 2e-4]]}],)");
  welded.replace(welded.find("\"forces\""), 8, R"("joints2")");
  welded.replace(welded.find("\"joints2\": []"), 13, "\"forces\": []");
  const std::string clamp = R"("node2": "start"})";
  welded.replace(welded.find(clamp), clamp.size(),
                 R"("node2": "start"}, {"name": "weld", "type": "fixed", "body1": "beam", "node1": "end", "body2": "bob"})");
  std::string loaded = cantilever(1, 0.01, 16, tip_load("point_force", Eigen::Vector3d(0, 0, -m * g)), solver);
  loaded.replace(loaded.find("{\"bodies\""), 9, "{\"gravity\": [0, 0, -9.81], \"bodies\"");
  const Model mw = test::model_from(welded), ml = test::model_from(loaded);
  Data dw(mw), dl(ml);
  initialize(mw, dw);
  initialize(ml, dl);
  const auto tw = test::output(mw, dw, "tip"), tl = test::output(ml, dl, "tip");
  std::printf("welded bob: tip (%.12f, %.12f), weight as a point force (%.12f, %.12f)\n", tw[0], tw[2], tl[0], tl[2]);
  EXPECT_GT(std::abs(tl[2]), 1e-3);  // a visible deflection
  EXPECT_NEAR(tw[0], tl[0], 1e-9);
  EXPECT_NEAR(tw[2], tl[2], 1e-9 * std::abs(tl[2]) + 1e-12);
}

// A rigid body welded to the tip with its centre of mass a = 0.1 m beyond it along the beam: the
// weld carries the body's weight W and its moment a x W into the beam. References: (1) the same
// cantilever with W and the moment (0, a m g, 0) applied as dead end loads (statics of a rigid
// attachment; the two differ only by the turn of the lever arm with the tip, O(theta^2) of the
// moment, theta = 0.017 rad here: a few 1e-7 m of tip); (2) linear beam theory at this small
// load, w = P L^3 / (3 EI) + M L^2 / (2 EI) (Euler-Bernoulli; shear adds P L / (kappa G A),
// 7e-7 m, and the large-deflection terms O(theta^2)), within 1 %. The node of the ancf beam
// carries no triad and such a weld is refused there (beam_elastica_test.cpp).
TEST(BeamGeometricallyExact, RigidBodyWeldedWithALeverArmLoadsTheTipWithItsWeightAndMoment) {
  const double m = 0.5, g = 9.81, arm = 0.1, L = 1, a = 0.01, EI = kE * a * a * a * a / 12;
  const std::string solver = R"({"analysis": "static"})";
  std::string welded = cantilever(L, a, 16, "", solver);
  welded.replace(welded.find("{\"bodies\""), 9, "{\"gravity\": [0, 0, -9.81], \"bodies\"");
  welded.replace(welded.find("}}],"), 4, R"(}}, {"name": "bob", "type": "rigid", "mass": 0.5, "com": [)" + num(L + arm) + R"(, 0, 0],
      "inertia": [[1e-4, 0, 0], [0, 2e-4, 0], [0, 0, 2e-4]]}],)");
  const std::string clamp = R"("node2": "start"})";
  welded.replace(welded.find(clamp), clamp.size(),
                 R"("node2": "start"}, {"name": "weld", "type": "fixed", "body1": "beam", "node1": "end", "body2": "bob"})");
  const std::string W = "[0, 0, " + num(-m * g) + "]", M = "[0, " + num(arm * m * g) + ", 0]";
  std::string loaded = cantilever(L, a, 16, R"({"name": "W", "type": "point_force", "body": "beam", "node": "end", "table": {"t": [0, 1], "value": [)" +
                                                W + ", " + W + R"(]}},
      {"name": "M", "type": "point_torque", "body": "beam", "node": "end", "table": {"t": [0, 1], "value": [)" + M + ", " + M + "]}}",
                                  solver);
  loaded.replace(loaded.find("{\"bodies\""), 9, "{\"gravity\": [0, 0, -9.81], \"bodies\"");
  const Model mw = test::model_from(welded), ml = test::model_from(loaded);
  Data dw(mw), dl(ml);
  initialize(mw, dw);
  initialize(ml, dl);
  const auto tw = test::output(mw, dw, "tip"), tl = test::output(ml, dl, "tip");
  // The beam's own weight adds w L^4 / (8 EI) (w = rho A g) to the linear tip deflection.
  const double P = m * g, Mo = arm * m * g, w = kRho * a * a * g;
  const double linear = P * L * L * L / (3 * EI) + Mo * L * L / (2 * EI) + w * L * L * L * L / (8 * EI);
  std::printf("welded bob with a %.2f m arm: tip (%.12f, %.12f); weight and moment as end loads (%.12f, %.12f); linear theory "
              "z = %.9f (%.3e relative)\n",
              arm, tw[0], tw[2], tl[0], tl[2], -linear, -tw[2] / linear - 1);
  EXPECT_GT(-tw[2], 5e-3);
  EXPECT_NEAR(tw[2], tl[2], 1e-6);
  EXPECT_NEAR(tw[0], tl[0], 1e-6);
  EXPECT_NEAR(-tw[2] / linear, 1.0, 1e-2);
}
