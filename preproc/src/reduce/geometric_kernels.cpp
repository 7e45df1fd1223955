#include "geometric_kernels.hpp"

#include "ffr/preproc/elements/solid.hpp"
#include "../assembly/sections.hpp"
#include "../assembly/sub_elements.hpp"

namespace ffr::preproc::detail {

ElementMatrices geometric_element(const FeModel& model, const ElementRef& ref, const Eigen::VectorXd& u) {
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
      em.K = solid_geometric_stiffness(blk.type, xe, model.part->materials[pb.property].mat, d);
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
