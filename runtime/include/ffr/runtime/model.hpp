#pragma once
// The Model: everything about a multibody system that does not change while it moves.
// Built once (load_model or by hand + finalize), then only read by the algorithms, which take
// (const Model&, Data&) like Pinocchio. Every quantity here is reduced: a flexible body keeps
// its primitive shape integrals (formats/SPEC.md sections 7-8) and the slices of its exported
// nodes, never a mesh.
//
// Coordinates (FORMULATION.md): each body owns z = [r0, u, v, w, y] (12 + nq numbers): the
// position of its frame origin, the three frame vectors (A = [u v w]) and its modal amplitudes.
// The ground has none.

#include "ffr/runtime/beam.hpp"
#include "ffr/runtime/plate.hpp"
#include "ffr/runtime/step_policy.hpp"
#include "ffr/runtime/table.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products

#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace ffr::runtime {

using Eigen::Matrix3d;
using Eigen::Matrix3Xd;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using Matrix36 = Eigen::Matrix<double, 3, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

inline constexpr int kGround = -1;

/// An exported node of a flexible body: undeformed position and mode slices (body frame).
struct NodeSlice {
  std::string name;
  Vector3d origin = Vector3d::Zero();
  Matrix3Xd phi;  ///< [3, nq] translational
  Matrix3Xd psi;  ///< [3, nq] small rotation

  /// phi y, the node's elastic displacement for modal coordinates y; zero for a body without
  /// modes (a beam's node body), where Eigen's product of the empty phi would offset its null
  /// data pointer (undefined behaviour, reported by UBSan).
  template <class Y>
  Vector3d displacement(const Y& y) const {
    return phi.cols() == 0 ? Vector3d::Zero() : Vector3d(phi * y);
  }
};

/// The interface-load members of one interface (SID /stiffening/interfaces/<name>): the
/// geometric stiffness of a unit force and moment at its node, resolved in K (FORMULATION.md 7).
struct InterfaceStiffening {
  std::string name;
  int node = -1;               ///< index into Body::nodes
  std::array<MatrixXd, 3> KF;  ///< KF[c](i,k) = K0F[k](i,c), less its modal part (below)
  std::array<MatrixXd, 3> KM;  ///< KM[c](i,k) = K0M[k](i,c), less its modal part
};

/// Geometric stiffening (formats/SPEC.md section 10), regrouped per load component so the
/// per-step geometric stiffness is a sum of nq x nq matrices: KG = sum_c a_c Kt[c] + ...
/// When the body also has the stiffness of its own modal stress (ModalStressStiffness), each
/// load case's matrix is stored less the part of it that its quasi-static modal response
/// already gives through Ke/M1 (FORMULATION.md 7: no double counting).
struct StiffeningTerms {
  std::array<MatrixXd, 3> Kt;  ///< Kt[c](i,k) = K0t[k](i,c)
  std::array<MatrixXd, 3> Kr;  ///< Kr[c](i,k) = K0r[k](i,c)
  std::array<MatrixXd, 6> Kw;  ///< Kw[j](i,k) = K0om[k](i,j), j in omega_bar order
  std::vector<InterfaceStiffening> interfaces;  ///< interfaces not held (loads from joints there)
  /// [3, nq]: column k = int c x Phi_k dm + (PsiI row k)^T, the angular momentum about O of the
  /// modal rates. With use_mean_spin (a Craig-Bampton body: its frame is a node's, which the
  /// joints may leave free to turn with the bending) the centrifugal cases see the body's mean
  /// spin omega + I^-1 spin_h y_dot, otherwise the frame's (FORMULATION.md 7).
  Matrix3Xd spin_h;
  bool use_mean_spin = false;
};

