#pragma once
// The Data: every buffer the algorithms write, sized once from a Model. After construction
// (and initialize()), a time step allocates nothing: all work goes into these members.

#include "ffr/runtime/model.hpp"
#include "ffr/runtime/owned.hpp"
#include "ffr/runtime/scheme.hpp"
#include "ffr/runtime/small_lu.hpp"
#include "ffr/runtime/state.hpp"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

namespace ffr::runtime {

using Matrix3N = Eigen::Matrix<double, 3, Eigen::Dynamic>;

/// Per-body kinematic and inertial quantities at the current state.
struct BodyData {
  Matrix3d A, Ad, Add;          ///< frame [u v w], its rate and acceleration
  Vector3d md;                  ///< int xbar dm = rdm + Pdm y
  Matrix3d Jc;                  ///< int xbar xbar^T dm (+ rotary pseudo-inertia)
  std::array<Matrix3Xd, 3> S;   ///< S_a = int xbar_a Phi dm = rPdm[a] + P_a(y), [3, nq]
  MatrixXd Pyd;                 ///< column 3b+c = PPdm[b][c] y_dot, [nq, 9]
  MatrixXd Py;                  ///< work: column 3b+c = PPdm[b][c] y, [nq, 9]
  MatrixXd M;                   ///< body mass matrix [nb, nb]
  Vector3d omega;               ///< body-frame angular velocity (from the frame vectors)
  Vector3d alpha;               ///< body-frame angular acceleration
  Vector3d acc;                 ///< body-frame acceleration of O minus gravity
  MatrixXd KG;                  ///< geometric stiffness [nq, nq] (stiffening)
  MatrixXd G1, X1;              ///< Ke/M1 (modal_stress_terms): its second derivative, and column k = M1[k] y
  Eigen::Matrix<double, 6, Eigen::Dynamic> iface_load;  ///< per stiffening interface: F, M in K
  MatrixXd feB, feG, feD;       ///< co-rotational path only: B, M_FE B, dw/dz_dot [3N, nb]
  VectorXd few, feg;            ///< co-rotational path only: w = 2 A_dot Phi y_dot and M_FE w [3N]
  VectorXd wq;                  ///< work [nq]
};

/// A marker's position and axes with their Jacobians (columns: the coordinates of its body).
struct MarkerData {
  Vector3d p, pd, pb;           ///< position, velocity, J_dot * z_dot
  Matrix3N Jp;                  ///< [3, nb]
  std::array<Vector3d, 3> e, ed, eb;
  std::array<Matrix3N, 3> Je;   ///< [3, nb] each
  Vector3d xbar;                ///< deformed local point
  std::array<Vector3d, 3> ebar; ///< deformed local axes
};

/// Iteration counts and residuals, for reports and tests.
struct Stats {
  std::int64_t steps = 0;
  std::int64_t newton_iterations = 0;
  std::int64_t factorizations = 0;
  std::int64_t solves = 0;       ///< solves with the factorised tangent (Newton, projections)
  int last_iterations = 0;      ///< of the last step (the policy reads State::last_iterations)
  double last_increment = 0;    ///< scaled
  double last_violation = 0;    ///< max |Phi| / length after the step
  double last_velocity_violation = 0;
  double last_acceleration_violation = 0;
};

/// Where a driven body was when the drives took over (after the initial assembly), and its
/// joint's fixed axis and point and the drive's coordinate then: the body's motion at t is this
/// pose turned about (slid along) the axis by the change of the prescribed coordinate.
struct DriveReference {
  Vector3d r0 = Vector3d::Zero();
  Matrix3d A = Matrix3d::Identity();
  Vector3d point = Vector3d::Zero();  ///< on the axis, global
  Vector3d axis = Vector3d::UnitZ();   ///< unit, global; the direction the coordinate grows (body side)
  double value = 0;                    ///< the prescribed coordinate at the reference
};

struct RelativeWork;  // relative.hpp

struct Data {
  explicit Data(const Model& model);

  /// The state (state.hpp): t, q, q_dot, q_ddot, lambda and what the next step reads of the
  /// steps before. Everything below it is workspace that a step rebuilds before reading it.
  State state;
  /// The scheme's mode (scheme.hpp); its coefficients and pseudo-acceleration are in the state.
  SchemeState scheme;
  /// Work: the state the generalized-alpha start returns to after its trapezoidal step.
  State start;

