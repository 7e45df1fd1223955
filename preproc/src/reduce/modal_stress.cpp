// Modal stress recovery: element stresses at the stiffness-rule points, extrapolated to the
// nodes through the linear (corner) shape functions, averaged over the elements at a node
// (modal_stress.hpp says why this is the CalculiX/Abaqus way); shells on their top, middle and
// bottom surfaces from their resultants (shell_stress_map).
#include "ffr/preproc/reduce/modal_stress.hpp"

#include "../assembly/sections.hpp"
#include "../assembly/sub_elements.hpp"
#include "ffr/formats/h5.hpp"
#include "ffr/preproc/elements/shell.hpp"
#include "ffr/preproc/elements/solid.hpp"
#include "ffr/preproc/elements/solid_shape.hpp"
#include "ffr/preproc/visual/visual.hpp"

#include <Eigen/QR>

#include <algorithm>
#include <cstdint>
#include <map>
#include <unordered_map>

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

constexpr char kInSolid = 1, kInShell = 2;

// Per mesh node: kInSolid | kInShell for the element kinds that hold it (beams carry no stress
// at a node).
std::vector<char> carrier_mask(const FeModel& model) {
  const Mesh& mesh = *model.mesh;
  std::vector<char> carries(static_cast<std::size_t>(mesh.num_nodes()), 0);
  for (const auto& pb : model.blocks) {
    if (pb.kind == ElementKind::Beam) continue;
    for (Index i : mesh.blocks[pb.block].conn) carries[static_cast<std::size_t>(i)] |= pb.kind == ElementKind::Solid ? kInSolid : kInShell;
  }
  return carries;
}

// A first-order shell element (a second-order one is its sub-elements, as the assembly
// computes it: src/assembly/sub_elements.hpp).
struct ShellFacet {
  ElementType type;
  std::size_t property = 0;
  std::vector<Index> nodes;
};

std::vector<ShellFacet> shell_facets(const FeModel& model) {
  const Mesh& mesh = *model.mesh;
  std::vector<ShellFacet> out;
  for (const auto& pb : model.blocks) {
    if (pb.kind != ElementKind::Shell) continue;
    const auto& blk = mesh.blocks[pb.block];
    const detail::SubElements sub = detail::sub_elements(blk.type);
    for (Index e = 0; e < blk.size(); ++e) {
      const Index* c = blk.element(e);
      for (const auto& local : sub.nodes) {
        ShellFacet f{sub.type, pb.property, {}};
        for (int i : local) f.nodes.push_back(c[i]);
        out.push_back(std::move(f));
      }
    }
  }
  return out;
}

// +1 or -1 per facet so that the signed normals form one orientation of each connected shell
// surface: neighbours across an edge run along it in opposite directions. The first facet of
// each piece keeps the mesh's orientation. gmsh orients each geometric surface on its own (a
// cylinder and its end disc may face opposite ways), so "top" at a node where surfaces meet
// needs this; at an edge of three or more facets (a T-joint) the first neighbour reached decides.
std::vector<int> orient(const std::vector<ShellFacet>& facets) {
  std::unordered_map<std::uint64_t, std::vector<std::pair<std::size_t, bool>>> edges;  // facet, runs low -> high
  auto key = [](Index a, Index b) {
    return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | static_cast<std::uint64_t>(std::max(a, b));
  };
  for (std::size_t f = 0; f < facets.size(); ++f) {
    const auto& n = facets[f].nodes;
    for (std::size_t i = 0; i < n.size(); ++i) {
      const Index a = n[i], b = n[(i + 1) % n.size()];
      edges[key(a, b)].emplace_back(f, a < b);
    }
  }
  std::vector<int> sign(facets.size(), 0);
  std::vector<std::size_t> queue;
  for (std::size_t seed = 0; seed < facets.size(); ++seed) {
    if (sign[seed] != 0) continue;
    sign[seed] = 1;
    queue.assign(1, seed);
    while (!queue.empty()) {
      const std::size_t g = queue.back();
      queue.pop_back();
      const auto& n = facets[g].nodes;
      for (std::size_t i = 0; i < n.size(); ++i) {
        const Index a = n[i], b = n[(i + 1) % n.size()];
        const bool runs_up = (a < b) == (sign[g] > 0);  // direction of the oriented facet along the edge
        for (const auto& [h, up] : edges[key(a, b)]) {
          if (sign[h] != 0) continue;
          sign[h] = up != runs_up ? 1 : -1;
          queue.push_back(h);
        }
      }
    }
  }
  return sign;
}

}  // namespace