/// The geometric stiffness of the body's own modal stress (SID /sid/Ke/M1, M1[k](i,j) =
/// Phi_i^T K_G(sigma_k) Phi_j), for the strain energy 1/2 s^T Ke s, s = y + Ke^+ g(y),
/// g_k = 1/2 y^T M1[k] y (FORMULATION.md 7). Stored twice, so each per-step quantity is one
/// product:
///   by_mode  [nq*nq + nq, nq], rows k*nq .. k*nq+nq-1 = M1[k] (by_mode y = [M1[0] y; ...]),
///            then Ke^+ in its last nq rows
///   by_coeff [nq*nq, nq], column k = vec(M1[k]):  by_coeff s = vec(sum_k s_k M1[k])
struct ModalStressStiffness {
  MatrixXd by_mode, by_coeff;
};

/// Prestress (SID /sid/ksigma): the modal force of the preloaded state and its geometric
/// stiffness, Q_y -= f0 + K1 y.
struct Prestress {
  VectorXd f0;
  MatrixXd K1;
};

/// The unreduced mass data of a flexible body, for the co-rotational comparison only (benchmarks,
/// docs/references.md "Shape integrals"):
/// when a body has it, its mass matrix and inertia forces are computed each step the
/// co-rotational way, B^T M_FE B and -B^T M_FE (2 A_dot Phi y_dot) with B the [3N, 12+nq]
/// velocity map of all N nodes, instead of from the shape integrals. Translational mass only.
struct FullMass {
  Eigen::VectorXd X;                     ///< [3N] undeformed nodal positions (body frame)
  Eigen::MatrixXd Phi;                   ///< [3N, nq] mode shapes
  Eigen::SparseMatrix<double> M;         ///< [3N, 3N] FE mass matrix
};

/// How a rigid body's motion is fixed by a joint to the ground alone: held by a fixed joint, or
/// turned (slid) by a revolute (prismatic) joint whose coordinate a motion prescribes. Such a
/// body is driven: its coordinates are known functions of time, not unknowns of the step
/// (FORMULATION.md section 9, driven bodies).
enum class DriveKind { None, Fixed, Revolute, Prismatic };
struct Drive {
  DriveKind kind = DriveKind::None;
  int joint = -1;
  int motion = -1;     ///< -1 for a fixed joint
  int side = 0;        ///< 1 or 2: which marker of the joint is on the body
};

/// One body. A rigid body is the special case nq = 0 (its integrals are m, m c_G and the
/// pseudo-inertia), which makes its mass matrix constant.
struct Body {
  std::string name;
  bool flexible = false;
  std::string source;  ///< SID path for a flexible body (for messages)
  int nq = 0;
  int offset = 0;      ///< index of r0 in the global coordinate vector
  int ncoord() const { return 12 + nq; }
  Drive drive;         ///< set by finalize() (rigid bodies driven relative to the ground)
  bool driven() const { return drive.kind != DriveKind::None; }
  /// A rigid body on a prismatic joint to the ground without a motion cannot turn: while driven
  /// bodies are eliminated, its frame vectors are known (its pose after the initial conditions)
  /// and only its position is an unknown of the step (FORMULATION.md section 9). Set by finalize().
  bool frame_locked = false;

