#pragma once
// Large-deformation thin plates: the ANCF thin (Kirchhoff) plate element after Dmitrochenko &
// Pogorelov, in its conforming 48-coordinate form (FORMULATION.md section 16). Each node of a
// structured grid carries its global position r and the gradients r_x, r_y, r_xy along the plate's
// material axes (12 coordinates); an element interpolates them by products of cubic Hermite
// polynomials (the Bogner-Fox-Schmit rectangle), so a material point's position is linear in the
// coordinates and the mass matrix is constant. The elastic energy is the membrane (Green) strain
// and the bending strain from the second derivatives projected on the unit normal:
//   U = int 1/2 eps^T C_m eps + 1/2 kappa^T C_b kappa dA,
//   eps = ((r_x.r_x - 1)/2, (r_y.r_y - 1)/2, r_x.r_y),  kappa = (r_xx.n, r_yy.n, r_xy.n),
//   n = r_x x r_y / |r_x x r_y|.
// In the runtime a plate is a flexible Body like a beam (beam.hpp): its frame is the global frame,
// held by twelve linear rows, to which its edge supports add linear rows (Body::frame_rows); its
// "modal" coordinates y are the nodal coordinates less their reference values q0 (Body::plate).

#include <Eigen/Core>

#include <string>
#include <vector>

namespace ffr::runtime {

struct Body;

/// One linear row of a plate's supports: scale * dir . y[index .. index + 2] = 0.
struct PlateSupportRow {
  int index = 0;                             ///< first of the three coordinates of y
  Eigen::Vector3d dir = Eigen::Vector3d::Zero();
  bool slope = false;                        ///< a gradient (dimensionless): scaled by the model length
};

/// The element data of one plate (constant).
struct AncfPlate {
  int nx = 0, ny = 0;          ///< elements along the material x (corner 0 to 1) and y (corner 0 to 3) axes
  double a = 0, b = 0;         ///< side lengths [m]
  double thickness = 0;        ///< [m]
  double E = 0, nu = 0;
  double rhoh = 0;             ///< mass per area [kg/m^2]
  /// Strain-rate (Kelvin-Voigt) damping time [s]: the damping stresses are tau times the
  /// elastic ones of the membrane strain and curvature rates.
  double tau = 0;
  Eigen::Vector3d e1, e2, e3;  ///< the material axes and the reference normal (global)
  Eigen::VectorXd q0;          ///< reference coordinates [12 nodes]: node k at 12k: r, r_x, r_y, r_xy
  std::vector<PlateSupportRow> supports;
  int nodes() const { return (nx + 1) * (ny + 1); }
  int nq() const { return 12 * nodes(); }
  int node(int i, int j) const { return j * (nx + 1) + i; }  ///< grid node (i along x, j along y)
  double dx() const { return a / nx; }
  double dy() const { return b / ny; }
};

/// How an edge of a plate is held (FORMULATION.md 16, supports).
enum class PlateSupport { Free, SimplySupported, Clamped };

/// A plate body: the flat rectangle with corners c[0] .. c[3] (in order round it: c[0] to c[1]
/// the x axis, c[0] to c[3] the y axis), nx x ny elements, thickness h, its edges held as
/// `edges` says (x0: x = 0, x1: x = a, y0: y = 0, y1: y = b). Its inertia is the FFR body's shape
/// integrals (formats/SPEC.md section 7 with Phi = the shape functions); its nodes are
/// n<i>_<j> (i = 0 .. nx, j = 0 .. ny). Throws ModelError (file, field) on degenerate input: too
/// few elements, coincident corners, corners off one plane or not a rectangle.
Body make_plate_body(const std::string& name, const Eigen::Vector3d (&c)[4], int nx, int ny, double h, double E, double nu,
                     double rho, double tau, const PlateSupport (&edges)[4], const std::string& file, const std::string& field);

/// The elastic and damping forces of a plate at y (coordinates less q0) and y_dot: Qy -= their
/// generalized force; with K and C (nq x nq, may be null) their tangents -dQ/dy, -dQ/dy_dot
/// added (the damping's dependence on y is left out of K: a Newton rate, not the solution).
/// Returns the strain energy. Allocation-free.
double ancf_plate_forces(const AncfPlate& plate, const Eigen::Ref<const Eigen::VectorXd>& y,
                         const Eigen::Ref<const Eigen::VectorXd>& yd, Eigen::Ref<Eigen::VectorXd> Qy, Eigen::MatrixXd* K,
                         Eigen::MatrixXd* C);

/// The tangents alone: -dQ/dy and -dQ/dy_dot of the elements' forces at y, y_dot added to the
/// nq x nq blocks K and C on the elements' blocks (nothing else is touched). Allocation-free.
void ancf_plate_tangents(const AncfPlate& plate, const Eigen::Ref<const Eigen::VectorXd>& y,
                         const Eigen::Ref<const Eigen::VectorXd>& yd, Eigen::Ref<Eigen::MatrixXd> K,
                         Eigen::Ref<Eigen::MatrixXd> C);

/// The strain energy alone.
double ancf_plate_energy(const AncfPlate& plate, const Eigen::Ref<const Eigen::VectorXd>& y);

/// What plate coordinate k (of y) is, for messages: "node n3_1 slope r_x z".
std::string plate_coordinate_name(const AncfPlate& plate, int k);

}  // namespace ffr::runtime
