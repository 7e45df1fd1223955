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
// motions at the start time. Motions that meet no stiffness (a vehicle's rolling on its tyres)
// get a proximal stiffness in each step and are accepted when no force drives them
// (FORMULATION.md 14, neutral motions).
#include "ffr/runtime/statics.hpp"

#include "ffr/runtime/beam.hpp"
#include "ffr/runtime/constraints.hpp"
#include "ffr/runtime/dynamics.hpp"
#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/integrator.hpp"
#include "../number_text.hpp"

#include <Eigen/Dense>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace ffr::runtime {
namespace {

constexpr int kMaxIterations = 100;
// Newton iterations of one load step (load stepping, settle_statically).
constexpr int kStepIterations = 30;
// Largest Newton correction taken at once, in model lengths (scaled_norm): far from the
// equilibrium the linearisation of the frame vectors' constraints is poor.
constexpr double kMaxCorrection = 0.2;
// The reduced stiffness, Jacobi-scaled (unit diagonal), is singular below this eigenvalue.
constexpr double kSingular = 1e-9;

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
                             : b.plate ? "its " + plate_coordinate_name(*b.plate, k - 12)
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

// The stiffness on the motions the constraints leave free (the tangent reduced to the null space
// of Phi_q), analysed for its neutral directions (FORMULATION.md section 14).
struct Reduced {
  double lo = 1.0;        // the smallest eigenvalue of the Jacobi-scaled reduced stiffness
  VectorXd lo_mode;       // its motion in the coordinates
  MatrixXd Z;             // the neutral motions (|eigenvalue| <= kSingular), weighted coordinates, orthonormal
  double kappa = 0;       // the model's stiffness scale, weighted coordinates
};

// The weights of the coordinates y = W q: increment_weight (fractions of the model length),
// floored at 1e-3 of the largest (a frame vector of a body without extent along it has weight 0).
VectorXd weights(const Model& model) {
  const VectorXd& w = model.increment_weight;
  const double top = w.size() ? w.maxCoeff() : 1.0;
  return w.cwiseMax(1e-3 * top);
}

Reduced reduce(const Model& model, const Data& data, const MatrixXd& T) {
  const int n = model.ncoord;
  Reduced out;
  // Weighted coordinates y = W q (W = increment_weight: fractions of the model length), where
  // the coordinates' stiffnesses compare.
  const VectorXd w = weights(model);
  const VectorXd wi = w.cwiseInverse();
  const MatrixXd J = data.Phiq.topRows(model.nconstraints);
  MatrixXd N;
  if (J.rows() == 0) {
    N = MatrixXd::Identity(n, n);
  } else {
    // The null space from Phi_q in the coordinates (its rank decided there, where the rows
    // are scaled), then carried to y and made orthonormal there.
    Eigen::BDCSVD<MatrixXd> svd(J, Eigen::ComputeFullV);
    const auto& s = svd.singularValues();
    const double smax = s.size() ? s(0) : 0.0;
    int rank = 0;
    for (Eigen::Index i = 0; i < s.size(); ++i)
      if (s(i) > 1e-10 * smax) ++rank;
    const MatrixXd Nw = w.asDiagonal() * svd.matrixV().rightCols(n - rank);
    Eigen::HouseholderQR<MatrixXd> qr(Nw);
    N = qr.householderQ() * MatrixXd::Identity(n, Nw.cols());
  }
  const MatrixXd S = wi.asDiagonal() * (0.5 * (T + T.transpose())) * wi.asDiagonal();
  // The load scale: the largest generalised applied force in y (a force times the model length),
  // i.e. the stiffness that moves a model length under it; stiffnesses far below it are round-off.
  const double load = (wi.asDiagonal() * data.Q).cwiseAbs().maxCoeff();
  // The stiffness scale kappa: the median of the positive diagonal stiffnesses in y (the load
  // scale where there are none).
  std::vector<double> diag;
  for (int i = 0; i < n; ++i)
    if (S(i, i) > kSingular * load) diag.push_back(S(i, i));
  out.kappa = load > 0 ? load : 1.0;
  if (!diag.empty()) {
    std::nth_element(diag.begin(), diag.begin() + static_cast<std::ptrdiff_t>(diag.size() / 2), diag.end());
    out.kappa = diag[diag.size() / 2];
  }
  if (N.cols() == 0) return out;  // nothing free to move
  MatrixXd R = N.transpose() * S * N;
  // Jacobi scaling: unit diagonal where the stiffness is positive, so a soft spring beside a
  // stiff one is not mistaken for none; a diagonal below kSingular times the largest or the load
  // scale (round-off of a motion that meets no stiffness) is scaled by that reference instead,
  // which keeps it below kSingular.
  const double ref = std::max(R.diagonal().maxCoeff(), load);
  VectorXd d(R.rows());
  for (Eigen::Index i = 0; i < R.rows(); ++i) {
    const double r = R(i, i) > kSingular * ref ? R(i, i) : ref;
    d(i) = r > 0 ? 1.0 / std::sqrt(r) : 1.0;
  }
  R = d.asDiagonal() * R * d.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<MatrixXd> eig(R);
  out.lo = eig.eigenvalues()(0);
  out.lo_mode = wi.cwiseProduct(N * (d.asDiagonal() * eig.eigenvectors().col(0)));
  std::vector<Eigen::Index> zero;
  for (Eigen::Index i = 0; i < R.rows(); ++i)
    if (std::abs(eig.eigenvalues()(i)) <= kSingular) zero.push_back(i);
  if (!zero.empty()) {
    MatrixXd V(R.rows(), static_cast<Eigen::Index>(zero.size()));
    for (std::size_t j = 0; j < zero.size(); ++j) V.col(static_cast<Eigen::Index>(j)) = eig.eigenvectors().col(zero[j]);
    const Eigen::Index k = V.cols();
    const MatrixXd Zw = N * (d.asDiagonal() * V);
    Eigen::HouseholderQR<MatrixXd> qr(Zw);
    out.Z = qr.householderQ() * MatrixXd::Identity(n, k);
  }
  return out;
}

// The neutral part of a correction dq (its projection on the neutral motions, weighted metric).
VectorXd neutral_part(const Model& model, const Reduced& r, const VectorXd& dq) {
  if (r.Z.cols() == 0) return VectorXd::Zero(dq.size());
  const VectorXd w = weights(model);
  return (r.Z * (r.Z.transpose() * w.cwiseProduct(dq))).cwiseQuotient(w);
}

// The names of the neutral motions (each by its largest coordinate), without repeats.
std::string neutral_names(const Model& model, const Reduced& r) {
  std::vector<std::string> names;
  for (Eigen::Index k = 0; k < r.Z.cols(); ++k) {
    const std::string nm = coordinate_name(model, VectorXd(r.Z.col(k).cwiseQuotient(weights(model))));
    if (std::find(names.begin(), names.end(), nm) == names.end()) names.push_back(nm);
  }
  std::string s;
  for (std::size_t i = 0; i < names.size(); ++i) s += (i ? "; " : "") + names[i];
  return s;
}

[[noreturn]] void refuse_driven_neutral(const Model& model, double t, const VectorXd& step, double size) {
  const std::string what =
      model.tires.empty()
          ? "hold that motion (a motion locking a wheel's joint, a brake, a joint, a spring or a bushing) or run the model "
            "dynamically"
          : "a tyre holds nothing along the road or sideways at rest (its horizontal forces come from the sliding "
            "velocity: a vehicle parked on an incline creeps, locked wheels or not), so settle the vehicle on a flat "
            "road, hold that motion with a joint, a spring or a bushing, or run the model dynamically";
  throw SolverError(t, size,
                    "static equilibrium at t = " + fmt(t) + " s: the stiffness is singular along a motion the joints allow, and "
                    "a force remains along it: nothing holds " + coordinate_name(model, step) + " against the loads (a wheel "
                    "free to roll on an incline, a body free to slide or fall); " + what);
}

// Refuses an equilibrium whose stiffness on the motions the constraints leave free is indefinite;
// neutral motions (no stiffness) are accepted when no force remains along them.
void check_stability(const Model& model, const Reduced& r, double t) {
  if (r.lo >= -kSingular) return;
  const std::string who = coordinate_name(model, r.lo_mode);
  throw SolverError(t, r.lo,
                    "static equilibrium at t = " + fmt(t) + " s: the equilibrium found is unstable (the stiffness on the motions "
                    "the joints allow is indefinite; the motion that lowers the potential moves " + who +
                    "): start the model closer to the stable equilibrium (e.g. a pendulum hanging, not upright), or run "
                    "it dynamically with damping");
}

// Newton from the current state at the model's full loads; `unconverged` is set when it throws
// because Newton did not converge (rather than for a refusal that load stepping cannot cure).
std::vector<std::string> settle_at(const Model& model, Data& data, bool& unconverged, int max_iterations = kMaxIterations) {
  unconverged = false;
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
  const VectorXd w = weights(model);
  MatrixXd T(n, n), A(n + m, n + m);
  VectorXd rhs(n + m), x(n + m), scale(n + m), neutral(n);
  Reduced red;
  double inc = 0, viol = 0;
  int it = 0, driven = 0;
  bool converged = false;
  for (it = 1; it <= max_iterations; ++it) {
    evaluate(model, data, t);
    viol = m ? data.Phi.cwiseAbs().maxCoeff() / model.length : 0.0;
    static_tangent(model, data, t, T);
    red = reduce(model, data, T);
    // The neutral motions get the model's stiffness scale kappa (in the weighted coordinates
    // y = w q: T += W Z kappa Z^T W): the KKT matrix is regular, and the correction along them is
    // the force along them over kappa, zero where no force remains. A proximal term only: the
    // equations solved (the residual) are unchanged.
    if (red.Z.cols() > 0) {
      const MatrixXd WZ = w.asDiagonal() * red.Z;
      T.noalias() += red.kappa * WZ * WZ.transpose();
    }
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
    neutral = neutral_part(model, red, x.head(n));
    const double inc_neutral = scaled_norm(model, neutral);
    const double inc_stiff = scaled_norm(model, VectorXd(x.head(n) - neutral));
    // Everything else settled while a neutral motion keeps moving under its force: the loads
    // drive a motion nothing holds (a wheel rolling down an incline). A few such iterations in
    // a row tell it from a start off the road (a wheel above it: its fall is neutral until the
    // tyre touches).
    driven = (inc_stiff < model.settings.newton_tolerance && viol < model.settings.tolerance &&
              inc_neutral >= model.settings.newton_tolerance) ? driven + 1 : 0;
    if (driven >= 3) refuse_driven_neutral(model, t, neutral, inc_neutral);
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
    // The last corrections mostly along a neutral motion: the loads drive it.
    if (scaled_norm(model, neutral) > 0.5 * inc) refuse_driven_neutral(model, t, neutral, inc);
    unconverged = true;
    throw SolverError(t, inc,
                      "static equilibrium at t = " + fmt(t) + " s: Newton did not converge in " + std::to_string(max_iterations) +
                          " iterations (last correction " + fmt(inc) + " of the model length, largest in " +
                          coordinate_name(model, x.head(n)) + "; constraint violation " + fmt(viol) +
                          "). " + ge_beam_failure_hint(model, q_start, data.state.q) +
                          "The model may have no equilibrium near its initial configuration (a body free to move under "
                          "the loads, or loads beyond what its springs can carry); hold the free motion with a joint or a "
                          "spring, start it closer to equilibrium, or run it dynamically with damping");
  }
  evaluate(model, data, t);
  static_tangent(model, data, t, T);
  red = reduce(model, data, T);
  check_stability(model, red, t);
  const VectorXd moved = data.state.q - q_start;
  double largest = 0;
  for (const Body& b : model.bodies) largest = std::max(largest, moved.segment<3>(b.offset).norm());
  std::vector<std::string> notes{"static equilibrium reached in " + std::to_string(it) +
                                 " Newton iterations (largest frame displacement " + fmt(largest) + " m; " +
                                 coordinate_name(model, moved) + " moved most)"};
  if (red.Z.cols() > 0)
    notes.push_back("static equilibrium: " + std::to_string(red.Z.cols()) +
                    " neutral motion(s) meet no stiffness and no force (left where the start put them; any position along them "
                    "is an equilibrium): " + neutral_names(model, red));
  return notes;
}

// The model with its applied loads (gravity and the point loads' tables) scaled by f.
void scale_loads(const Model& full, double f, Model& scaled) {
  scaled.gravity = f * full.gravity;
  for (std::size_t i = 0; i < full.loads.size(); ++i) {
    const Table& tb = full.loads[i].table;
    scaled.loads[i].table = Table(tb.times(), f * tb.values(), tb.kind());
  }
}

}  // namespace

