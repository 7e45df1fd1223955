// The stiffness of a body's own modal stress (/sid/Ke/M1), prestress (/sid/ksigma) and the
// interface-load stiffening (FORMULATION.md 7): analytic tangents against central finite
// differences, the force against the gradient of the energy the runtime reports, energy
// conservation to the trapezoidal rule's order at large amplitude, the joint load that reaches an
// interface against statics, and refusal of a malformed Ke/M1.
#include "ffr/formats/h5.hpp"
#include "central_differences.hpp"
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>
#include <sys/wait.h>

using namespace ffr::runtime;

namespace {

using test::central_differences;

// A Ke/M1 of the stated convention (M1[k] symmetric, not symmetric in k), of size `scale`.
std::vector<Eigen::MatrixXd> random_ke_m1(int nq, double scale, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::MatrixXd> M1;
  for (int k = 0; k < nq; ++k) {
    Eigen::MatrixXd A = Eigen::MatrixXd::NullaryExpr(nq, nq, [&](Eigen::Index, Eigen::Index) { return u(rng); });
    M1.push_back(scale * (A + A.transpose()));
  }
  return M1;
}

ffr::formats::Sid stressed_body(bool prestress) {
  ffr::formats::Sid sid = test::lumpy_body(3);
  const double k = sid.Ke.cwiseAbs().maxCoeff();
  sid.KeM1 = random_ke_m1(3, 5 * k, 11);
  if (prestress) {
    sid.ksigma.M0 = Eigen::Vector3d(0.3, -0.2, 0.1) * k * 0.01;
    Eigen::Matrix3d S = Eigen::Matrix3d::Random();
    sid.ksigma.M1 = 0.1 * k * (S + S.transpose());
  }
  return sid;
}

const char* kFree = R"({
  "bodies": [{"name": "flex", "type": "flexible", "sid": "body.sid.h5", "position": [0.1, 0.2, 0.3],
              "orientation": [[0.36, 0.48, -0.8], [-0.8, 0.6, 0], [0.48, 0.64, 0.6]],
              "modal_coordinates": [0.05, -0.04, 0.03], "velocity": [0.1, 0, 0], "angular_velocity": [0, 0.5, 1]}],
  "solver": {"end": 0.2, "step": 1e-3}
})";

}  // namespace

// K = -dQ/dq of the Ke/M1 and ksigma terms: G1 + X1 + X1^T + K1 against central differences of Q,
// and Q_y against the gradient of the potential energy (the cubic strain energy and the
// prestress energy): the force is conservative and the tangent symmetric.
TEST(ModalStress, ForceTangentAndEnergyGradientMatchFiniteDifferences) {
  test::TempDir dir("modal_stress_fd");
  test::write_sid_file(stressed_body(true), dir / "body.sid.h5");
  const Model model = test::model_from(kFree, dir.path);
  ASSERT_TRUE(model.bodies[0].modal_stress.has_value());
  ASSERT_TRUE(model.bodies[0].prestress.has_value());
  Data data(model);
  const Eigen::VectorXd q = data.state.q, qd = Eigen::VectorXd::Zero(q.size());
  auto forces = [&](const Eigen::VectorXd& z) {
    data.state.q = z;
    data.state.qd = qd;
    update_bodies(model, data);
    update_markers(model, data);
    generalized_forces(model, data, 0);
    return Eigen::VectorXd(data.Q);
  };
  forces(q);
  force_tangents(model, data, 0);
  const Eigen::MatrixXd K = data.K;
  const Eigen::MatrixXd Kfd = -central_differences(forces, q, 1e-7);
  const double err = (K - Kfd).cwiseAbs().maxCoeff() / K.cwiseAbs().maxCoeff();
  const int o = model.bodies[0].offset;
  const auto Kyy = K.block(o + 12, o + 12, 3, 3);
  std::printf("Ke/M1 + ksigma tangent vs finite differences: %.2e of max |K| %.3e; asymmetry of K_yy %.2e\n", err,
              K.cwiseAbs().maxCoeff(), (Kyy - Kyy.transpose()).cwiseAbs().maxCoeff() / Kyy.cwiseAbs().maxCoeff());
  EXPECT_LT(err, 1e-7);
  EXPECT_LT((Kyy - Kyy.transpose()).cwiseAbs().maxCoeff(), 1e-12 * Kyy.cwiseAbs().maxCoeff());
  // Q_y = -dV/dy (no gravity, at rest: the inertia forces vanish).
  const Eigen::VectorXd Q = forces(q);
  Eigen::VectorXd y = q.segment(o + 12, 3);
  auto potential = [&](const Eigen::VectorXd& yy) {
    data.state.q = q;
    data.state.q.segment(o + 12, 3) = yy;
    Eigen::VectorXd v(1);
    v(0) = energy(model, data).potential;
    return v;
  };
  const Eigen::MatrixXd grad = central_differences(potential, y, 1e-7);
  const double gerr = (grad.transpose() + Q.segment(o + 12, 3)).cwiseAbs().maxCoeff() / Q.segment(o + 12, 3).cwiseAbs().maxCoeff();
  std::printf("Q_y vs -dV/dy: %.2e\n", gerr);
  EXPECT_LT(gerr, 1e-7);
}