  // The unknowns of the step: the first nf coordinates, the first na constraint rows (in
  // blocks model.blocks[0 .. nblocks)). All of them while the initial conditions are made
  // (every body moves); afterwards, with driven bodies eliminated, model.nfree and
  // model.nactive, the driven bodies following their drives (drive_bodies).
  int nf = 0, na = 0, nblocks = 0;
  /// The coordinates solved for, ascending: [0, nf) less the frame vectors of frame-locked
  /// bodies (Body::frame_locked), which follow drive_bodies like a driven body's. The tangent is
  /// built over [0, nf) and factorised over these (empty: all of [0, nf)).
  std::vector<int> unknowns;
  /// unknowns as runs of consecutive coordinates (a body's, a frame-locked body's position):
  /// unknowns[at + i] = first + i for i < len. The gathers go along them, contiguous.
  struct Run {
    int at, first, len;
  };
  std::vector<Run> unknown_runs;
  VectorXd lu_work;             ///< the right-hand side gathered to the unknowns
  std::vector<char> integrated;           ///< per body: its coordinates are unknowns now
  /// Whether the step's passes over the tangent blocks and over the constraint blocks' columns
  /// are cheaper than the dense ones for the unknowns now (tangent_blocks.hpp): decided by
  /// set_unknowns, the only place the unknowns change; false (the dense passes) until then.
  bool tangent_blocks_pay = false, block_columns_pay = false;
  /// With tangent_blocks_pay: per column of the factorised tangent (the unknowns', in their
  /// order), the first and last row its tangent blocks reach, between which the factorisation
  /// clears, gathers and scans (SmallLU::compute_within); set by set_unknowns.
  std::vector<int> lu_first, lu_last;
  /// With tangent_blocks_pay: the order of the factorised tangent's rows and columns, body by
  /// body (tangent_blocks.cpp, factorisation_order): lu_runs maps its positions to coordinates
  /// in runs (as unknown_runs), lu_pos a coordinate to its position (-1: not an unknown).
  std::vector<Run> lu_runs;
  std::vector<int> lu_pos;
  /// The pairs of distinct bodies whose off-diagonal tangent blocks can be nonzero, each once
  /// (lower index first; tangent_blocks.hpp, coupled_body_pairs).
  std::vector<std::array<int, 2>> body_pairs;
  /// Per body: its diagonal tangent block is an ancf beam's band (tangent_blocks.hpp, banded_beam).
  std::vector<char> banded;
  std::vector<DriveReference> drive_ref;  ///< per body (driven bodies only)

  // Per-element work.
  std::vector<BodyData> bodies;
  std::vector<MarkerData> markers;
  MatrixXd Phiq;                ///< constraint Jacobian Phi_q [m, n], dense (zero outside the blocks)

  // Global vectors and matrices (n = coordinates, m = constraint rows).
  VectorXd Q;                   ///< generalized forces (applied + velocity-dependent inertia)
  MatrixXd K, C;                ///< -dQ/dq, -dQ/dqd (analytic)
  VectorXd Phi, Phit, gamma;    ///< constraint value, partial time derivative, acceleration bias
  VectorXd lambda_eff;          ///< lambda + alpha Phi
  VectorXd lambda0;             ///< multipliers at the start of the step
  /// The multipliers with the projected accelerations (M q_dd + Phi_q^T lambda = Q for the
  /// q_dd after the acceleration projection): what the reaction outputs read. The step's own
  /// lambda balances the scheme's accelerations before the projection, whose error (undamped by
  /// the trapezoidal rule) would show in the reactions (FORMULATION.md 13).
  VectorXd reaction_lambda;
  MatrixXd W;                   ///< M + kv C + kq K at the last factorisation (projection metric; scheme.hpp)
  MatrixXd T;                   ///< tangent W + kq Phi_q^T alpha Phi_q
  SmallLU lu;                   ///< of the scaled tangent S T S (see factorize_tangent)
  VectorXd scale;               ///< S = diag(|T_ii|^-1/2): equilibration of masses vs stiffnesses
  bool tangent_valid = false;
  /// Drops what the tangents keep for later steps (the factorised tangent, the bushings' part:
  /// bushing_K): a run that goes on from another state (restored, settled) builds its own.
  void forget_tangents() { tangent_valid = false; bushing_tangent_age = -1; }
  bool tangent_fresh_step = false; ///< factorised during the current step (or set-up)
  /// Set by the step while it builds its first tangent, the one tangent that may take a sliding
  /// tyre's exact slope (tire.cpp, FORMULATION.md 8) and the bushings' part kept from an earlier
  /// step (NewtonPolicy::bushing_tangent_steps).
  bool first_tangent_of_step = false;
  bool tangent_metric_only = false; ///< T = W + h^2/4 alpha Phi_q^T Phi_q exactly (the projections' own)

  // Integrator work.
  VectorXd q0, qd0, qdd0;       ///< state at the start of the step
  VectorXd qd_hat, qdd_hat;     ///< the scheme's affine terms (scheme.hpp)
  VectorXd f, dq, r, sigma, c, tmp, vstar;
  /// exact_multipliers' work: Y = T^-1 Phi_a^T [n, m], S = Phi_a Y [m, m] and its pivoted factor
  /// in place, the pivot order, the multipliers and the pivoted solution [m].
  MatrixXd projY, projS;
  std::vector<int> proj_order;
  int proj_rank = 0;
  VectorXd proj_mu, proj_w;
  // Motions: values from the C API override the table when set.
  std::vector<char> motion_external;
  std::vector<Eigen::Vector3d> motion_value;  ///< value, rate, acceleration

