// A planar four-bar of four revolute joints modelled in 3-D: three of its twenty joint
// conditions are redundant (the out-of-plane ones of the closed loop), so Phi_q is
// rank-deficient and the multipliers are not unique. The augmented Lagrangian must run it
// without the user removing anything. Oracle: an independent one-degree-of-freedom model of
// the same mechanism (crank angle theta as the only coordinate, closed-form loop closure,
// Lagrange's equation m(theta) theta'' + m'(theta) theta'^2 / 2 = -V'(theta)) integrated with
// classical RK4 at a much smaller step.
#include "four_bar_oracle.hpp"
#include "support.hpp"

#include <Eigen/QR>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace ffr::runtime;

namespace {

// The mechanism (geometry, loop closure, bars, model file): tools/bench/formulations; its
// one-degree-of-freedom oracle: four_bar_oracle.hpp.
using namespace formulations::four_bar;
using formulations::num;
constexpr double th0 = kTheta0;

struct Outcome {
  double worst, violation, dE, E0;
  std::size_t notes;
};

std::string four_bar_json(double h) { return json(h, 1.0, "absolute"); }

Outcome run(double h) {
  const double T = 1.0;
  const Model model = test::model_from(four_bar_json(h));
  EXPECT_EQ(model.nconstraints, 3 * 6 + 4 * 5);
  Data data(model);
  const auto notes = initialize(model, data);
  for (const auto& n : notes) std::printf("note: %s\n", n.c_str());

  // Oracle: RK4 on the one-DOF equation.
  const std::vector<double> ref = test::four_bar_oracle::crank_angles(h, static_cast<int>(T / h));  // theta at every runtime step
  double worst = 0, worst_violation = 0;
  const double E0 = energy(model, data).total();
  double worst_dE = 0;
  for (std::size_t s = 0; s < ref.size(); ++s) {
    step(model, data);
    const double theta = th0 + joint_coordinate(model, data, 0, JointCoordinate::Angle);
    worst = std::max(worst, std::abs(theta - ref[s]));
    worst_violation = std::max(worst_violation, data.stats.last_violation);
    worst_dE = std::max(worst_dE, std::abs(energy(model, data).total() - E0));
  }
  std::printf("four-bar h = %g: theta(1 s) = %.9f (oracle %.9f), worst |dtheta| %.2e rad, violation %.2e, energy drift %.2e J of %.3f\n",
              h, th0 + joint_coordinate(model, data, 0, JointCoordinate::Angle), ref.back(), worst, worst_violation, worst_dE, E0);
  return {worst, worst_violation, worst_dE, E0, notes.size()};
}

}  // namespace

TEST(FourBar, RedundantRevolutesMatchOneDofModel) {
  const Outcome a = run(1e-3), b = run(5e-4);
  EXPECT_EQ(a.notes, 0u);  // consistent initial state given: nothing to adjust
  EXPECT_LT(b.worst, 1e-4);
  EXPECT_NEAR(a.worst / b.worst, 4.0, 0.6);  // second order
  EXPECT_LT(a.violation, 1e-11);
  EXPECT_LT(a.dE, 2e-4 * std::abs(a.E0));
}

// The exact multipliers (exact_multipliers.cpp: the projections' and Newton's fallback when their passes stall) with the
// three redundant rows: the correction Y mu it gives for a consistent right-hand side
// c = Phi_a v must be the one of the KKT system [T Phi_a^T; Phi_a 0] [dx; mu] = [0; c] (dx is
// unique although mu is not), solved independently by Eigen's complete orthogonal decomposition
// of the whole singular KKT matrix; and the three redundant rows must be the ones it leaves out.
TEST(FourBar, ExactMultipliersMatchTheKktSolutionWithRedundantRows) {
  const Model model = test::model_from(four_bar_json(1e-3));
  Data data(model);
  initialize(model, data);
  for (int i = 0; i < 10; ++i) step(model, data);
  refresh_tangent(model, data, data.state.t, data.state.lambda);
  const int nf = data.nf, na = data.na;
  ASSERT_TRUE(data.unknowns.empty());
  Eigen::VectorXd v(data.state.q.size());
  for (int i = 0; i < v.size(); ++i) v(i) = std::sin(1.0 + 0.7 * i);
  const Eigen::VectorXd c = data.Phiq.topLeftCorner(na, nf) * v.head(nf);
  const int rank = factor_exact_multipliers(data);
  solve_exact_multipliers(data, c);
  const Eigen::VectorXd dx = data.projY.topLeftCorner(nf, na) * data.proj_mu.head(na);

  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(nf + na, nf + na);
  kkt.topLeftCorner(nf, nf) = data.T.topLeftCorner(nf, nf);
  kkt.bottomLeftCorner(na, nf) = data.Phiq.topLeftCorner(na, nf);
  kkt.topRightCorner(nf, na) = data.Phiq.topLeftCorner(na, nf).transpose();
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(nf + na);
  rhs.tail(na) = c;
  const Eigen::VectorXd ref = kkt.completeOrthogonalDecomposition().solve(rhs);
  const double diff = (dx - ref.head(nf)).cwiseAbs().maxCoeff(), size = ref.head(nf).cwiseAbs().maxCoeff();
  const double residual = (data.Phiq.topLeftCorner(na, nf) * dx - c).cwiseAbs().maxCoeff();
  std::printf("exact multipliers: rank %d of %d rows; correction against the KKT solution %.3e (of %.3e); "
              "constraint residual %.3e (of %.3e)\n",
              rank, na, diff, size, residual, c.cwiseAbs().maxCoeff());
  EXPECT_EQ(rank, na - 3);
  EXPECT_LT(diff, 1e-9 * size);
  EXPECT_LT(residual, 1e-10 * c.cwiseAbs().maxCoeff());
}