// A free body about its mean axes vibrating at large amplitude (the cubic energy a sizeable part
// of the quadratic one) while it tumbles: the trapezoidal rule conserves the energy only to its
// O(h^2) error on a nonlinear system (FORMULATION.md 11), so the worst energy drift over the run
// must fall fourfold when h is halved.
TEST(ModalStress, FreeBodyWithKeM1ConservesEnergyToSecondOrder) {
  test::TempDir dir("modal_stress_energy");
  ffr::formats::Sid sid = test::mean_axis_body(3);
  sid.De.setZero();
  const double k = sid.Ke.cwiseAbs().maxCoeff();
  // The cubic energy is unbounded below: this size keeps the motion (energy) well inside its
  // well (twice as large, the body ran over the saddle and away).
  sid.KeM1 = random_ke_m1(3, 0.3 * k, 5);
  test::write_sid_file(sid, dir / "body.sid.h5");
  const double w_max = std::sqrt(sid.Ke.diagonal().maxCoeff() / sid.Me.diagonal().minCoeff());
  std::vector<double> drift;
  double cubic_share = 0;
  for (const double h : {0.04 / w_max, 0.02 / w_max, 0.01 / w_max}) {
    char json[1024];
    std::snprintf(json, sizeof json, R"({
  "bodies": [{"name": "flex", "type": "flexible", "sid": "body.sid.h5", "modal_coordinates": [0.05, -0.04, 0.03],
              "angular_velocity": [0, 0.2, 0.4]}],
  "solver": {"end": %.17g, "step": %.17g}
})", 400 * 0.04 / w_max, h);
    const Model model = test::model_from(json, dir.path);
    Data data(model);
    initialize(model, data);
    const int o = model.bodies[0].offset;
    {
      const Eigen::VectorXd y = data.state.q.segment(o + 12, 3);
      double cubic = 0;
      for (int m = 0; m < 3; ++m) cubic += 0.5 * y(m) * y.dot(sid.KeM1[static_cast<std::size_t>(m)] * y);
      cubic_share = std::abs(cubic) / (0.5 * y.dot(sid.Ke * y));
    }
    const Energy e0 = energy(model, data);
    const double E0 = e0.kinetic + e0.potential;
    double worst = 0;
    for (std::int64_t i = 0; i < step_count(model); ++i) {
      step(model, data);
      const Energy e = energy(model, data);
      worst = std::max(worst, std::abs(e.kinetic + e.potential - E0));
    }
    drift.push_back(worst / std::abs(E0));
  }
  std::printf("cubic / quadratic strain energy at the start %.2f; energy drift %.3e, %.3e, %.3e (ratios %.2f, %.2f)\n",
              cubic_share, drift[0], drift[1], drift[2], drift[0] / drift[1], drift[1] / drift[2]);
  EXPECT_GT(cubic_share, 0.1);
  EXPECT_NEAR(drift[0] / drift[1], 4, 0.8);
  EXPECT_NEAR(drift[1] / drift[2], 4, 0.8);
}

