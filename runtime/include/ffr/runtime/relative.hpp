#pragma once
// The relative (joint-coordinate) formulation, FORMULATION.md section 18: a semi-recursive,
// velocity-transformation scheme after García de Jalón, Cuadrado and co-workers. A spanning
// tree of the joint graph is chosen; each body reached through a revolute, prismatic,
// cylindrical or fixed joint between two markers on body frames (not on flexible nodes) is
// placed by its parent and that joint's coordinates; a body reached through a spherical or
// universal joint, or through a revolute or fixed joint with a marker on a flexible node (a reduced
// body's, an ANCF beam's or plate's), is placed at the joint's point (its position follows the
// parent's point, its frame keeps its natural coordinates); every other body keeps its natural
// coordinates z as its own "joint" coordinates (a free base). The relative coordinates s are
// these joint coordinates, the free bodies' z and every tree body's modal coordinates y. The
// absolute coordinates are q = q(s), q_dot = R(s) s_dot; the equations of motion are the
// absolute ones (mass matrices, forces, constraints of the existing evaluation) projected by R:
//   R^T (M q_ddot - Q) + (Phi_q R)^T lambda = 0,
// with only the rows that the tree does not satisfy by construction kept as constraints (the cut
// joints, motions, couplers and the free bodies' frames), integrated by the same trapezoidal
// index-3 augmented Lagrangian with projections. The state of the Data (q, q_dot, q_ddot) is the
// reconstructed absolute one, so outputs, energy and the C API read it unchanged.

#include "ffr/runtime/data.hpp"
#include "ffr/runtime/model.hpp"
#include "ffr/runtime/small_lu.hpp"

#include <limits>
#include <string>
#include <vector>

