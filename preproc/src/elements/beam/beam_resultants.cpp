// Section resultants of a linear beam solution and the geometric stiffness of its axial force.

#include "beam_local.hpp"

#include "../shell/material_check.hpp"

namespace ffr::preproc {

BeamResultants beam_resultants(const Eigen::MatrixX3d& xe, const BeamSection& s, const Eigen::VectorXd& d_e) {
  beam::check_input(xe, s);
  if (d_e.size() != 12)
    structural::fail("beam LINE2", "displacement vector has " + std::to_string(d_e.size()) + " entries, expected 12");
  BeamResultants r;
  r.R = beam_frame(xe, s.y_axis);
  const beam::ShapeParams p = beam::shape_params(xe, s);
  r.length = p.L;
  // Nodal forces on the element; the resultant on the positive face is +f at node 2 and -f at node 1.
  const Eigen::Matrix<double, 12, 1> f = beam::local_stiffness(p, s) * (beam::local_transform(r.R) * d_e);
  r.at1 = -f.head<6>();
  r.at2 = f.tail<6>();
  return r;
}

Eigen::MatrixXd beam_geometric_stiffness(const Eigen::MatrixX3d& xe, const BeamSection& s, double N) {
  beam::check_input(xe, s);
  const Eigen::Matrix3d R = beam_frame(xe, s.y_axis);
  const beam::ShapeParams p = beam::shape_params(xe, s);
  const double polar = (s.Iy + s.Iz) / s.A;
  Eigen::Matrix<double, 12, 12> Kl = Eigen::Matrix<double, 12, 12>::Zero();
  for (int g = 0; g < 4; ++g) {
    const Eigen::Matrix<double, 6, 12> D = beam::interpolation_ds(p, beam::kGauss4X[g]);
    const double w = N * beam::kGauss4W[g] * p.L;
    Kl += w * (D.row(1).transpose() * D.row(1) + D.row(2).transpose() * D.row(2) +
               polar * D.row(3).transpose() * D.row(3));
  }
  const Eigen::Matrix<double, 12, 12> T = beam::local_transform(R);
  return T.transpose() * Kl * T;
}

Eigen::MatrixXd beam_geometric_stiffness(const Eigen::MatrixX3d& xe, const BeamSection& s, const Eigen::VectorXd& d_e) {
  return beam_geometric_stiffness(xe, s, beam_resultants(xe, s, d_e).axial());
}

}  // namespace ffr::preproc