// Where Newton from the start does not converge at the full loads (a strongly nonlinear
// equilibrium: a cantilever rolled up by its end moment), the loads are stepped from zero, each
// equilibrium starting the next; a step that fails is halved (FORMULATION.md 14, load stepping).
std::vector<std::string> settle_statically(const Model& model, Data& data) {
  const VectorXd q0 = data.state.q, lambda0 = data.state.lambda;
  bool unconverged = false;
  try {
    return settle_at(model, data, unconverged);
  } catch (const SolverError&) {
    if (!unconverged || (model.loads.empty() && model.gravity.isZero())) throw;
  }
  Model scaled = model;  // set-up only: the step never comes here
  double done = 0, step = 0.125;
  int steps = 0;
  std::vector<std::string> notes;
  data.state.q = q0;
  data.state.lambda = lambda0;
  while (done < 1) {
    const double f = std::min(1.0, done + step);
    const VectorXd q = data.state.q, lambda = data.state.lambda;
    bool failed = false;
    try {
      scale_loads(model, f, scaled);
      // A load step that Newton does not settle quickly is halved rather than iterated on.
      notes = f < 1 ? settle_at(scaled, data, unconverged, kStepIterations) : settle_at(model, data, unconverged, kStepIterations);
    } catch (const SolverError&) {
      if (!unconverged || step < 1.0 / 1024) throw;
      failed = true;
    }
    if (failed) {
      data.state.q = q;
      data.state.lambda = lambda;
      step *= 0.5;
      continue;
    }
    done = f;
    ++steps;
    step *= 1.5;
  }
  notes.push_back("static equilibrium: Newton from the start did not converge at the full loads; reached by " +
                  std::to_string(steps) + " load steps from zero");
  return notes;
}

}  // namespace ffr::runtime
