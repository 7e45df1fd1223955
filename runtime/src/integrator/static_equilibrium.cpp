// Static equilibrium (FORMULATION.md section 14).
//
// Newton's method on the equilibrium and the constraints together (the Karush-Kuhn-Tucker
// system of the potential's stationary point on the constraint manifold):
//   [K + H   Phi_q^T] [dq]   [Q - Phi_q^T lambda]
//   [Phi_q   -d I   ] [dl] = [-Phi              ],   q += dq, lambda += dl,
// with K = -dQ/dq at zero velocities and accelerations and H = sum lambda_i Phi_i,qq. Solved
// directly (not by the step's augmented-Lagrangian passes): a static tangent has no mass to set
// the penalty's scale against, and a penalty chosen against the stiffest modes leaves the
// multiplier passes crawling on the soft ones. The small -d I (relative to the equilibrated
// matrix) keeps redundant constraints (a closed planar loop) solvable; Newton's residual corrects
// what it leaves. Every body is an unknown here, the driven ones held by their joints and
// motions at the start time.
#include "ffr/runtime/statics.hpp"

#include "ffr/runtime/constraints.hpp"
#include "ffr/runtime/dynamics.hpp"
#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/integrator.hpp"

#include <Eigen/Dense>
#include <Eigen/SVD>

#include <cmath>
#include <cstdio>

