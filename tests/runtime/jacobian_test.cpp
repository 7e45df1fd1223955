// Analytic Jacobians against central finite differences: constraint Jacobian and acceleration
// bias (Phi_dd = Phi_q q_dd + gamma, Phi_d = Phi_q q_d + Phi_t), and the force tangents
// K = -dQ/dq, C = -dQ/dq_d, for every joint type, motion type and force element, on a flexible
// body with node rotations and rotary inertia and on a rigid body, at a generic state (off the
// constraint manifold on purpose: the derivatives must hold everywhere).
#include "central_differences.hpp"
#include "state_probe.hpp"
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

using namespace ffr::runtime;

namespace {

using test::central_differences;
using test::rel_err;

std::string model_json() {
  return R"({
  "gravity": [0.3, -1.0, -9.81],
  "bodies": [
    {"name": "flex", "type": "flexible", "sid": "lumpy.sid.h5", "position": [0.1, 0.2, 0.3],
     "orientation": [[0.36, 0.48, -0.8], [-0.8, 0.6, 0], [0.48, 0.64, 0.6]],
     "modal_coordinates": [0.01, -0.02, 0.015]},
    {"name": "link", "type": "rigid", "mass": 2.0, "com": [0.5, 0.1, 0.2],
     "inertia": [[0.02, 0.001, 0], [0.001, 0.03, 0.002], [0, 0.002, 0.025]], "position": [0.4, 0, 0.1]}
  ],
  "joints": [
    {"name": "j_rev", "type": "revolute", "body1": "ground", "body2": "flex", "node2": "A", "axis": [0, 0.6, 0.8]},
    {"name": "j_sph", "type": "spherical", "body1": "flex", "body2": "link", "node1": "B"},
    {"name": "j_uni", "type": "universal", "body1": "link", "body2": "ground", "at": [0.7, 0.1, 0.2], "axis1": [1, 0, 0], "axis2": [0, 0, 1]},
    {"name": "j_cyl", "type": "cylindrical", "body1": "flex", "body2": "link", "node1": "C", "axis": [0.2, 1, 0.1]},
    {"name": "j_pri", "type": "prismatic", "body1": "link", "body2": "ground", "at": [0.5, 0.2, 0.0], "axis": [1, 1, 0]},
    {"name": "j_fix", "type": "fixed", "body1": "ground", "body2": "flex", "at": [0.3, 0.3, 0.3], "axis": [0, 0, 1]},
    {"name": "j_rev2", "type": "revolute", "body1": "flex", "body2": "link", "node1": "C", "axis": [1, 0, 0]}
  ],
  "motions": [
    {"joint": "j_rev", "table": {"t": [0, 0.5, 1, 2], "value": [0, 0.3, 0.2, 1.0]}},
    {"joint": "j_pri", "table": {"t": [0, 1, 2], "value": [0, 0.1, -0.2]}},
    {"joint": "j_cyl", "coordinate": "displacement", "table": {"t": [0, 1, 2], "value": [0, 0.05, 0.02]}}
  ],
  "forces": [
    {"type": "spring_damper", "body1": "ground", "at1": [0, 0, 1], "body2": "flex", "node2": "B", "k": 300, "c": 4, "length0": 0.7},
    {"type": "spring_damper", "body1": "link", "at1": [0.6, 0, 0.1], "body2": "flex", "k": 100, "c": 2},
    {"type": "bushing", "body1": "flex", "node1": "C", "body2": "link", "stiffness": [100, 200, 300, 4, 5, 6], "damping": [1, 2, 3, 0.1, 0.2, 0.3]},
    {"type": "bushing", "body1": "ground", "at": [0.2, 0.1, 0], "body2": "link", "axes": [[0, 1, 0], [0, 0, 1], [1, 0, 0]], "stiffness": [10, 20, 30, 1, 2, 3], "damping": [1, 1, 1, 0.1, 0.1, 0.1]},
    {"type": "point_force", "body": "flex", "node": "B", "table": {"t": [0, 1], "value": [[1, 2, 3], [2, 0, -1]]}},
    {"type": "point_torque", "body": "flex", "node": "C", "table": {"t": [0, 1], "value": [[0.1, -0.2, 0.3], [0, 0, 0]]}},
    {"type": "point_force", "body": "link", "at": [0.5, 0.1, 0.1], "table": {"t": [0, 1], "value": [[0, 0, -5], [0, 0, -5]]}},
    {"type": "point_torque", "body": "link", "table": {"t": [0, 1], "value": [[0.5, 0, 0], [0.5, 0, 0]]}}
  ],
  "solver": {"end": 1.0, "step": 1e-3}
})";
}

struct Fixture : ::testing::Test, test::StateProbe {
  test::TempDir dir{"jac"};
  double t = 0.37;

  void SetUp() override {
    test::write_sid_file(test::lumpy_body(3), dir / "lumpy.sid.h5");
    start(test::model_from(model_json(), dir.path), 3);
    // External loads on a node and a frame origin too.
    set_external_load(*data, 0, 2, Eigen::Vector3d(0.5, -1, 2), Eigen::Vector3d(0.1, 0.2, -0.3));
    set_external_load(*data, 1, 0, Eigen::Vector3d::Zero(), Eigen::Vector3d(-0.2, 0.1, 0.4));
  }

