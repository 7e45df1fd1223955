// Stress recovery at the stiffness-rule points and the geometric (initial-stress) stiffness.
#include "ffr/preproc/elements/solid.hpp"

#include "isoparametric.hpp"

#include <string>

namespace ffr::preproc {

SolidStress solid_stress(ElementType t, const Eigen::MatrixX3d& xe, const Material& mat,
                         const Eigen::VectorXd& d_e, const SolidOptions& opt) {
  check_solid_material(mat);
  const SolidShape& s = solid_shape(t);
  detail::check_geometry(s, xe);
  const int nn = s.nodes, ng = s.stiffness_rule.size();
  if (d_e.size() != 3 * nn)
    throw ElementError(std::string(name(t)) + " stress: displacement vector has " + std::to_string(d_e.size()) +
                       " entries, expected " + std::to_string(3 * nn));
  const detail::Lame L = detail::lame(mat);
  // U(a, i) = displacement component i of node a.
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> U(d_e.data(), nn, 3);

  const bool bubbles = t == ElementType::Hex8 && opt.hex8_incompatible;
  Eigen::Matrix<double, 3, 3> Ua = Eigen::Matrix3d::Zero();  // bubble amplitudes, row k = mode k
  Eigen::Matrix3d J0inv = Eigen::Matrix3d::Identity();
  double detJ0 = 1;
  if (bubbles) {
    const Eigen::Matrix<double, 9, 1> alpha = detail::hex8_incompatible(s, xe, L).A * d_e;
    for (int k = 0; k < 3; ++k) Ua.row(k) = alpha.segment<3>(3 * k).transpose();
    const Eigen::Matrix3d J0 = detail::hex8_centre_jacobian(xe);
    J0inv = J0.inverse();
    detJ0 = J0.determinant();
  }

  SolidStress out;
  out.x.resize(3, ng);
  out.sigma.resize(6, ng);
  ShapeGradients G(nn, 3);
  for (int g = 0; g < ng; ++g) {
    const Eigen::Matrix3d J = detail::jacobian(xe, s.dN_stiffness[g]);
    detail::physical_gradients(s.dN_stiffness[g], J.inverse(), G);
    Eigen::Matrix3d H = U.transpose() * G;  // H(i, k) = du_i / dx_k
    if (bubbles)
      H += Ua.transpose() *
           detail::hex8_bubble_gradients(s.stiffness_rule.xi[g], J0inv, detJ0, J.determinant());
    const Eigen::Matrix3d eps = 0.5 * (H + H.transpose());
    Eigen::Matrix3d S = 2 * L.mu * eps;
    S.diagonal().array() += L.lambda * eps.trace();
    out.sigma.col(g) = detail::tensor_to_voigt(S);
    out.x.col(g) = xe.transpose() * s.N_stiffness[g];
  }
  return out;
}

Eigen::MatrixXd solid_geometric_stiffness(ElementType t, const Eigen::MatrixX3d& xe,
                                          const Eigen::Matrix<double, 6, Eigen::Dynamic>& sigma) {
  const SolidShape& s = solid_shape(t);
  detail::check_geometry(s, xe);
  const int nn = s.nodes, ng = s.stiffness_rule.size();
  if (sigma.cols() != ng)
    throw ElementError(std::string(name(t)) + " geometric stiffness: stress given at " +
                       std::to_string(sigma.cols()) + " points, the element has " + std::to_string(ng));
  Eigen::MatrixXd KG = Eigen::MatrixXd::Zero(3 * nn, 3 * nn);
  ShapeGradients G(nn, 3);
  for (int g = 0; g < ng; ++g) {
    const Eigen::Matrix3d J = detail::jacobian(xe, s.dN_stiffness[g]);
    detail::physical_gradients(s.dN_stiffness[g], J.inverse(), G);
    detail::add_geometric_stiffness(KG, G, detail::voigt_to_tensor(sigma.col(g)),
                                    s.stiffness_rule.w[g] * J.determinant());
  }
  return KG;
}

Eigen::MatrixXd solid_geometric_stiffness(ElementType t, const Eigen::MatrixX3d& xe, const Material& mat,
                                          const Eigen::VectorXd& d_e, const SolidOptions& opt) {
  return solid_geometric_stiffness(t, xe, solid_stress(t, xe, mat, d_e, opt).sigma);
}

}  // namespace ffr::preproc