  // Inertia (body frame, about the frame origin O).
  double mass = 0;
  Vector3d rdm = Vector3d::Zero();   ///< int c dm
  Matrix3d J0 = Matrix3d::Zero();    ///< int c c^T dm + rotary pseudo-inertia (1/2 tr(I) 1 - I)
  Matrix3Xd Pdm;                     ///< [3, nq]
  std::array<Matrix3Xd, 3> rPdm;     ///< rPdm[a] = int c_a Phi dm, [3, nq]
  std::array<std::array<MatrixXd, 3>, 3> PPdm;  ///< int Phi_a^T Phi_b dm, [nq, nq]
  /// The nine PPdm[a][b] stacked, rows 3a+b first: PPdm_stack x is all nine PPdm[a][b] x
  /// ([9 nq]) in one product. Set by finalize().
  MatrixXd PPdm_stack;
  MatrixXd PsiI;                     ///< [nq, 3] = sum Psi_p^T I_p (rotary coupling)
  MatrixXd Myy;                      ///< sum_a PPdm[a][a] + sum Psi^T I Psi: constant modal mass
  MatrixXd Ke, De;                   ///< modal stiffness and total modal damping
  bool has_rotary_coupling = false;
  std::optional<StiffeningTerms> stiffening;  ///< only when the SID has it and it is enabled
  std::optional<ModalStressStiffness> modal_stress;  ///< /sid/Ke/M1, when present and enabled
  std::optional<Prestress> prestress;                 ///< /sid/ksigma, when nonzero and enabled
  std::shared_ptr<const FullMass> full_mass;  ///< benchmarks only (see FullMass)
  /// A beam body (beam.hpp): y are its nodal coordinates less beam->q0, its elastic forces the
  /// element's, its frame held at the global frame by its twelve-row block (FORMULATION.md 15).
  std::shared_ptr<const AncfBeam> beam;
  /// The rows of its frame's constraint block: 6 (orthonormal frame vectors) or 12 (a beam's
  /// frame held at the global frame).
  int frame_rows() const { return beam ? 12 : plate ? 12 + static_cast<int>(plate->supports.size()) : 6; }
  /// A plate body (plate.hpp): like a beam, its frame held at the global frame; its edge
  /// supports are further linear rows of that block (FORMULATION.md 16).
  std::shared_ptr<const AncfPlate> plate;
  /// The frame is held at the global frame and the nodal coordinates carry every motion.
  bool held_frame() const { return beam || plate; }
  std::vector<NodeSlice> nodes;

  // Initial state as given in the model file (global).
  Vector3d r0 = Vector3d::Zero();
  Matrix3d A0 = Matrix3d::Identity();
  Vector3d v0 = Vector3d::Zero(), w0 = Vector3d::Zero();
  VectorXd y0, yd0;

  /// Scale of each modal coordinate for convergence tests: a length times sqrt(m / Me_kk).
  VectorXd y_scale;

  int find_node(const std::string& n) const {
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (nodes[i].name == n) return static_cast<int>(i);
    return -1;
  }
};

/// A point with a triad attached to a body (or to the ground), possibly at a SID node so it
/// follows the node's deformation: p = r0 + A (c + phi y), axis k = A (E_k + (psi y) x E_k).
struct Marker {
  int body = kGround;
  int node = -1;                     ///< node index in the body, -1 if rigidly on the frame
  Vector3d c = Vector3d::Zero();     ///< local point (global point for the ground)
  Matrix3d E = Matrix3d::Identity(); ///< columns e, f, g (local; global for the ground)
  Matrix3Xd phi;                     ///< [3, nq] (zero when node < 0)
  Matrix3Xd psi;                     ///< [3, nq] node rotation slice (zero when node < 0)
  std::array<Matrix3Xd, 3> phiE;     ///< -skew(E_k) psi: the axes' mode slices
  /// The axes something reads (joint rows, joint coordinates, bushings; set by finalize): the
  /// others, their rates and Jacobians are not computed (left zero).
  std::array<bool, 3> axes{true, true, true};
  /// >= 0: the marker is on a plate node and reads the node's exact triad (FORMULATION.md 16,
  /// "Welds"): the index in y of the node's r_x (r_y follows at + 3). Its axes are then
  /// A T(r_x, r_y) triad_R.col(k), T the Gram-Schmidt triad of the gradients, instead of the
  /// linearised E_k + phiE_k y. Set for a fixed joint between a plate node and a moving body.
  int triad = -1;
  Vector3d triad_x0 = Vector3d::Zero(), triad_y0 = Vector3d::Zero();  ///< the node's reference r_x, r_y (local)
  Matrix3d triad_R = Matrix3d::Identity();  ///< E in the reference triad T0: T0^T E (column k: axis k's weights)
};