// A flexible body held at its interface node by a fixed joint, in gravity, its vibration damped
// out: by statics the joint carries the weight, so the load that reaches the interface is
// F = -m g and the moment about the node M = -(r_G - r_node) x m g (resolved in K).
TEST(ModalStress, InterfaceLoadIsTheStaticJointReaction) {
  test::TempDir dir("iface_load");
  ffr::formats::Sid sid = test::lumpy_body(3);
  sid.stiffening.emplace();
  sid.stiffening->K0t.assign(3, ffr::formats::MatX3::Zero(3, 3));
  sid.stiffening->K0r.assign(3, ffr::formats::MatX3::Zero(3, 3));
  sid.stiffening->K0om.assign(3, ffr::formats::MatX6::Zero(3, 6));
  ffr::formats::Stiffening::Interface itf;
  itf.name = "A";
  itf.K0F.assign(3, ffr::formats::MatX3::Zero(3, 3));
  itf.K0M.assign(3, ffr::formats::MatX3::Zero(3, 3));
  sid.stiffening->interfaces.push_back(itf);
  test::write_sid_file(sid, dir / "body.sid.h5");
  const Model model = test::model_from(R"({
  "gravity": [0, 0, -9.81],
  "bodies": [{"name": "flex", "type": "flexible", "sid": "body.sid.h5", "damping": {"ratio": 0.7},
              "orientation": [[0.36, 0.48, -0.8], [-0.8, 0.6, 0], [0.48, 0.64, 0.6]]}],
  "joints": [{"name": "clamp", "type": "fixed", "body1": "ground", "body2": "flex", "node2": "A", "axis": [0, 0, 1]}],
  "solver": {"end": 4.0, "step": 1e-3}
})", dir.path);
  ASSERT_EQ(model.bodies[0].stiffening->interfaces.size(), 1u);
  Data data(model);
  initialize(model, data);
  for (std::int64_t i = 0; i < step_count(model); ++i) step(model, data);
  generalized_forces(model, data, data.state.t);
  const Body& b = model.bodies[0];
  const BodyData& bd = data.bodies[0];
  const Eigen::Vector3d g(0, 0, -9.81);
  const Eigen::Vector3d r0 = data.state.q.segment<3>(b.offset);
  const int node = b.find_node("A");
  const NodeSlice& n = b.nodes[static_cast<std::size_t>(node)];
  const Eigen::Vector3d r_node = r0 + bd.A * (n.origin + n.phi * data.state.q.segment(b.offset + 12, b.nq));
  const Eigen::Vector3d r_G = r0 + bd.A * bd.md / b.mass;
  const Eigen::Vector3d F = bd.A.transpose() * (-b.mass * g);
  const Eigen::Vector3d M = bd.A.transpose() * (-(r_G - r_node).cross(b.mass * g));
  const Eigen::Vector3d FK = bd.iface_load.col(0).head<3>(), MK = bd.iface_load.col(0).tail<3>();
  std::printf("interface force in K (%.6f, %.6f, %.6f), statics (%.6f, %.6f, %.6f); moment (%.6f, %.6f, %.6f), statics (%.6f, %.6f, %.6f); modal velocity %.1e\n",
              FK(0), FK(1), FK(2), F(0), F(1), F(2), MK(0), MK(1), MK(2), M(0), M(1), M(2),
              data.state.qd.segment(b.offset + 12, b.nq).norm());
  EXPECT_LT((FK - F).norm(), 1e-6 * F.norm());
  EXPECT_LT((MK - M).norm(), 1e-6 * F.norm() * (r_G - r_node).norm());
}