namespace ffr::runtime {

/// How one body's absolute coordinates follow from s.
struct RelativeBody {
  bool free = true;        ///< its z are relative coordinates (s_first .. s_first + 12 + nq)
  int parent = kGround;    ///< a tree body's parent (body index or kGround)
  int joint = -1;          ///< a tree body's joint to its parent
  int parent_marker = -1;  ///< the joint's marker on the parent
  int s_angle = -1;        ///< its joint angle about the parent marker's axis e (-1: none)
  int s_slide = -1;        ///< its joint slide along that axis (-1: none)
  int s_first = -1;        ///< free: its first coordinate; tree: its first modal coordinate (-1: none);
                           ///< placed at a point: its nine frame coordinates, then its modal ones
  /// Placed at a point (a spherical joint, or the point of a joint at a flexible node): its
  /// position follows the parent's joint point, its frame keeps its natural coordinates (and
  /// their frame rows), the joint's other rows stay constraints.
  bool point = false;
  int child_marker = -1;   ///< placed at a point: the joint's marker on the body itself
  /// The relative coordinates its absolute ones depend on lie in [col0, col0 + ncols): its own
  /// and its ancestors' (R is zero outside, so the products run over this range only).
  int col0 = 0, ncols = 0;
  /// A tree body's rows of R (and of its rates) past its first `top` (its position at a point:
  /// 3; its frame when placed wholly: 12) are zero outside its own columns [own0, col0 + ncols):
  /// only its position (frame) follows its ancestors. The products of refresh run over that
  /// pattern (relative/step.cpp).
  int own0 = 0, top = 0;
};

/// The spanning tree (built once by finalize, never changed by the step).
struct RelativeTree {
  int ns = 0;                         ///< number of relative coordinates
  std::vector<int> order;             ///< bodies, every parent before its children
  std::vector<RelativeBody> bodies;   ///< per body
  std::vector<char> tree_joint;       ///< per joint: 1 satisfied by construction (its rows dropped),
                                      ///< 2 its point only (its three point rows dropped, the rest kept)
  std::vector<int> kept_blocks;       ///< constraint blocks that stay constraints
  int kept_rows = 0;
  bool flexible = false;              ///< some body has modal coordinates
  /// Pairs of bodies a force element couples (i < j): where the force tangents K, C have blocks
  /// off the bodies' own.
  std::vector<std::pair<int, int>> pairs;
  /// Pairs of bodies (i <= j) a kept constraint block joins, and each flexible body with itself:
  /// where the constraint Hessian and the modal acceleration tangent have blocks.
  std::vector<std::pair<int, int>> hessian_pairs;
  std::vector<char> hessian_self;    ///< per body: (b, b) is among hessian_pairs
  std::string description;            ///< what the tree is, for the notes
  /// One line per joint the tree satisfies (assembled: no multiplier, no constraint row for what
  /// it places), for the notes: "joint 'hang' assembled (spherical, body 'bob' placed at node
  /// 'end' of 'beam')".
  std::vector<std::string> assembled;
};

/// The relative state and workspace, sized once (relative_step allocates nothing).
struct RelativeWork {
  explicit RelativeWork(const Model& model);
  VectorXd s, sd, sdd, s0, sd0, sdd0, sdd_prev, sd_hat, sdd_hat;
  /// Generalized-alpha's pseudo-acceleration of s (scheme_coefficients.cpp's a, in s), and the
  /// coordinates, rates and accelerations kept across its start step.
  VectorXd a, start_s, start_sd, start_sdd;
  double h_prev = 0;
  bool have_previous = false;
  /// The tree bodies' pose in their parent marker's triad when the coordinates were last taken
  /// from the absolute state (sync): A = T_p Rx(angle) rel_A, r0 = P + T_p (Rx(angle) rel_p + slide e_x).
  std::vector<Matrix3d> rel_A;
  std::vector<Vector3d> rel_p;
  MatrixXd R;              ///< dq/ds [n, ns]
  /// dR/dt = d(R s_dot)/ds at fixed s_dot [n, ns]: q_ddot = R s_ddot + R_dot s_dot, and the
  /// tangent's rate term d(R_dot s_dot)/d(s_dot) = 2 R_dot (FORMULATION.md 18).
  MatrixXd Rd;
  /// dq_ddot/ds at fixed s_dot and s_ddot [n, ns]: the curvature of q(s) in q_ddot.
  MatrixXd Ra;
  MatrixXd Z;  ///< work [n, ns]: 2 kv R_dot + kq Ra (the tangent's mass terms, one product)
  /// The absolute residual force M q_ddot - Q + Phi_q^T (lambda + alpha Phi) [n], and per body
  /// the part of it (with its descendants') that acts on its frame coordinates r, A ([3 x 4]:
  /// force, then A's nine entries), for the curvature term sum_k (dR/ds_k)^T F.
  VectorXd force;
  std::vector<Eigen::Matrix<double, 3, 4>> frame_force;
  /// false: the tangent without the derivatives of R (as before they were added; the tests
  /// compare Newton's contraction with and without them).
  bool exact_tangent = true;
  VectorXd weight;         ///< per relative coordinate: the scaled size of the displacement it causes
  VectorXd keep;           ///< per constraint row: 1 kept, 0 satisfied by the tree
  MatrixXd Phis;           ///< Phi_q R on the kept rows [m, ns] (zero elsewhere)
  /// Per kept block (RelativeTree::kept_blocks' order): Phis's columns [lo, hi) outside which
  /// its rows are zero (a body's frame rows see its own frame only), set with Phis.
  std::vector<int> span_lo, span_hi;
  std::vector<int> kept;   ///< the kept rows, in order
  /// The direct projection's work (relative/projection.cpp): Y = Tm^-1 Phis^T of the kept rows
  /// [ns, kept], S = Phis Y [kept, kept] and its pivoted Cholesky factor, its pivot order, and
  /// vectors [kept].
  MatrixXd projY, projS;
  std::vector<int> proj_order;
  VectorXd proj_own, proj_w, proj_mu, proj_c;
  MatrixXd Ts;             ///< tangent [ns, ns]
  MatrixXd Wb, WR;         ///< work: a body's (pair's) block of W, and W times R rows
  MatrixXd PA;             ///< work [m, ns]: alpha times Phis
  SmallLU lu;
  VectorXd scale;
  /// The projections' metric: the tangent without R's derivatives (refresh), its factors and
  /// scaling, and whether it was rebuilt since it was last factorised.
  MatrixXd Tm;
  SmallLU lu_m;
  VectorXd scale_m;
  bool metric_stale = true;
  VectorXd f, ds, r, sigma, c, g, bias, qsave;
  VectorXd y;  ///< work [ns]: a column of projY being solved for (factor_kept_multipliers)
  /// The absolute state this formulation last produced: a different one (initialize,
  /// restore_state, the C API) makes the next step take its coordinates from it afresh.
  VectorXd q_last, qd_last;
  double t_last = std::numeric_limits<double>::quiet_NaN();
};

/// Builds model.relative (finalize calls it when the formulation is Relative, or Auto chose it).
/// Throws ModelError naming the model file and the field of what the relative formulation cannot
/// run.
void build_relative_tree(Model& model);

/// The Auto rule (FORMULATION.md section 18): Relative or Absolute for this model, and why.
Formulation choose_formulation(const Model& model, std::string& why);

/// One ALI3-P step of h in the relative coordinates, trapezoidal or generalized-alpha as the
/// model's solver says (step() calls it when the model has a relative tree). Allocation-free.
void relative_step(const Model& model, Data& data, double h);

/// The parts of relative_step, for the tests of its Newton iteration: the step's set-up to t + h
/// (scheme coefficients, predictor of s, penalty weights); the residual f(s) at RelativeWork::s
/// (s_dot and s_ddot affine in s through the scheme, the multipliers fixed) into
/// RelativeWork::f, evaluating the model there; and the tangent df/ds at the last residual's
/// iterate into RelativeWork::Ts (and factorised).
void relative_begin_step(const Model& model, Data& data, double h);
void relative_residual(const Model& model, Data& data, double t);
void relative_tangent(const Model& model, Data& data, double t);

/// Ts += factor sum_k (dR/ds_k)^T F (symmetric), F = RelativeWork::force: the curvature of q(s)
/// weighted by the absolute residual force, by the tree's recursion (children's forces carried to
/// their parents' frames).
void relative_curvature(const Model& model, Data& data, double factor, MatrixXd& Ts);

/// Takes the relative coordinates, rates and accelerations from the absolute state of data
/// (consistent with the joints), with every tree joint coordinate zero there.
void relative_sync(const Model& model, Data& data);

/// q, q_dot and q_ddot (data.state) from s, s_dot, s_ddot, and R when `jacobian`; with `rates`
/// (and `jacobian`) also R_dot and Ra, which only the tangent reads (step.cpp's refresh): a
/// Newton iteration that keeps its tangent skips them.
void relative_kinematics(const Model& model, Data& data, bool jacobian, bool rates = true);

}  // namespace ffr::runtime