enum class JointType { Revolute, Spherical, Fixed, Prismatic, Cylindrical, Universal };
const char* to_string(JointType t);

/// Which scalar a motion or output reads from a joint.
enum class JointCoordinate { Angle, Displacement };

struct Joint {
  std::string name;
  JointType type = JointType::Spherical;
  int m1 = -1, m2 = -1;  ///< markers
  int block = -1;        ///< its constraint block
  double d0 = 0;         ///< initial displacement along the axis (prismatic/cylindrical coordinate zero)
};

/// A coupler (belt, gear, rack): the change of joint1's coordinate is `ratio` times joint2's,
/// one constraint row w (theta1 - ratio theta2) (w = model length for an angle of joint1, else 1;
/// both coordinates are zero in the initial configuration).
struct Coupler {
  std::string name;
  int joint1 = -1, joint2 = -1;
  JointCoordinate c1 = JointCoordinate::Angle, c2 = JointCoordinate::Angle;
  double ratio = 1;
  int block = -1;
};

struct Motion {
  int joint = -1;
  JointCoordinate coordinate = JointCoordinate::Angle;
  Table table;           ///< one component
  /// The table is the coordinate's rate: the coordinate is its exact integral from the start
  /// time (zero there, the initial configuration), the rate the table, the acceleration its slope.
  bool speed = false;
  double start = 0;      ///< the start time (for a speed)
  int block = -1;
};

/// Tension F = f(l - length0) + g(l_dot) + preload along the line of two points, f and g linear
/// (k, c) or tables of the deflection and of the rate (MODEL_FILE.md "Forces").
struct SpringDamper {
  std::string name;
  int m1 = -1, m2 = -1;
  double k = 0, c = 0, length0 = 0;
  Table force_table;    ///< deflection l - length0 -> force (replaces k when not empty)
  Table damping_table;  ///< rate l_dot -> force (replaces c when not empty)
  double preload = 0;   ///< constant tension [N]
};

/// Coulomb friction along the line of two points (a friction damper): its tension opposes the
/// rate of change of their distance with magnitude `force`. Without a series spring, regularised:
/// T = force clamp(l_dot / velocity_tolerance, -1, 1). With a series spring (a rubber bearing),
/// T = series_stiffness (l - length0 - s) with the slip s of a Jenkins element, exact stick and
/// slip by return mapping (FORMULATION.md section 8, friction dampers).
struct FrictionDamper {
  std::string name;
  int m1 = -1, m2 = -1;
  double force = 0;               ///< Coulomb force [N]
  double series_stiffness = 0;    ///< [N/m]; 0: none
  double velocity_tolerance = 0;  ///< [m/s]; regularisation without a series spring
  double length0 = 0;             ///< initial length: the series spring is unloaded there
};

/// Linear 6-DOF bushing: force and torque from the displacement and small rotation of marker 2
/// relative to marker 1, resolved in marker 1's triad.
struct Bushing {
  std::string name;
  int m1 = -1, m2 = -1;
  Vector6d k = Vector6d::Zero(), c = Vector6d::Zero();
  Vector6d s0 = Vector6d::Zero();  ///< measures in the initial configuration (the unloaded state)
  /// Per axis (x, y, z, rx, ry, rz): a characteristic of the measure's change from s0 (force or
  /// torque), replacing that axis's k when not empty.
  std::array<Table, 6> tables;
  Vector6d preload = Vector6d::Zero();  ///< constant force and torque (bushing axes) added to each axis
};

/// A force or torque (global components) at a marker, from a time table with 3 components.
struct PointLoad {
  std::string name;
  int marker = -1;
  bool torque = false;
  Table table;
};

/// A road (MODEL_FILE.md "Roads"): a height profile along a horizontal travel direction, the same
/// across it. A point x of the road plane has s = x . direction and lies `height(s)` above the
/// global origin along `up` (against gravity).
struct Road {
  std::string name;
  Vector3d direction = Vector3d::UnitX();  ///< unit, normal to gravity
  Vector3d up = Vector3d::UnitZ();         ///< unit, against gravity
  Table profile;                           ///< s -> height, one component
};