// A Ke/M1 slice that is not symmetric in (i, j) is refused when the model is loaded, naming the
// SID file and the dataset; ffr-sim exits with status 2.
TEST(ModalStress, AsymmetricKeM1IsRefused) {
  test::TempDir dir("modal_stress_bad");
  ffr::formats::Sid sid = stressed_body(false);
  sid.KeM1[1](0, 2) += 0.1 * sid.KeM1[1].cwiseAbs().maxCoeff();
  test::write_sid_file(sid, dir / "body.sid.h5");
  try {
    test::model_from(kFree, dir.path);
    FAIL() << "accepted an asymmetric Ke/M1";
  } catch (const ModelError& e) {
    const std::string what = e.what();
    std::printf("%s\n", what.c_str());
    EXPECT_NE(what.find("body.sid.h5"), std::string::npos);
    EXPECT_NE(what.find("/sid/Ke/M1"), std::string::npos);
    EXPECT_NE(what.find("symmetric"), std::string::npos);
  }
  test::write_text(dir / "model.json", kFree);
  const test::SimRun run = test::run_ffr_sim((dir / "model.json").string() + " -o " + (dir / "out.h5").string());
  const std::string& out = run.output;
  EXPECT_EQ(run.status, 2) << out;
  EXPECT_NE(out.find("/sid/Ke/M1"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
}

// A Ke/M1 of the wrong shape ([3,3,2] for nq = 3, written past the formats writer, which refuses
// it) is refused by ffr-sim with exit status 2, naming the SID file and the dataset.
TEST(ModalStress, WrongShapeKeM1IsRefused) {
  test::TempDir dir("modal_stress_shape");
  test::write_sid_file(stressed_body(false), dir / "body.sid.h5");
  {
    const hid_t f = H5Fopen((dir / "body.sid.h5").c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(f, 0);
    ASSERT_GE(H5Ldelete(f, "/sid/Ke/M1", H5P_DEFAULT), 0);
    const hsize_t dims[3] = {3, 3, 2};
    const hid_t space = H5Screate_simple(3, dims, nullptr);
    const hid_t ds = H5Dcreate2(f, "/sid/Ke/M1", H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    const std::vector<double> zeros(18, 0.0);
    H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, zeros.data());
    H5Dclose(ds);
    H5Sclose(space);
    H5Fclose(f);
  }
  test::write_text(dir / "model.json", kFree);
  const test::SimRun run = test::run_ffr_sim((dir / "model.json").string() + " -o " + (dir / "out.h5").string());
  const std::string& out = run.output;
  std::printf("%s", out.c_str());
  EXPECT_EQ(run.status, 2) << out;
  EXPECT_NE(out.find("body.sid.h5"), std::string::npos) << out;
  EXPECT_NE(out.find("/sid/Ke/M1"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
}

// The load-case stiffening -KG y depends on the frame's acceleration, angular acceleration and
// spin (FORMULATION.md 7); the step's tangent carries -dQ_y/dq_dd and -dQ_y/dq_d
// (body_stiffening_rate_tangents) against central differences of Q over q_dd and q_d.
TEST(ModalStress, StiffeningRateTangentsMatchFiniteDifferences) {
  test::TempDir dir("stiffening_rates_fd");
  ffr::formats::synthetic::ChainParams p;
  p.points = 6;
  p.length = 1.0;
  p.mass = 1.0;
  p.EA = 1e4;
  p.EIy = p.EIz = 20.0;
  p.modes = 5;
  p.clamped = true;  // a free chain's inertial cases vanish (all inertia relief)
  p.stiffening = true;
  test::write_sid_file(ffr::formats::synthetic::spring_chain(p).sid, dir / "body.sid.h5");
  const Model clamped = test::model_from(R"({
  "bodies": [{"name": "flex", "type": "flexible", "sid": "body.sid.h5", "stiffening": true, "position": [0.1, 0.2, 0.3],
              "orientation": [[0.36, 0.48, -0.8], [-0.8, 0.6, 0], [0.48, 0.64, 0.6]],
              "modal_coordinates": [0.05, -0.04, 0.03, 0.02, -0.01], "angular_velocity": [0, 0.5, 1]}],
  "joints": [{"name": "hinge", "type": "revolute", "body1": "ground", "body2": "flex", "node2": "A", "axis": [0, 0, 1]}],
  "gravity": [0, 0, -9.81], "solver": {"end": 0.2, "step": 1e-3}
})",
                                       dir.path);
  // The frame's spin (a clamped body), and the body's mean spin (what a Craig-Bampton body uses).
  for (const bool mean_spin : {false, true}) {
  Model model = clamped;
  model.bodies[0].stiffening->use_mean_spin = mean_spin;
  const Body& b = model.bodies[0];
  ASSERT_TRUE(b.stiffening.has_value());
  Data data(model);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  const Eigen::VectorXd q = data.state.q;
  const Eigen::VectorXd qd = Eigen::VectorXd::NullaryExpr(q.size(), [&](Eigen::Index) { return u(rng); });
  const Eigen::VectorXd qdd = Eigen::VectorXd::NullaryExpr(q.size(), [&](Eigen::Index) { return 30 * u(rng); });
  const int o = b.offset, nq = b.nq, nb = b.ncoord();
  auto forces = [&](const Eigen::VectorXd& v, const Eigen::VectorXd& a) {
    data.state.q = q;
    data.state.qd = v;
    data.state.qdd = a;
    update_bodies(model, data);
    update_markers(model, data);
    generalized_forces(model, data, 0);
    return Eigen::VectorXd(data.Q.segment(o + 12, nq));
  };
  forces(qd, qdd);
  force_tangents(model, data, 0);
  Eigen::MatrixXd Wm = Eigen::MatrixXd::Zero(nb, nb), Wc = Eigen::MatrixXd::Zero(nb, nb);
  body_stiffening_rate_tangents(b, data.bodies[0], q.segment(o + 12, nq), qd.segment(o + 12, nq), 0.0, Wm);  // the q_dd part
  body_stiffening_rate_tangents(b, data.bodies[0], q.segment(o + 12, nq), qd.segment(o + 12, nq), 1.0, Wc);
  Wc -= Wm;  // the q_d part
  const Eigen::MatrixXd C = data.C.block(o + 12, o, nq, nb) + Wc.bottomRows(nq);
  // Q is linear in q_dd and quadratic in q_d: central differences are exact up to round-off for
  // any step, so a large one keeps the round-off of Q (its large Ke y) out.
  const Eigen::MatrixXd Mfd = -central_differences([&](const Eigen::VectorXd& a) { return forces(qd, a); }, qdd, 0.1);
  const Eigen::MatrixXd Cfd = -central_differences([&](const Eigen::VectorXd& v) { return forces(v, qdd); }, qd, 0.1);
  const double em = (Wm.bottomRows(nq) - Mfd.middleCols(o, nb)).cwiseAbs().maxCoeff() / Mfd.cwiseAbs().maxCoeff();
  const double ec = (C - Cfd.middleCols(o, nb)).cwiseAbs().maxCoeff() / Cfd.cwiseAbs().maxCoeff();
  std::printf("stiffening (%s spin): -dQ_y/dq_dd %.2e of max %.3e, -dQ_y/dq_d (with the inertia forces') %.2e of max %.3e\n",
              mean_spin ? "mean" : "frame", em,
              Mfd.cwiseAbs().maxCoeff(), ec, Cfd.cwiseAbs().maxCoeff());
  EXPECT_GT(Mfd.cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_LT(em, 1e-9);
  EXPECT_LT(ec, 1e-9);
  }
}