std::vector<Index> stress_nodes(const FeModel& model) {
  const Mesh& mesh = *model.mesh;
  const PartSpec& part = *model.part;
  const StressSpec& spec = *part.stress;
  const std::vector<char> carries = carrier_mask(model);
  std::vector<Index> out;
  if (spec.surface) {
    std::vector<Index> vertices;
    surface_with_modes(model, Eigen::MatrixXd(model.num_dofs, 0), &vertices);
    for (Index n : vertices)
      if (carries[static_cast<std::size_t>(n)]) out.push_back(n);
    if (out.empty())
      throw FormatError(part.file.string(), "stress.surface",
                        "the outer surface has no node of a solid or shell element (stress is recovered in solids "
                        "and shells only)");
    return out;
  }
  const auto it = mesh.node_groups.find(spec.group);
  if (it == mesh.node_groups.end()) {
    std::string known;
    for (const auto& [name, nodes] : mesh.node_groups) known += (known.empty() ? "" : ", ") + name;
    throw FormatError(part.file.string(), "stress.group", "no group '" + spec.group + "' in the mesh (groups: " + known + ")");
  }
  for (Index n : it->second) {
    if (!carries[static_cast<std::size_t>(n)])
      throw FormatError(part.file.string(), "stress.group",
                        "node " + std::to_string(mesh.node_tag(n)) + " of group '" + spec.group +
                            "' belongs to no solid or shell element (stress is recovered in solids and shells "
                            "only, not in beams)");
    out.push_back(n);
  }
  if (out.empty()) throw FormatError(part.file.string(), "stress.group", "group '" + spec.group + "' has no nodes");
  return out;
}