/// A tyre (tire.cpp, FORMULATION.md section 8, tyres): a disc wheel of `radius` about the spin
/// axis of its marker (axis e, at the wheel centre) in point contact with a road. Normal force
/// k delta + c delta_dot in contact (never pulling); horizontal forces from the slips, saturated at
/// friction times the normal force; without slip stiffnesses the normal force alone.
struct Tire {
  std::string name;
  int marker = -1;                 ///< at the wheel centre; axis 0 the spin axis
  int road = -1;                   ///< index into Model::roads
  double radius = 0;
  double vertical_stiffness = 0, vertical_damping = 0;  ///< [N/m], [N s/m]
  double longitudinal_stiffness = 0;                    ///< [N per unit slip]; 0: none
  double cornering_stiffness = 0;                       ///< [N/rad]; 0: none
  double friction = 0;                                  ///< mu
  double velocity_tolerance = 0.1;                      ///< [m/s]: the slips' speed regularisation
};

enum class OutputType {
  NodeDeformation, NodePosition, ModalCoordinates, JointCoordinate, Energy,
  JointRate, JointReaction, NodeVelocity, BodyAngularVelocity, ElementForce
};
/// Which list an element_force output reads (Output::element indexes it).
enum class ForceElementKind { SpringDamper, Bushing, FrictionDamper, Tire };

struct Output {
  std::string name;
  OutputType type = OutputType::Energy;
  int body = -1, node = -1, joint = -1;
  Vector3d point = Vector3d::Zero();     ///< local point of a node_position on a rigid body
  std::vector<JointCoordinate> coords;  ///< for JointCoordinate and JointRate
  int size = 0;
  ForceElementKind element_kind = ForceElementKind::SpringDamper;  ///< for ElementForce
  int element = -1;                     ///< index into Model::springs, bushings, friction_dampers or tires
};

/// Constraint equations come in blocks that touch at most two bodies (a coupler's row three: its
/// two joints' bodies), whose columns of the dense Jacobian they fill; the tangent is assembled
/// from small products over the pairs of a block's bodies.
enum class BlockKind { RigidBody, Joint, Motion, Coupler };
struct ConstraintBlock {
  BlockKind kind = BlockKind::Joint;
  int index = -1;                 ///< body, joint or motion index
  int row0 = 0, rows = 0;
  int body1 = kGround, body2 = kGround;
  /// A joint's block holds its rows [first, first + rows). A frame-locked body's prismatic joint
  /// to the ground is split in two: its two translational rows, then its three rotational rows,
  /// which hold while the frames are known (held_by_lock, see order_blocks).
  int first = 0;
  bool held_by_lock = false;
  /// A coupler's third and fourth bodies (a belt between two shafts turning in a moving body, or
  /// each in its own housing): its two joints' bodies besides the ground are body1, body2,
  /// body3, body4 in the order met.
  int body3 = kGround, body4 = kGround;
};

/// The step's integration scheme (FORMULATION.md section 9, scheme.hpp).
enum class Integrator { Trapezoidal, GeneralizedAlpha };

/// The coordinates the step integrates (FORMULATION.md section 18): the bodies' natural
/// coordinates, or joint coordinates over a spanning tree (relative.hpp); Auto picks one by the
/// rule of relative.hpp (choose_formulation) when the model is finalized.
enum class Formulation { Absolute, Relative, Auto };
struct RelativeTree;