  // External loads (set_external_load): per body, slot 0 = frame origin, slot 1 + p = node p.
  // The step visits only the slots in ext_list (the set ones, each once): a SID may carry
  // thousands of nodes, and a pass over all of them at every evaluation made the step
  // mesh-dependent.
  std::vector<Matrix3N> ext_force, ext_torque;
  std::vector<std::vector<int>> ext_list;
  std::vector<MarkerData> ext_marker;  ///< work for one node per body

  // Force-element work, sized for the largest pair of bodies an element joins.
  MatrixXd fK, fC, fH;          ///< [n12, n12]
  Eigen::Matrix<double, 6, Eigen::Dynamic> fg;  ///< gradients of up to 6 scalar measures
  VectorXd fz, fhz;             ///< [n12]
  std::array<Matrix3N, 4> w3;   ///< [3, nb max]
  VectorXd lt;                  ///< [6 nb max]: a line force's weighted transposed point Jacobians, one per end
  /// Tyres: the Jacobian of the wheel marker's point and three axes, their rate derivative and a
  /// product, [12, nb max] each (tire.cpp).
  Eigen::Matrix<double, 12, Eigen::Dynamic> tJ, tV, tW;
  /// Tyres: sliding well beyond the friction circle at the last accepted state (commit_friction),
  /// one each (the step's first tangent takes such a tyre's exact slope: first_tangent_of_step).
  std::vector<char> tire_sliding;
  /// Bushings (bushing.cpp): each end's stacked Jacobian [J_p; J_e0; J_e1; J_e2] and a weighted
  /// product, [12, nb max] each; the rank-six factor of K, [6, n12]; one end's transposed
  /// factors g^T, (diag(c) g)^T and J^T, [nb max, 24] in all.
  std::array<Eigen::Matrix<double, 12, Eigen::Dynamic>, 2> bJ;
  Eigen::Matrix<double, 12, Eigen::Dynamic> bT;
  Eigen::Matrix<double, 6, Eigen::Dynamic> bP;
  VectorXd bt;
  /// The bushings' part of K and C as last built ([n, n], zero outside their bodies' blocks;
  /// empty without bushings) and the steps it has been used for since (-1: none built); the
  /// step's first tangent may take it instead of building it again (first_tangent_of_step,
  /// NewtonPolicy::bushing_tangent_steps, force_tangents).
  MatrixXd bushing_K, bushing_C;
  /// The blocks of K the bushings write, each once: [row0, rows, col0, cols].
  std::vector<std::array<int, 4>> bushing_blocks;
  int bushing_tangent_age = -1;

  // Constraint-Hessian work, sized for the largest pair of bodies a joint joins.
  MatrixXd cH;                  ///< [n12, n12]
  Eigen::Matrix<double, 4, Eigen::Dynamic> cg;  ///< angle row: g_x, g_y, N, w
  VectorXd cl;                  ///< [6] scaled multipliers of one joint

  Stats stats;
  VectorXd alpha;               ///< penalty of each constraint row in use (penalty_weights)
  MatrixXd Jw;                  ///< work: a penalty-weighted Jacobian block (add_penalty_tangent)
  VectorXd penalty_rows;        ///< work: the penalty weights of one block's rows

  /// The relative formulation's state and workspace (relative.hpp); null for the absolute one.
  Owned<RelativeWork> relative;
};

/// Which bodies and markers an update covers: all, or those of the unknowns alone (the ground's
/// and driven bodies' are then left as they are: within a step, after drive_bodies at its time
/// and one update of everything, they do not change).
enum class Scope { All, Unknowns };

/// True when `body` is not the ground and its coordinates are unknowns of the step now. Markers
/// of other bodies act like the ground's: points and axes that move as given, without columns.
inline bool integrated(const Data& data, int body) { return body != kGround && data.integrated[static_cast<std::size_t>(body)]; }

/// How many of an integrated body's coordinates, from its first, the tangent needs: all of them,
/// or a frame-locked body's position alone while its frame is known (Data::unknowns).
inline int unknown_columns(const Model& model, const Data& data, int body) {
  const Body& b = model.bodies[static_cast<std::size_t>(body)];
  return b.frame_locked && !data.unknowns.empty() ? 3 : b.ncoord();
}

/// Applies force and torque (global axes) at a body's load slot (0 = frame origin, 1 + p = its
/// node p) from the next evaluation on, until clear_external_loads. Allocation-free.
void set_external_load(Data& data, int body, int slot, const Vector3d& force, const Vector3d& torque);
/// Removes every external load.
void clear_external_loads(Data& data);

}  // namespace ffr::runtime
