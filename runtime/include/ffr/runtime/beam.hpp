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

namespace ffr::runtime {

struct Body;

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

/// The strain energy alone.
double ancf_beam_energy(const AncfBeam& beam, const Eigen::Ref<const Eigen::VectorXd>& y);

}  // namespace ffr::runtime
