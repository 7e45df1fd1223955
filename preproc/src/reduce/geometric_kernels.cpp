#include "geometric_kernels.hpp"

#include "ffr/preproc/elements/solid.hpp"
#include "../assembly/sections.hpp"
#include "../assembly/sub_elements.hpp"
#include "../elements/solid/isoparametric.hpp"

namespace ffr::preproc::detail {
namespace {

// K_G of a solid at its mass-rule points, for the linear stress of d_e evaluated at the same
// points (as solid_stress does at the stiffness points: HEX8's incompatible modes included).
Eigen::MatrixXd solid_geometric_cubic(ElementType t, const Eigen::MatrixX3d& xe, const Material& mat,
                                      const Eigen::VectorXd& d_e, const SolidOptions& opt) {
  check_solid_material(mat);
  const SolidShape& s = solid_shape(t);
  check_geometry(s, xe);
  const int nn = s.nodes, ng = s.mass_rule.size();
  const Lame L = lame(mat);
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>> U(d_e.data(), nn, 3);
  const bool bubbles = t == ElementType::Hex8 && opt.hex8_incompatible;
  Eigen::Matrix3d Ua = Eigen::Matrix3d::Zero(), J0inv = Eigen::Matrix3d::Identity();
  double detJ0 = 1;
  if (bubbles) {
    const Eigen::Matrix<double, 9, 1> alpha = hex8_incompatible(s, xe, L).A * d_e;
    for (int k = 0; k < 3; ++k) Ua.row(k) = alpha.segment<3>(3 * k).transpose();
    const Eigen::Matrix3d J0 = hex8_centre_jacobian(xe);
    J0inv = J0.inverse();
    detJ0 = J0.determinant();
  }
  Eigen::MatrixXd KG = Eigen::MatrixXd::Zero(3 * nn, 3 * nn);
  ShapeGradients G(nn, 3);
  for (int g = 0; g < ng; ++g) {
    const Eigen::Matrix3d J = jacobian(xe, s.dN_mass[g]);
    physical_gradients(s.dN_mass[g], J.inverse(), G);
    Eigen::Matrix3d H = U.transpose() * G;
    if (bubbles) H += Ua.transpose() * hex8_bubble_gradients(s.mass_rule.xi[g], J0inv, detJ0, J.determinant());
    const Eigen::Matrix3d eps = 0.5 * (H + H.transpose());
    Eigen::Matrix3d S = 2 * L.mu * eps;
    S.diagonal().array() += L.lambda * eps.trace();
    add_geometric_stiffness(KG, G, S, s.mass_rule.w[g] * J.determinant());
  }
  return KG;
}

}  // namespace

ElementMatrices geometric_element(const FeModel& model, const ElementRef& ref, const Eigen::VectorXd& u,
                                  GeometricRule rule) {
  const auto dofs = element_dofs(model, ref);
  ElementMatrices em;
  const auto nd = static_cast<Index>(dofs.size());
  if (ref.block < 0) {
    em.K = Eigen::MatrixXd::Zero(nd, nd);
    return em;
  }
  Eigen::VectorXd d(nd);
  for (Index i = 0; i < nd; ++i) d(i) = u(dofs[static_cast<std::size_t>(i)]);
  const auto& pb = model.blocks[static_cast<std::size_t>(ref.block)];
  const auto& blk = model.mesh->blocks[pb.block];
  const Eigen::MatrixX3d xe = model.mesh->element_coords(blk, ref.index);
  switch (pb.kind) {
    case ElementKind::Solid:
      em.K = rule == GeometricRule::Cubic
                 ? solid_geometric_cubic(blk.type, xe, model.part->materials[pb.property].mat, d, solid_options(blk))
                 : solid_geometric_stiffness(blk.type, xe, model.part->materials[pb.property].mat, d, solid_options(blk));
      break;
    case ElementKind::Shell: {
      const ShellSection sec = shell_section(model.part->shells[pb.property]);
      em.K = composite_matrix(blk.type, xe, d, 6, [&](ElementType t, const Eigen::MatrixX3d& x, const Eigen::VectorXd& ds) {
        return shell_geometric_stiffness(t, x, sec, ds);
      });
      break;
    }
    case ElementKind::Beam: {
      const BeamSection sec = beam_section(model.part->beams[pb.property]);
      em.K = composite_matrix(blk.type, xe, d, 6, [&](ElementType, const Eigen::MatrixX3d& x, const Eigen::VectorXd& ds) {
        return beam_geometric_stiffness(x, sec, ds);
      });
      break;
    }
  }
  return em;
}

}  // namespace ffr::preproc::detail
