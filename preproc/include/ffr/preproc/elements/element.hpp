#pragma once
// The interface every element kernel implements (solids, shells, beams, attached masses).
//
// DOF layout: an element's DOF vector d_e stacks its nodes in gmsh order; each node has
// `dofs_per_node` DOFs in *global (body-frame) axes*: 3 = (ux, uy, uz) for solids,
// 6 = (ux, uy, uz, rx, ry, rz) for shells and beams (small rotations).
//
// Mass is described twice, consistently:
//  - M, the consistent mass matrix (what the eigen-solver uses), and
//  - mass samples: an exact quadrature of the element's distributed mass. Each sample is a
//    material point (weight w = dm, undeformed position c, and N, the 3 x ndof map from d_e to
//    the point's displacement u = N d_e, including fibre offsets: u = u_node + theta x e).
//    Then  M = sum_g w N_g^T N_g + M_rotary  exactly, and every inertia invariant of
//    formats/SPEC.md section 8 is an exact sum over samples (no nodal lumping).
//  - M_rotary: mass that no material point carries (e.g. the drilling inertia a shell adds
//    so that M stays definite); it enters the SID's "rotary part". Empty when there is none.

#include <Eigen/Core>

#include <stdexcept>
#include <string>
#include <vector>

namespace ffr::preproc {

struct Material {
  double E = 0, nu = 0, rho = 0;
};

struct MassSample {
  double w = 0;                                   ///< mass of the sample [kg]
  Eigen::Vector3d c = Eigen::Vector3d::Zero();    ///< undeformed position
  Eigen::Matrix<double, 3, Eigen::Dynamic> N;     ///< 3 x ndof: u(c) = N d_e
};

struct ElementMatrices {
  int dofs_per_node = 3;
  Eigen::MatrixXd K;         ///< ndof x ndof, symmetric positive semi-definite
  Eigen::MatrixXd M;         ///< ndof x ndof, consistent mass (samples + rotary)
  Eigen::MatrixXd M_rotary;  ///< ndof x ndof or empty
  std::vector<MassSample> samples;
};

/// Thrown by kernels for degenerate or inverted geometry or bad properties. The assembly
/// adds the element's tag and group to the message.
class ElementError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace ffr::preproc