struct SolverSettings {
  double start = 0.0;
  double end = 1.0;
  double step = 1e-3;            ///< fixed step; with `adaptive`, the first step tried
  // Scheme and step control (scheme.hpp, step_control.cpp).
  Integrator integrator = Integrator::Trapezoidal;
  double spectral_radius = 1.0;  ///< generalized-alpha rho_inf in [0, 1] (1: no numerical damping)
  bool adaptive = false;         ///< "step": "auto": steps chosen by the local error estimate
  double rtol = 1e-6;            ///< adaptive: relative tolerance of the local error
  double atol = -1;              ///< adaptive: absolute tolerance [m]; < 0: rtol times the model length
  double output_interval = 0;    ///< adaptive: time between recorded samples (the steps land on them)
  double max_step = 0;           ///< adaptive: largest step (0: the output interval)
  int output_every = 1;          ///< record every n-th step
  double tolerance = 1e-12;      ///< constraint violation left by Newton and the projections (model lengths)
  /// Newton: estimated error of the accepted coordinates (scaled: lengths / model length, frame
  /// vectors, modal amplitudes / y_scale). Far below a step's truncation error, far above round-off.
  double newton_tolerance = 1e-10;
  int max_iterations = 30;  ///< at most kMaxNewtonIterations
  double penalty = 1e4;          ///< alpha * h^2/4 relative to the mean body mass (FORMULATION.md 9)
  /// Keep the factorised tangent over steps while Newton converges fast (it is refreshed as
  /// soon as an iteration contracts slowly). Off (default): a fresh tangent every step. The
  /// penalty dominates the tangent, so a tangent older than a step is only good when no body
  /// turns by more than ~1/penalty radians per step. Not accuracy-preserving in general (the
  /// model file refuses it, MODEL_FILE.md); kept for the step benchmark's comparison.
  bool reuse_jacobian = false;
  /// Take the coordinates of driven bodies (see Drive) out of the unknowns of the step: they
  /// follow their joint and motion exactly, and the constraints among the ground and driven
  /// bodies alone drop out. Off: every body is integrated (the reference the tests compare with).
  bool eliminate_driven = true;
  /// "analysis": "static": solve the equilibrium at the start time and record it alone.
  bool static_analysis = false;
  /// "initial_equilibrium": settle statically before the dynamic run.
  bool initial_equilibrium = false;
  /// Acceptance and tangent-refresh rules of the step (step_policy.hpp); not in the model file.
  StepPolicy policy;
  /// "formulation" (FORMULATION.md section 18). Relative (or Auto choosing it) implies
  /// eliminate_driven = false: every body's natural coordinates are reconstructed each step.
  Formulation formulation = Formulation::Absolute;
};

/// At most this many coordinates in a model (finalize refuses more): the step holds dense
/// coordinate-by-coordinate matrices (K, C, W, T and the tangent's LU; the constraint Jacobian and
/// the projections' matrices of as many rows), about 1 GB at this size, and a model far beyond it
/// spent minutes zeroing them before it ran out of memory.
constexpr int kMaxModelCoordinates = 5000;

/// The largest `solver.max_iterations` a model file may set (Newton iterations a step).
constexpr int kMaxNewtonIterations = 1000;

/// The largest `solver.penalty`: the rounding of the constraint forces grows with it and beyond
/// it costs accuracy (Andrews' mechanism at h = 1e-5 s: 1e9 ends 4e-9 rad from the default,
/// 1e10 7e-7, 1e11 5e-5, a sixth of the step's own error; tests/runtime/andrews_options_test.cpp).
constexpr double kMaxPenalty = 1e9;

/// The loosest constraint `tolerance` (model lengths): a looser one costs accuracy (Andrews'
/// mechanism at h = 1e-5 s: 1e-8 ends 7e-9 rad from the default, 1e-7 3e-7, 1e-6 9e-6, 3 % of the
/// step's own error, 1e-3 44 %; tests/runtime/andrews_options_test.cpp).
constexpr double kMaxConstraintTolerance = 1e-8;

/// A tolerance in model lengths (the constraints' `tolerance`, Newton's `newton_tolerance`) below
/// this asks for more than the coordinates' rounding, about 1e-16 of their size, resolves: only
/// an increment or violation that happens to be zero meets it.
constexpr double kRoundOffTolerance = 1e-15;

