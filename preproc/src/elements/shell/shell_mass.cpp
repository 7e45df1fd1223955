// Shell mass: material points on the element's (possibly warped, bilinear) mid-surface,
// x(xi, eta) = sum N_i x_i, and along the fibre through it, at z = ±t/(2 sqrt 3) on the element
// normal n (2-point Gauss in the thickness: exact for the quadratic z-terms). A point moves
// with the nodal translations and rotations interpolated by the same N_i as the stiffness:
//     u = sum N_i (u_i + theta_i x z n) = sum N_i (u_i - z ñ theta_i).
// In the plane: 2 x 2 Gauss (QUAD4) or the 3-point rule (TRI3); both integrate N_i N_j,
// c and c c^T exactly on a flat facet (det J is at most linear on a flat quad).
// The drilling rotation moves no material point; a lumped rho t^3/12 int N_i dA about n per
// node keeps M definite and is reported as M_rotary.

#include "shell_mass.hpp"

#include "material_check.hpp"
#include "shape2d.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace ffr::preproc::shell {

void shell_mass(ElementType type, const Eigen::MatrixX3d& xe, const ShellFrame& frame, const ShellSection& s,
                ElementMatrices& out) {
  const int n = static_cast<int>(xe.rows());
  const int ndof = 6 * n;
  const double t = s.thickness, rho = s.material.rho;
  const Eigen::Vector3d nrm = frame.R.row(2).transpose();
  const Rule2 rule = type == ElementType::Quad4 ? quad_gauss2() : tri_rule3();

  out.samples.clear();
  out.M = Eigen::MatrixXd::Zero(ndof, ndof);
  Eigen::VectorXd node_area = Eigen::VectorXd::Zero(n);
  for (std::size_t g = 0; g < rule.xi.size(); ++g) {
    const double xi = rule.xi[g].x(), eta = rule.xi[g].y();
    Eigen::VectorXd N(n);
    Eigen::MatrixXd dN(2, n);
    if (type == ElementType::Quad4) {
      N = quad4_N(xi, eta);
      dN = quad4_dN(xi, eta);
    } else {
      N = tri3_N(xi, eta);
      dN = tri3_dN();
    }
    const Eigen::Vector3d x = xe.transpose() * N;
    const Eigen::Matrix<double, 2, 3> G = dN * xe;  // tangents x,xi and x,eta
    const double dA = G.row(0).cross(G.row(1)).norm() * rule.w[g];
    node_area += dA * N;
    for (double zeta : {-kGauss2, kGauss2}) {
      const double z = 0.5 * t * zeta;
      MassSample smp;
      smp.w = rho * dA * 0.5 * t;
      smp.c = x + z * nrm;
      smp.N = Eigen::MatrixXd::Zero(3, ndof);
      const Eigen::Matrix3d lever = -structural::skew(z * nrm);  // theta x e = -ẽ theta
      for (int i = 0; i < n; ++i) {
        smp.N.block<3, 3>(0, 6 * i) = N(i) * Eigen::Matrix3d::Identity();
        smp.N.block<3, 3>(0, 6 * i + 3) = N(i) * lever;
      }
      out.M.noalias() += smp.w * smp.N.transpose() * smp.N;
      out.samples.push_back(std::move(smp));
    }
  }

  out.M_rotary = Eigen::MatrixXd::Zero(ndof, ndof);
  const Eigen::Matrix3d nn = nrm * nrm.transpose();
  for (int i = 0; i < n; ++i)
    out.M_rotary.block<3, 3>(6 * i + 3, 6 * i + 3) = rho * t * t * t / 12 * node_area(i) * nn;
  out.M += out.M_rotary;
}

}  // namespace ffr::preproc::shell
