// Modal stress recovery: element stresses at the stiffness-rule points, extrapolated to the
// nodes through the linear (corner) shape functions, averaged over the elements at a node
// (modal_stress.hpp says why this is the CalculiX/Abaqus way).
#include "ffr/preproc/reduce/modal_stress.hpp"

#include "ffr/formats/h5.hpp"
#include "ffr/preproc/elements/solid.hpp"
#include "ffr/preproc/elements/solid_shape.hpp"
#include "ffr/preproc/visual/visual.hpp"

#include <Eigen/QR>

#include <map>

namespace ffr::preproc {
namespace {

using formats::FormatError;

ElementType corner_type(ElementType t) {
  switch (t) {
    case ElementType::Tet10: return ElementType::Tet4;
    case ElementType::Hex20: case ElementType::Hex27: return ElementType::Hex8;
    case ElementType::Wedge15: return ElementType::Wedge6;
    default: return t;
  }
}

// E (nodes x points): nodal values = E * values at the stiffness-rule points.
Eigen::MatrixXd extrapolation(ElementType t) {
  const SolidShape& s = solid_shape(t);
  const SolidShape& c = solid_shape(corner_type(t));
  const int ng = static_cast<int>(s.stiffness_rule.size()), nc = c.nodes;
  if (ng < nc) return Eigen::MatrixXd::Constant(s.nodes, ng, 1.0 / ng);  // a one-point rule: the constant
  ShapeValues N(nc);
  ShapeGradients dN(nc, 3);
  Eigen::MatrixXd A(ng, nc), B(s.nodes, nc);
  for (int g = 0; g < ng; ++g) {
    c.eval(s.stiffness_rule.xi[g], N, dN);
    A.row(g) = N.transpose();
  }
  for (int a = 0; a < s.nodes; ++a) {
    Eigen::Vector3d xi = s.reference_nodes[static_cast<std::size_t>(a)];
    // The rational PYRAMID5 basis is 0/0 at the apex; its limit there is N = (0, 0, 0, 0, 1).
    if (t == ElementType::Pyramid5 && xi.z() > 1 - 1e-12) xi.z() = 1 - 1e-9;
    c.eval(xi, N, dN);
    B.row(a) = N.transpose();
  }
  return B * A.colPivHouseholderQr().solve(Eigen::MatrixXd::Identity(ng, ng));
}

}  // namespace

std::vector<Index> stress_nodes(const FeModel& model) {
  const Mesh& mesh = *model.mesh;
  const PartSpec& part = *model.part;
  const StressSpec& spec = *part.stress;
  std::vector<char> in_solid(static_cast<std::size_t>(mesh.num_nodes()), 0);
  for (const auto& pb : model.blocks) {
    if (pb.kind != ElementKind::Solid) continue;
    const auto& blk = mesh.blocks[pb.block];
    for (Index i : blk.conn) in_solid[static_cast<std::size_t>(i)] = 1;
  }
  std::vector<Index> out;
  if (spec.surface) {
    std::vector<Index> vertices;
    surface_with_modes(model, Eigen::MatrixXd(model.num_dofs, 0), &vertices);
    for (Index n : vertices)
      if (in_solid[static_cast<std::size_t>(n)]) out.push_back(n);
    if (out.empty())
      throw FormatError(part.file.string(), "stress.surface",
                        "the outer surface has no node of a solid element (stress is recovered in solids only)");
    return out;
  }
  const auto it = mesh.node_groups.find(spec.group);
  if (it == mesh.node_groups.end()) {
    std::string known;
    for (const auto& [name, nodes] : mesh.node_groups) known += (known.empty() ? "" : ", ") + name;
    throw FormatError(part.file.string(), "stress.group", "no group '" + spec.group + "' in the mesh (groups: " + known + ")");
  }
  for (Index n : it->second) {
    if (!in_solid[static_cast<std::size_t>(n)])
      throw FormatError(part.file.string(), "stress.group",
                        "node " + std::to_string(mesh.node_tag(n)) + " of group '" + spec.group +
                            "' belongs to no solid element (stress is recovered in solids only)");
    out.push_back(n);
  }
  if (out.empty()) throw FormatError(part.file.string(), "stress.group", "group '" + spec.group + "' has no nodes");
  return out;
}

formats::ModalStress recover_modal_stress(const FeModel& model, const Eigen::MatrixXd& Phi, const std::vector<Index>& nodes) {
  const Mesh& mesh = *model.mesh;
  const PartSpec& part = *model.part;
  const Index nq = Phi.cols();
  const auto ns = static_cast<Index>(nodes.size());
  std::vector<Index> slot(static_cast<std::size_t>(mesh.num_nodes()), -1);
  for (Index i = 0; i < ns; ++i) slot[static_cast<std::size_t>(nodes[static_cast<std::size_t>(i)])] = i;

  formats::ModalStress out;
  out.selection = part.stress && !part.stress->surface ? "group:" + part.stress->group : "surface";
  out.recovery =
      "stress at the stiffness-rule points extrapolated to the nodes by the linear shape functions "
      "(least squares), plain mean over the solid elements at the node";
  out.modes.assign(static_cast<std::size_t>(nq), formats::ModalStress::RowsX6::Zero(ns, 6));
  std::vector<int> count(static_cast<std::size_t>(ns), 0);
  std::map<ElementType, Eigen::MatrixXd> E;
  Eigen::VectorXd d;
  for (const auto& pb : model.blocks) {
    if (pb.kind != ElementKind::Solid) continue;
    const auto& blk = mesh.blocks[pb.block];
    const Material& mat = part.materials[pb.property].mat;
    const int nn = num_nodes(blk.type);
    auto e_it = E.find(blk.type);
    if (e_it == E.end()) e_it = E.emplace(blk.type, extrapolation(blk.type)).first;
    const Eigen::MatrixXd& X = e_it->second;
    d.resize(3 * nn);
    for (Index e = 0; e < blk.size(); ++e) {
      const Index* c = blk.element(e);
      bool touches = false;
      for (int a = 0; a < nn && !touches; ++a) touches = slot[static_cast<std::size_t>(c[a])] >= 0;
      if (!touches) continue;
      const Eigen::MatrixX3d xe = mesh.element_coords(blk, e);
      for (int a = 0; a < nn; ++a)
        if (slot[static_cast<std::size_t>(c[a])] >= 0) ++count[static_cast<std::size_t>(slot[static_cast<std::size_t>(c[a])])];
      for (Index k = 0; k < nq; ++k) {
        for (int a = 0; a < nn; ++a)
          for (int i = 0; i < 3; ++i) d(3 * a + i) = Phi(model.dof(c[a], i), k);
        const Eigen::MatrixXd nodal = solid_stress(blk.type, xe, mat, d, solid_options(blk)).sigma * X.transpose();  // 6 x nn
        auto& m = out.modes[static_cast<std::size_t>(k)];
        for (int a = 0; a < nn; ++a) {
          const Index s = slot[static_cast<std::size_t>(c[a])];
          if (s >= 0) m.row(s) += nodal.col(a).transpose();
        }
      }
    }
  }
  for (Index i = 0; i < ns; ++i) {
    const double w = 1.0 / count[static_cast<std::size_t>(i)];  // every node is in a solid (stress_nodes)
    for (auto& m : out.modes) m.row(i) *= w;
  }
  out.node.resize(static_cast<std::size_t>(ns));
  out.position.resize(ns, 3);
  for (Index i = 0; i < ns; ++i) {
    const Index n = nodes[static_cast<std::size_t>(i)];
    out.node[static_cast<std::size_t>(i)] = static_cast<std::int64_t>(mesh.node_tag(n));
    out.position.row(i) = mesh.x.row(n);
  }
  return out;
}

}  // namespace ffr::preproc