formats::ModalStress recover_modal_stress(const FeModel& model, const Eigen::MatrixXd& Phi, const std::vector<Index>& nodes) {
  const Mesh& mesh = *model.mesh;
  const PartSpec& part = *model.part;
  const Index nq = Phi.cols();
  const std::vector<char> carries = carrier_mask(model);

  // Rows: a node of solids has one (the 3-D stress), a node of shells three (top, middle,
  // bottom), a node of both has four; in the order of `nodes`.
  std::vector<Index> solid_row(static_cast<std::size_t>(mesh.num_nodes()), -1), shell_row = solid_row;
  std::vector<Index> row_node;
  std::vector<std::int64_t> layer;
  for (Index n : nodes) {
    const char c = carries[static_cast<std::size_t>(n)];
    if (c & kInSolid) {
      solid_row[static_cast<std::size_t>(n)] = static_cast<Index>(row_node.size());
      row_node.push_back(n);
      layer.push_back(formats::kSolid);
    }
    if (c & kInShell) {
      shell_row[static_cast<std::size_t>(n)] = static_cast<Index>(row_node.size());
      for (const auto l : {formats::kShellTop, formats::kShellMiddle, formats::kShellBottom}) {
        row_node.push_back(n);
        layer.push_back(l);
      }
    }
  }
  const auto ns = static_cast<Index>(row_node.size());
  bool any_shell = false;
  for (const auto l : layer) any_shell = any_shell || l != formats::kSolid;

  formats::ModalStress out;
  out.selection = part.stress && !part.stress->surface ? "group:" + part.stress->group : "surface";
  out.recovery =
      "stress at the stiffness-rule points extrapolated to the nodes by the linear shape functions "
      "(least squares), plain mean over the solid elements at the node";
  if (any_shell)
    out.recovery +=
        "; shells: resultants at the in-plane integration points extrapolated to the corners by the corner shape "
        "functions, plane stress through the thickness (top/bottom: membrane +- bending, middle: membrane and the "
        "peak transverse shear 3Q/2t), plain mean over the shell elements at the node, oriented to the node's normal";
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
      for (int a = 0; a < nn && !touches; ++a) touches = solid_row[static_cast<std::size_t>(c[a])] >= 0;
      if (!touches) continue;
      const Eigen::MatrixX3d xe = mesh.element_coords(blk, e);
      for (int a = 0; a < nn; ++a)
        if (solid_row[static_cast<std::size_t>(c[a])] >= 0) ++count[static_cast<std::size_t>(solid_row[static_cast<std::size_t>(c[a])])];
      for (Index k = 0; k < nq; ++k) {
        for (int a = 0; a < nn; ++a)
          for (int i = 0; i < 3; ++i) d(3 * a + i) = Phi(model.dof(c[a], i), k);
        const Eigen::MatrixXd nodal = solid_stress(blk.type, xe, mat, d, solid_options(blk)).sigma * X.transpose();  // 6 x nn
        auto& m = out.modes[static_cast<std::size_t>(k)];
        for (int a = 0; a < nn; ++a) {
          const Index s = solid_row[static_cast<std::size_t>(c[a])];
          if (s >= 0) m.row(s) += nodal.col(a).transpose();
        }
      }
    }
  }

  formats::ModalStress::RowsX3 normal = formats::ModalStress::RowsX3::Zero(ns, 3);
  if (any_shell) {
    const std::vector<ShellFacet> facets = shell_facets(model);
    const std::vector<int> sign = orient(facets);
    Eigen::MatrixXd De;
    for (std::size_t f = 0; f < facets.size(); ++f) {
      const ShellFacet& fa = facets[f];
      const int nn = static_cast<int>(fa.nodes.size());
      bool touches = false;
      for (int a = 0; a < nn && !touches; ++a) touches = shell_row[static_cast<std::size_t>(fa.nodes[static_cast<std::size_t>(a)])] >= 0;
      if (!touches) continue;
      Eigen::MatrixX3d xs(nn, 3);
      De.resize(6 * nn, nq);
      for (int a = 0; a < nn; ++a) {
        const Index node = fa.nodes[static_cast<std::size_t>(a)];
        xs.row(a) = mesh.x.row(node);
        for (int i = 0; i < 6; ++i) De.row(6 * a + i) = Phi.row(model.dof(node, i));
      }
      const ShellStressMap map = shell_stress_map(fa.type, xs, detail::shell_section(part.shells[fa.property]));
      // On an element whose normal opposes the oriented surface's, its top is the surface's bottom.
      const bool flip = sign[f] < 0;
      const Eigen::MatrixXd top = (flip ? map.bottom : map.top) * De, mid = map.middle * De,
                            bot = (flip ? map.top : map.bottom) * De;  // 6n x nq
      for (int a = 0; a < nn; ++a) {
        const Index s = shell_row[static_cast<std::size_t>(fa.nodes[static_cast<std::size_t>(a)])];
        if (s < 0) continue;
        normal.row(s) += sign[f] * map.normal.transpose();
        for (Index r = s; r < s + 3; ++r) ++count[static_cast<std::size_t>(r)];
        for (Index k = 0; k < nq; ++k) {
          auto& m = out.modes[static_cast<std::size_t>(k)];
          m.row(s) += top.block(6 * a, k, 6, 1).transpose();
          m.row(s + 1) += mid.block(6 * a, k, 6, 1).transpose();
          m.row(s + 2) += bot.block(6 * a, k, 6, 1).transpose();
        }
      }
    }
  }
  for (Index i = 0; i < ns; ++i) {
    const double w = 1.0 / count[static_cast<std::size_t>(i)];  // every row's node is in such an element (stress_nodes)
    for (auto& m : out.modes) m.row(i) *= w;
  }
  out.node.resize(static_cast<std::size_t>(ns));
  out.position.resize(ns, 3);
  for (Index i = 0; i < ns; ++i) {
    const Index n = row_node[static_cast<std::size_t>(i)];
    out.node[static_cast<std::size_t>(i)] = static_cast<std::int64_t>(mesh.node_tag(n));
    out.position.row(i) = mesh.x.row(n);
  }
  if (any_shell) {
    // The node's normal: the mean of its oriented elements' normals (the rows of a node's three
    // layers share it).
    for (Index i = 0; i < ns; ++i) {
      if (layer[static_cast<std::size_t>(i)] != formats::kShellTop) continue;
      const double len = normal.row(i).norm();
      if (len > 0) normal.row(i) /= len;
      normal.row(i + 1) = normal.row(i + 2) = normal.row(i);
    }
    out.layer = std::move(layer);
    out.normal = std::move(normal);
  }
  return out;
}

}  // namespace ffr::preproc