  VectorXd forces(const VectorXd& a, const VectorXd& b) {
    set(a, b, qdd);
    generalized_forces(model, *data, t);
    return data->Q;
  }
};

}  // namespace

TEST_F(Fixture, ConstraintJacobianMatchesFiniteDifferences) {
  set(q, qd, qdd);
  evaluate_constraints(model, *data, t);
  const MatrixXd J = data->Phiq;  // the dense Jacobian the products use, assembled from the blocks
  const MatrixXd Jfd = central_differences([&](const VectorXd& z) { return constraints(z, t); }, q, 1e-6);
  std::printf("constraint Jacobian: relative error %.2e (%ld x %ld)\n", rel_err(J, Jfd), (long)J.rows(), (long)J.cols());
  EXPECT_LT(rel_err(J, Jfd), 1e-7);
}

TEST_F(Fixture, AccelerationBiasAndTimeDerivativesMatchFiniteDifferences) {
  // Along the path q(s) = q + s qd + s^2/2 qdd at time t + s.
  set(q, qd, qdd);
  evaluate_constraints(model, *data, t);
  const MatrixXd J = data->Phiq;
  const VectorXd Phit = data->Phit, gamma = data->gamma;
  const double eps = 1e-4;
  auto path = [&](double s) { return constraints(q + s * qd + 0.5 * s * s * qdd, t + s); };
  const VectorXd p0 = path(0), pp = path(eps), pm = path(-eps);
  const VectorXd d1 = (pp - pm) / (2 * eps), d2 = (pp - 2 * p0 + pm) / (eps * eps);
  std::printf("Phi_dot: %.2e, Phi_ddot: %.2e\n", rel_err(J * qd + Phit, d1), rel_err(J * qdd + gamma, d2));
  EXPECT_LT(rel_err(J * qd + Phit, d1), 1e-7);
  EXPECT_LT(rel_err(J * qdd + gamma, d2), 1e-5);  // second differences: eps^2 and round-off
}

TEST_F(Fixture, ForceTangentsMatchFiniteDifferences) {
  set(q, qd, qdd);
  generalized_forces(model, *data, t);
  force_tangents(model, *data, t);
  const MatrixXd K = data->K, C = data->C;
  const MatrixXd Kfd = -central_differences([&](const VectorXd& z) { return forces(z, qd); }, q, 1e-6);
  const MatrixXd Cfd = -central_differences([&](const VectorXd& zd) { return forces(q, zd); }, qd, 1e-6);
  std::printf("K: %.2e (max |K| %.2e), C: %.2e (max |C| %.2e)\n", rel_err(K, Kfd), K.cwiseAbs().maxCoeff(), rel_err(C, Cfd), C.cwiseAbs().maxCoeff());
  EXPECT_LT(rel_err(K, Kfd), 1e-6) << "worst K entry off by " << (K - Kfd).cwiseAbs().maxCoeff();
  EXPECT_LT(rel_err(C, Cfd), 1e-6) << "worst C entry off by " << (C - Cfd).cwiseAbs().maxCoeff();
}

TEST_F(Fixture, ConstraintHessianMatchesFiniteDifferences) {
  // d(Phi_q^T lambda)/dq for fixed lambda against central differences.
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  const VectorXd lam = VectorXd::NullaryExpr(model.nconstraints, [&](Eigen::Index) { return 10 * u(rng); });
  const Hessians hs = constraint_hessians(lam, t);
  const MatrixXd& H = hs.H;
  const MatrixXd& Hfd = hs.Hfd;
  std::printf("constraint Hessian: %.2e (max %.2e)\n", rel_err(H, Hfd), H.cwiseAbs().maxCoeff());
  EXPECT_LT(rel_err(H, Hfd), 1e-6);
}

TEST_F(Fixture, ModalAccelerationTangentMatchesFiniteDifferences) {
  // d(M(q) q_dd)/dy of the flexible body's modal rows at frozen q_dd (the term the Newton
  // tangent adds, FORMULATION.md 9), against central differences over its modal amplitudes.
  const Body& flex = model.bodies[0];
  const int o = flex.offset + 12, nq = flex.nq;
  ASSERT_GT(nq, 0);
  auto modal_inertia = [&](const VectorXd& y) {
    VectorXd z = q;
    z.segment(o, nq) = y;
    set(z, qd, qdd);
    mass_matrices(model, *data);
    VectorXd out = VectorXd::Zero(model.ncoord);
    mass_times(model, *data, qdd, out);
    return VectorXd(out.segment(o, nq));
  };
  set(q, qd, qdd);
  mass_matrices(model, *data);
  MatrixXd T = MatrixXd::Zero(model.ncoord, model.ncoord);
  add_modal_acceleration_tangent(model, *data, 1.0, T);
  const MatrixXd D = T.block(o, o, nq, nq);
  const MatrixXd Dfd = central_differences(modal_inertia, q.segment(o, nq), 1e-6);
  std::printf("modal acceleration tangent: %.2e (max %.2e)\n", rel_err(D, Dfd), Dfd.cwiseAbs().maxCoeff());
  EXPECT_GT(Dfd.cwiseAbs().maxCoeff(), 1e-3);  // the state makes the term matter
  EXPECT_LT(rel_err(D, Dfd), 1e-7);
  // Nothing outside the modal block (the rigid link has none).
  T.block(o, o, nq, nq).setZero();
  EXPECT_EQ(T.cwiseAbs().maxCoeff(), 0.0);
}