namespace ffr::runtime {
namespace {

constexpr int kMaxIterations = 100;
// Largest Newton correction taken at once, in model lengths (scaled_norm): far from the
// equilibrium the linearisation of the frame vectors' constraints is poor.
constexpr double kMaxCorrection = 0.2;
// The reduced stiffness, Jacobi-scaled (unit diagonal), is singular below this eigenvalue.
constexpr double kSingular = 1e-9;

std::string fmt(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", v);
  return b;
}

// The coordinate with the largest weighted entry of v, as "body 'name', what".
std::string coordinate_name(const Model& model, const VectorXd& v) {
  Eigen::Index j = 0;
  v.cwiseAbs().cwiseProduct(model.increment_weight).maxCoeff(&j);
  for (const Body& b : model.bodies) {
    if (j < b.offset || j >= b.offset + b.ncoord()) continue;
    const int k = static_cast<int>(j) - b.offset;
    const std::string what = k < 3 ? std::string("its position along ") + "xyz"[k]
                             : k < 12 ? std::string("its rotation (frame vector ") + "uvw"[(k - 3) / 3] + ")"
                             : b.beam ? "its " + beam_coordinate_name(k - 12)
                                      : "its modal coordinate " + std::to_string(k - 12);
    return "body '" + b.name + "', " + what;
  }
  return "coordinate " + std::to_string(j);
}

// K + H at the current state (every body an unknown) into T.
void static_tangent(const Model& model, Data& data, double t, MatrixXd& T) {
  force_tangents(model, data, t);
  T = data.K;
  add_constraint_hessian(model, data, data.state.lambda, 1.0, T);
}

// Refuses an equilibrium whose stiffness on the motions the constraints leave free is not
// positive definite.
void check_stability(const Model& model, const Data& data, const MatrixXd& T, double t) {
  const int n = model.ncoord;
  const MatrixXd J = data.Phiq.topRows(model.nconstraints);
  MatrixXd N;
  if (J.rows() == 0) {
    N = MatrixXd::Identity(n, n);
  } else {
    Eigen::BDCSVD<MatrixXd> svd(J, Eigen::ComputeFullV);
    const auto& s = svd.singularValues();
    const double smax = s.size() ? s(0) : 0.0;
    int rank = 0;
    for (Eigen::Index i = 0; i < s.size(); ++i)
      if (s(i) > 1e-10 * smax) ++rank;
    N = svd.matrixV().rightCols(n - rank);
  }
  if (N.cols() == 0) return;  // nothing free to move
  const MatrixXd S = 0.5 * (T + T.transpose());
  MatrixXd R = N.transpose() * S * N;
  // Jacobi scaling: unit diagonal where the stiffness is positive; a direction with none
  // (or a negative one) is already the answer.
  VectorXd d(R.rows());
  for (Eigen::Index i = 0; i < R.rows(); ++i) d(i) = R(i, i) > 0 ? 1.0 / std::sqrt(R(i, i)) : 1.0;
  R = d.asDiagonal() * R * d.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(R);
  const double lo = eig.eigenvalues()(0);
  if (lo > kSingular) return;
  const VectorXd mode = N * (d.asDiagonal() * eig.eigenvectors().col(0));
  const std::string who = coordinate_name(model, mode);
  if (lo < -kSingular)
    throw SolverError(t, lo,
                      "static equilibrium at t = " + fmt(t) + " s: the equilibrium found is unstable (the stiffness on the motions "
                      "the joints allow is indefinite; the motion that lowers the potential moves " + who +
                      "): start the model closer to the stable equilibrium (e.g. a pendulum hanging, not upright), or run "
                      "it dynamically with damping");
  throw SolverError(t, lo,
                    "static equilibrium at t = " + fmt(t) + " s: the model has no stable equilibrium: a motion the joints allow "
                    "meets no stiffness (it moves " + who + "); hold it with a joint, a motion, a spring or a bushing, or run "
                    "the model dynamically (remove \"analysis\": \"static\" / \"initial_equilibrium\")");
}

}  // namespace

std::vector<std::string> settle_statically(const Model& model, Data& data) {
  const double t = data.state.t;
  const int n = model.ncoord, m = model.nconstraints;
  set_unknowns(model, data, false);  // every body an unknown, every row active
  data.state.qd.setZero();
  data.state.qdd.setZero();
  // The multipliers of the initial conditions start Newton (near an equilibrium they are nearly
  // the static ones); where those could not be computed (a body without inertia about an axis a
  // force element holds) from zero.
  if (!data.state.lambda.allFinite()) data.state.lambda.setZero();
  const VectorXd q_start = data.state.q;
  MatrixXd T(n, n), A(n + m, n + m);
  VectorXd rhs(n + m), x(n + m), scale(n + m);
  double inc = 0, viol = 0;
  int it = 0;
  bool converged = false;
  for (it = 1; it <= kMaxIterations; ++it) {
    evaluate(model, data, t);
    viol = m ? data.Phi.cwiseAbs().maxCoeff() / model.length : 0.0;
    static_tangent(model, data, t, T);
    rhs.head(n) = data.Q;
    rhs.head(n).noalias() -= data.Phiq.transpose() * data.state.lambda;
    rhs.tail(m) = -data.Phi;
    A.topLeftCorner(n, n) = T;
    A.topRightCorner(n, m) = data.Phiq.transpose();
    A.bottomLeftCorner(m, n) = data.Phiq;
    A.bottomRightCorner(m, m).setZero();
    // Equilibration by the rows' largest entries (the matrix mixes stiffnesses, lengths and
    // dimensionless rows), then the small regularisation of the multipliers' block.
    for (int i = 0; i < n + m; ++i) {
      const double r = A.row(i).cwiseAbs().maxCoeff();
      scale(i) = r > 0 ? 1.0 / std::sqrt(r) : 1.0;
    }
    A = scale.asDiagonal() * A * scale.asDiagonal();
    A.bottomRightCorner(m, m).diagonal().setConstant(-1e-12);
    x = A.partialPivLu().solve(VectorXd(scale.cwiseProduct(rhs)));
    x = scale.cwiseProduct(x);
    inc = scaled_norm(model, x.head(n));
    if (!std::isfinite(inc)) break;
    const double damp = inc > kMaxCorrection ? kMaxCorrection / inc : 1.0;
    data.state.q += damp * x.head(n);
    data.state.lambda += damp * x.tail(m);
    if (damp == 1.0 && inc < model.settings.newton_tolerance && viol < model.settings.tolerance) {
      converged = true;
      break;
    }
  }
  if (!converged && !std::isfinite(inc))
    throw SolverError(t, inc,
                      "static equilibrium at t = " + fmt(t) + " s: the equilibrium equations are singular at iteration " +
                          std::to_string(it) + ": the loads move a body that nothing holds (no joint, spring or bushing "
                          "resists them; a free body under gravity); hold it, or run the model dynamically");
  if (!converged) {
    throw SolverError(t, inc,
                      "static equilibrium at t = " + fmt(t) + " s: Newton did not converge in " + std::to_string(kMaxIterations) +
                          " iterations (last correction " + fmt(inc) + " of the model length, largest in " +
                          coordinate_name(model, x.head(n)) + "; constraint violation " + fmt(viol) +
                          "): the model may have no equilibrium near its initial configuration (a body free to move under "
                          "the loads, or loads beyond what its springs can carry); hold the free motion with a joint or a "
                          "spring, start it closer to equilibrium, or run it dynamically with damping");
  }
  evaluate(model, data, t);
  static_tangent(model, data, t, T);
  check_stability(model, data, T, t);
  const VectorXd moved = data.state.q - q_start;
  double largest = 0;
  for (const Body& b : model.bodies) largest = std::max(largest, moved.segment<3>(b.offset).norm());
  return {"static equilibrium reached in " + std::to_string(it) + " Newton iterations (largest frame displacement " + fmt(largest) +
          " m; " + coordinate_name(model, moved) + " moved most)"};
}

}  // namespace ffr::runtime
