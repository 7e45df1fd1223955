#pragma once
// Large-deformation beam bodies: the gradient-deficient ANCF beam element (FORMULATION.md
// section 15). Each node carries its global position r and slope r_x (6 coordinates); an
// element interpolates them by cubic Hermite polynomials, so a material point's position is
// linear in the coordinates and the mass matrix is constant. The elastic energy is the axial
// (Green) strain and the exact curvature of the centre line:
//   U = 1/2 int EA eps^2 + EI kappa^2 dx,  eps = (r_x.r_x - 1)/2,
//   kappa^2 = |r_x x r_xx|^2 / |r_x|^6.
// In the runtime a beam is a flexible Body whose frame is the global frame, held there by
// twelve linear rows (its constraint block), and whose "modal" coordinates y are the nodal
// coordinates less their reference values q0 (Body::beam).

#include <Eigen/Core>

#include <string>
#include <vector>

namespace ffr::runtime {

struct Body;
struct Model;
struct Data;

/// The element data of one beam (constant).
struct AncfBeam {
  int elements = 0;
  double length = 0;        ///< whole beam [m]
  double EA = 0, EI = 0;    ///< axial and bending stiffness
  double rhoA = 0;          ///< mass per length [kg/m]
  /// Strain-rate (Kelvin-Voigt) damping time [s]: the damping stresses are tau times the
  /// elastic ones of the strain and curvature rates.
  double tau = 0;
  Eigen::VectorXd q0;       ///< reference coordinates [6 (elements + 1)]: node k at 6k: r, r_x
  int nq() const { return 6 * (elements + 1); }
  double element_length() const { return length / elements; }
};

/// At most this many elements in an ancf beam (make_beam_body refuses more): its inertia is held
/// as a flexible body's dense shape integrals, about twenty nq x nq matrices, 0.4 GB at 240
/// elements (1446 coordinates, the plate's limit of 121 nodes gives 1452).
constexpr int kMaxAncfBeamElements = 240;

/// A beam body: the straight beam from `start` to `end` in `elements` elements, its inertia as
/// the FFR body's shape integrals (formats/SPEC.md section 7 with Phi = the shape functions),
/// nodes n0 .. nN, start, end. Throws ModelError (file, field) on degenerate input.
Body make_beam_body(const std::string& name, const Eigen::Vector3d& start, const Eigen::Vector3d& end, int elements,
                    double E, double rho, double area, double inertia, double tau, const std::string& file,
                    const std::string& field);

/// The elastic and damping forces of a beam at y (coordinates less q0) and y_dot: Qy -= their
/// generalized force; with K and C (nq x nq, may be null) their tangents -dQ/dy, -dQ/dy_dot
/// added (the damping's dependence on y is left out of K: a Newton rate, not the solution).
/// Returns the strain energy. Allocation-free.
double ancf_beam_forces(const AncfBeam& beam, const Eigen::Ref<const Eigen::VectorXd>& y,
                        const Eigen::Ref<const Eigen::VectorXd>& yd, Eigen::Ref<Eigen::VectorXd> Qy, Eigen::MatrixXd* K,
                        Eigen::MatrixXd* C);

/// What beam coordinate k (of y) is, for messages: "node n3 slope z".
std::string beam_coordinate_name(int k);

/// The nodal index (0 .. elements) of a beam body's node slice (Body::nodes: n0 .. nN, start, end).
inline int beam_node_index(const AncfBeam& beam, int slice) {
  return slice <= beam.elements ? slice : slice == beam.elements + 1 ? 0 : beam.elements;
}

/// The tangents alone: -dQ/dy and -dQ/dy_dot of the elements' forces at y, y_dot added to the
/// nq x nq blocks K and C on the elements' 12 x 12 blocks (nothing else is touched). Allocation-free.
void ancf_beam_tangents(const AncfBeam& beam, const Eigen::Ref<const Eigen::VectorXd>& y,
                        const Eigen::Ref<const Eigen::VectorXd>& yd, Eigen::Ref<Eigen::MatrixXd> K,
                        Eigen::Ref<Eigen::MatrixXd> C);

/// The strain energy alone.
double ancf_beam_energy(const AncfBeam& beam, const Eigen::Ref<const Eigen::VectorXd>& y);

// The geometrically exact (Simo-Reissner) beam in directors (FORMULATION.md section 17). Each
// node carries its position r and three orthonormal directors d1, d2, d3 (d3 the section's
// normal, d1 and d2 its principal axes), exactly the natural coordinates [r0, u, v, w] of a rigid
// body: a node is a rigid body (its lumped mass and section rotary inertia) whose frame-vector
// constraints are the directors' orthonormality, and the elements are force elements between
// consecutive nodes. Rotations are never parametrised (rotationless, after Betsch & Steinmann).

/// One geometrically exact beam (constant): its node bodies and its elements' stiffness.
struct GeBeam {
  std::string name;
  int elements = 0;
  double length = 0;                        ///< whole beam [m]
  std::vector<int> node_bodies;             ///< Model::bodies index of node k (elements + 1)
  Eigen::Vector3d CG = Eigen::Vector3d::Zero();  ///< k G A, k G A, E A (shear 1, shear 2, axial)
  Eigen::Vector3d CK = Eigen::Vector3d::Zero();  ///< E I1, E I2, G J (bending about d1, d2; torsion)
  double tau = 0;                           ///< strain-rate (Kelvin-Voigt) damping time [s]
  /// Each element's strains in the reference configuration (stress-free there), [6, elements]:
  /// Gamma_1..3, K_1..3.
  Eigen::Matrix<double, 6, Eigen::Dynamic> strain0;
  double element_length() const { return length / elements; }
};

/// One element of a geometrically exact beam between nodes a and b, its coordinates q = [r_a,
/// d1_a, d2_a, d3_a, r_b, d1_b, d2_b, d3_b] and rates qd: adds its elastic and damping forces'
/// negative (the energy's gradient plus the damping force) to f; with K, C (may be null) adds
/// their tangents; returns its strain energy. Allocation-free.
double ge_beam_element(const GeBeam& beam, int element, const Eigen::Matrix<double, 24, 1>& q,
                       const Eigen::Matrix<double, 24, 1>& qd, Eigen::Matrix<double, 24, 1>& f,
                       Eigen::Matrix<double, 24, 24>* K, Eigen::Matrix<double, 24, 24>* C);

/// All elements of a beam: with add_q their forces into data.Q, with tangents their -dQ/dq,
/// -dQ/dqd into data.K, data.C (the node bodies' frame columns). Allocation-free.
void ge_beam_forces(const Model& model, const GeBeam& beam, Data& data, bool add_q, bool tangents);
/// The beam's strain energy in the current state.
double ge_beam_energy(const Model& model, const GeBeam& beam, const Data& data);

/// The element's six strains (Gamma_1..3, K_1..3) at coordinates q.
Eigen::Matrix<double, 6, 1> ge_beam_strains(const GeBeam& beam, const Eigen::Matrix<double, 24, 1>& q);

/// An element's relative rotation: the angle [rad] by which the section turns from node a to
/// node b, and the element.
struct ElementTurn {
  int element = -1;
  double angle = 0;
};
/// The element of the beam whose nodes' directors differ by the largest rotation at the model's
/// coordinates q (elements with non-finite coordinates are skipped). Its curvature is
/// theta / sin(theta) times the directors' skew part, singular at theta = pi: an element cannot
/// turn by half a revolution, and Newton fails as one nears it.
ElementTurn ge_beam_largest_turn(const Model& model, const GeBeam& beam, const Eigen::VectorXd& q);

/// What a failing step should say of the model's geometrically exact beams: the element turned
/// furthest at the step's start q0 or at the iterate q, when it turns by more than 120 degrees,
/// and what to do (more elements); empty otherwise.
std::string ge_beam_failure_hint(const Model& model, const Eigen::VectorXd& q0, const Eigen::VectorXd& q);

/// A geometrically exact beam's node bodies (the rigid bodies of nodes n0 .. nN, named
/// "<name>:n<k>") and its element data, from the straight beam from `start` to `end` with the
/// section's d1 axis along `y_axis` (projected normal to the beam). Throws ModelError (file,
/// field) on degenerate input. The node bodies are appended to `nodes` (their indices in the
/// model are the caller's: GeBeam::node_bodies is left empty).
GeBeam make_ge_beam(std::vector<Body>& nodes, const std::string& name, const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                         const Eigen::Vector3d& y_axis, int elements, double E, double G, double rho, double area,
                         double Iy, double Iz, double J, double shear_factor, double tau, const std::string& file,
                         const std::string& field);

}  // namespace ffr::runtime