/// A step spans at least this many spacings of the doubles near the run's times, so that t + h
/// is the step's end to 1e-5 of the step. Far from t = 0 (from t = 1e15 s doubles are 0.125 s
/// apart) a smaller step moves t by a rounded amount or not at all: the tables and motions are
/// read at wrong times, and an adaptive run whose steps no longer advance t never ends.
constexpr double kMinStepInTimeSpacings = 1e5;

/// The smallest step the times of a run from `start` to `end` resolve: kMinStepInTimeSpacings
/// spacings of the doubles at the larger of |start| and |end|.
inline double time_resolution_step(double start, double end) {
  const double t = std::max(std::abs(start), std::abs(end));
  return kMinStepInTimeSpacings * (std::nextafter(t, HUGE_VAL) - t);
}

struct Model {
  std::string source;            ///< model file (for messages)
  /// The SID files the flexible bodies were read from, as opened (against the model file's
  /// folder): the tools refuse an output that names one.
  std::vector<std::string> sid_files;
  Vector3d gravity = Vector3d::Zero();
  std::vector<Body> bodies;
  std::vector<Marker> markers;
  std::vector<Joint> joints;
  std::vector<Motion> motions;
  std::vector<Coupler> couplers;
  std::vector<SpringDamper> springs;
  std::vector<Bushing> bushings;
  std::vector<PointLoad> loads;
  std::vector<Road> roads;
  std::vector<Tire> tires;
  std::vector<FrictionDamper> friction_dampers;
  std::vector<Output> outputs;
  SolverSettings settings;
  /// Geometrically exact beams (beam.hpp): their nodes are among `bodies`, their elements
  /// force elements between them (FORMULATION.md 17).
  std::vector<GeBeam> ge_beams;

  // Filled by finalize(). Coordinates: the bodies that are integrated first (nfree numbers),
  // the driven ones after them; the frame vectors of frame-locked bodies among the first are
  // known too (nunknown unknowns). Constraint blocks: those that involve an integrated body first
  // (nactive rows in active_blocks blocks), then those among the ground and driven bodies only,
  // which hold by construction once the driven bodies follow their drives.
  std::vector<ConstraintBlock> blocks;
  int nfree = 0;
  int nunknown = 0;              ///< unknowns of the step: nfree less 9 per frame-locked body
  int nactive = 0;
  int active_blocks = 0;
  /// Per body, where external loads (C API) can act: slot 0 the frame origin, 1 + p node p.
  std::vector<std::vector<Marker>> load_slots;
  int ncoord = 0;
  int nconstraints = 0;
  double length = 1.0;           ///< characteristic length (constraint and convergence scaling)
  /// Per coordinate, the weight of its Newton increment in the convergence tests (scaled_norm):
  /// sqrt(M_jj / m) / length from its own diagonal mass M_jj in its body of mass m, so an
  /// increment counts by the displacement of the body's mass it causes; a frame vector's at
  /// least by the farthest marker along its axis (where joints and forces act).
  VectorXd increment_weight;
  double mass = 1.0;             ///< mean body mass (penalty scaling)
  std::vector<std::string> notes;  ///< things the set-up changed or assumed, for the caller to show
  /// The relative formulation's spanning tree (relative.hpp), set by finalize() when the
  /// formulation is (or Auto chose) Relative; null for the absolute one.
  std::shared_ptr<const RelativeTree> relative;

  int find_body(const std::string& n) const;
  int find_joint(const std::string& n) const;
  int find_output(const std::string& n) const;
};

/// Offsets, constraint blocks and scales. Call after filling bodies/markers/joints/motions.
/// Throws ModelError on inconsistent contents (e.g. a motion on a spherical joint).
void finalize(Model& model);

/// Constraint rows of a joint type (without its motion).
int joint_rows(JointType t);

}  // namespace ffr::runtime
