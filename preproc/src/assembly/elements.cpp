// Which kernel computes which element, and where its DOFs go.
#include "ffr/preproc/assembly/assembly.hpp"
#include "ffr/preproc/elements/attached_mass.hpp"
#include "ffr/preproc/elements/beam.hpp"
#include "ffr/preproc/elements/shell.hpp"
#include "ffr/preproc/elements/solid.hpp"
#include "sections.hpp"
#include "sub_elements.hpp"

namespace ffr::preproc {

namespace {

// A plain point mass on a translational node: one sample at the node, M = m I3.
ElementMatrices point_mass(const Eigen::Vector3d& x, double m) {
  ElementMatrices em;
  em.dofs_per_node = 3;
  em.K = Eigen::MatrixXd::Zero(3, 3);
  em.M = m * Eigen::MatrixXd::Identity(3, 3);
  MassSample s;
  s.w = m;
  s.c = x;
  s.N = Eigen::Matrix3d::Identity();
  em.samples.push_back(s);
  return em;
}

}  // namespace

std::vector<ElementRef> all_elements(const FeModel& model) {
  std::vector<ElementRef> refs;
  for (std::size_t b = 0; b < model.blocks.size(); ++b) {
    const auto n = model.mesh->blocks[model.blocks[b].block].size();
    for (Index e = 0; e < n; ++e) refs.push_back({static_cast<int>(b), e});
  }
  for (std::size_t m = 0; m < model.masses.size(); ++m) refs.push_back({-1, static_cast<Index>(m)});
  return refs;
}

std::vector<Index> element_dofs(const FeModel& model, const ElementRef& ref) {
  std::vector<Index> dofs;
  if (ref.block >= 0) {
    const auto& pb = model.blocks[static_cast<std::size_t>(ref.block)];
    const auto& blk = model.mesh->blocks[pb.block];
    const int per_node = pb.kind == ElementKind::Solid ? 3 : 6;
    const int nn = num_nodes(blk.type);
    for (int i = 0; i < nn; ++i)
      for (int a = 0; a < per_node; ++a) dofs.push_back(model.dof(blk.element(ref.index)[i], a));
    return dofs;
  }
  const auto& m = model.masses[static_cast<std::size_t>(ref.index)];
  if (m.interface >= 0) {
    const Index d0 = model.interfaces[static_cast<std::size_t>(m.interface)].dof;
    for (int a = 0; a < 6; ++a) dofs.push_back(d0 + a);
  } else {
    for (int a = 0; a < model.node_ndof[static_cast<std::size_t>(m.node)]; ++a) dofs.push_back(model.dof(m.node, a));
  }
  return dofs;
}

ElementMatrices element_matrices(const FeModel& model, const ElementRef& ref) {
  const PartSpec& part = *model.part;
  if (ref.block >= 0) {
    const auto& pb = model.blocks[static_cast<std::size_t>(ref.block)];
    const auto& blk = model.mesh->blocks[pb.block];
    const Eigen::MatrixX3d xe = model.mesh->element_coords(blk, ref.index);
    switch (pb.kind) {
      case ElementKind::Solid:
        // Solids need no samples: their inertia integrals follow exactly from the scalar mass
        // matrix Ms (see invariants.hpp), which saves a third of the kernel time on HEX20.
        return solid_element(blk.type, xe, part.materials[pb.property].mat, solid_options(blk, false));
      case ElementKind::Shell: {
        const ShellSection sec = detail::shell_section(part.shells[pb.property]);
        return detail::composite(blk.type, xe, 6, [&](ElementType t, const Eigen::MatrixX3d& x) { return shell_element(t, x, sec); });
      }
      case ElementKind::Beam: {
        const BeamSection sec = detail::beam_section(part.beams[pb.property]);
        return detail::composite(blk.type, xe, 6, [&](ElementType, const Eigen::MatrixX3d& x) { return beam_element(x, sec); });
      }
    }
  }
  const auto& m = model.masses[static_cast<std::size_t>(ref.index)];
  if (m.interface >= 0)
    return attached_mass(model.interfaces[static_cast<std::size_t>(m.interface)].x, m.mass, m.offset, m.inertia);
  const Eigen::Vector3d x = model.mesh->x.row(m.node).transpose();
  if (model.node_ndof[static_cast<std::size_t>(m.node)] == 3) return point_mass(x, m.mass);
  return attached_mass(x, m.mass, m.offset, m.inertia);
}

ElementMatrices element_mass(const FeModel& model, const ElementRef& ref) {
  if (ref.block >= 0) {
    const auto& pb = model.blocks[static_cast<std::size_t>(ref.block)];
    if (pb.kind == ElementKind::Shell) {
      const auto& blk = model.mesh->blocks[pb.block];
      const Eigen::MatrixX3d xe = model.mesh->element_coords(blk, ref.index);
      const ShellSection sec = detail::shell_section(model.part->shells[pb.property]);
      return detail::composite(blk.type, xe, 6,
                               [&](ElementType t, const Eigen::MatrixX3d& x) { return shell_mass_element(t, x, sec); });
    }
  }
  return element_matrices(model, ref);  // beams and attached masses are cheap as they are
}

}  // namespace ffr::preproc
