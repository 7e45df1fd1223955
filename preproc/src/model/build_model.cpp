#include "ffr/formats/h5.hpp"
#include "ffr/preproc/model/fe_model.hpp"

#include <Eigen/Geometry>

#include <cstdio>
#include <limits>
#include <numeric>
#include <sstream>
#include <unordered_set>

namespace ffr::preproc {
namespace {

using formats::FormatError;

const char* kind_name(ElementKind k) {
  return k == ElementKind::Solid ? "solid material" : k == ElementKind::Shell ? "shell" : "beam";
}
int kind_dim(ElementKind k) { return k == ElementKind::Solid ? 3 : k == ElementKind::Shell ? 2 : 1; }
const char* dim_name(int d) { return d == 3 ? "volume" : d == 2 ? "surface" : d == 1 ? "curve" : "point"; }

// Adds the blocks of `group` that carry a property of `kind`; checks the group exists and
// has elements of the right dimension.
void add_blocks(const Mesh& mesh, const PartSpec& part, FeModel& model, ElementKind kind, std::size_t prop,
                const std::string& group, const std::string& field) {
  bool found_group = mesh.node_groups.count(group) > 0;
  int other_dim = -1;
  bool added = false;
  for (std::size_t b = 0; b < mesh.blocks.size(); ++b) {
    const auto& blk = mesh.blocks[b];
    if (blk.group != group) continue;
    found_group = true;
    if (dimension(blk.type) != kind_dim(kind)) {
      other_dim = dimension(blk.type);
      continue;
    }
    model.blocks.push_back({kind, b, prop});
    added = true;
  }
  if (!found_group) {
    std::string known;
    for (const auto& [name, nodes] : mesh.node_groups) known += (known.empty() ? "" : ", ") + name;
    throw FormatError(part.file.string(), field, "no group '" + group + "' in the mesh (groups: " + known + ")");
  }
  if (!added) {
    std::string what = "group '" + group + "' has no " + dim_name(kind_dim(kind)) + " elements";
    if (other_dim >= 0) what += " (it is a " + std::string(dim_name(other_dim)) + " group)";
    throw FormatError(part.file.string(), field, what + "; a " + kind_name(kind) + " needs a " +
                                                     dim_name(kind_dim(kind)) + " group");
  }
}

Index nearest_used_node(const FeModel& model, const Eigen::Vector3d& p, double& dist) {
  Index best = -1;
  double best_d2 = std::numeric_limits<double>::infinity();
  const auto& x = model.mesh->x;
  for (Index n = 0; n < x.rows(); ++n) {
    if (model.node_ndof[static_cast<std::size_t>(n)] == 0) continue;
    const double d2 = (x.row(n).transpose() - p).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = n;
    }
  }
  dist = std::sqrt(best_d2);
  return best;
}

// The diagonal of the bounding box of the nodes with DOFs: a point farther than it from every
// such node is not near the part at all (a point in the wrong units or a typo).
double used_node_diagonal(const FeModel& model) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  const auto& x = model.mesh->x;
  for (Index n = 0; n < x.rows(); ++n)
    if (model.node_ndof[static_cast<std::size_t>(n)] > 0) {
      lo = lo.cwiseMin(x.row(n).transpose());
      hi = hi.cwiseMax(x.row(n).transpose());
    }
  return (hi - lo).norm();
}

// The mesh node nearest to `at` (a point mass's or an output node's), refused naming `field`
// when it is farther than the part's diagonal.
Index node_near_the_part(const FeModel& model, const Eigen::Vector3d& at, double diagonal, const std::string& file,
                         const std::string& field, double& dist) {
  const Index n = nearest_used_node(model, at, dist);
  if (!(dist <= diagonal)) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "the nearest mesh node is %g away, more than the diagonal of the part's bounding box (%g): "
                  "'at' is not near the part (in the part's length unit)",
                  dist, diagonal);
    throw FormatError(file, field, buf);
  }
  return n;
}

}  // namespace

int FeModel::find_interface(const std::string& name) const {
  for (std::size_t i = 0; i < interfaces.size(); ++i)
    if (interfaces[i].name == name) return static_cast<int>(i);
  return -1;
}

void FeModel::dof_owner(Index d, Index& owner, int& component, bool& is_interface) const {
  is_interface = d >= mesh_dofs();
  if (is_interface) {
    owner = (d - mesh_dofs()) / 6;
    component = static_cast<int>((d - mesh_dofs()) % 6);
    return;
  }
  owner = dof_node[static_cast<std::size_t>(d)];
  component = static_cast<int>(d - node_dof[static_cast<std::size_t>(owner)]);
}

Eigen::Matrix<double, 1, 6> FeModel::rigid_motion(Index d) const {
  Index owner;
  int comp;
  bool is_itf;
  dof_owner(d, owner, comp, is_itf);
  const Eigen::Vector3d x = is_itf ? interfaces[static_cast<std::size_t>(owner)].x : Eigen::Vector3d(mesh->x.row(owner).transpose());
  Eigen::Matrix<double, 1, 6> r = Eigen::Matrix<double, 1, 6>::Zero();
  r(comp) = 1.0;  // translation DOF under its translation, or rotation DOF under its rotation
  if (comp < 3)
    for (int a = 0; a < 3; ++a) r(3 + a) = Eigen::Vector3d::Unit(a).cross(x)(comp);
  return r;
}

FeModel build_model(const Mesh& mesh, const PartSpec& part) {
  FeModel model;
  model.mesh = &mesh;
  model.part = &part;
  for (std::size_t i = 0; i < part.materials.size(); ++i)
    add_blocks(mesh, part, model, ElementKind::Solid, i, part.materials[i].group, "materials[" + std::to_string(i) + "].group");
  for (std::size_t i = 0; i < part.shells.size(); ++i)
    add_blocks(mesh, part, model, ElementKind::Shell, i, part.shells[i].group, "shells[" + std::to_string(i) + "].group");
  for (std::size_t i = 0; i < part.beams.size(); ++i)
    add_blocks(mesh, part, model, ElementKind::Beam, i, part.beams[i].group, "beams[" + std::to_string(i) + "].group");

  // An element in two groups that both carry properties would be counted twice.
  {
    std::unordered_set<std::size_t> seen;
    for (const auto& pb : model.blocks) {
      const auto& blk = mesh.blocks[pb.block];
      for (Index e = 0; e < blk.size(); ++e) {
        const std::size_t tag = mesh.element_tag(blk, e);
        if (!blk.tags.empty() && !seen.insert(tag).second)
          throw FormatError(part.file.string(), "group " + blk.group,
                            "element " + std::to_string(tag) + " belongs to two groups that both have properties");
      }
    }
  }

  // DOFs per node: 6 where a shell or beam touches the node, else 3 where a solid does.
  model.node_ndof.assign(static_cast<std::size_t>(mesh.num_nodes()), 0);
  for (const auto& pb : model.blocks) {
    const auto& blk = mesh.blocks[pb.block];
    const int ndof = pb.kind == ElementKind::Solid ? 3 : 6;
    for (Index n : blk.conn) {
      auto& d = model.node_ndof[static_cast<std::size_t>(n)];
      d = std::max(d, ndof);
    }
  }
  model.node_dof.assign(model.node_ndof.size(), -1);
  Index next = 0;
  for (std::size_t n = 0; n < model.node_ndof.size(); ++n)
    if (model.node_ndof[n] > 0) {
      model.node_dof[n] = next;
      next += model.node_ndof[n];
      model.dof_node.insert(model.dof_node.end(), static_cast<std::size_t>(model.node_ndof[n]), static_cast<Index>(n));
    }

  // Interfaces: extra 6-DOF nodes after the mesh DOFs.
  for (std::size_t i = 0; i < part.interfaces.size(); ++i) {
    const auto& spec = part.interfaces[i];
    const std::string field = "interfaces[" + std::to_string(i) + "].group";
    auto it = mesh.node_groups.find(spec.group);
    if (it == mesh.node_groups.end())
      throw FormatError(part.file.string(), field, "no group '" + spec.group + "' in the mesh");
    InterfaceNode node;
    node.name = spec.name;
    node.group = spec.group;
    node.coupling = spec.coupling;
    for (Index n : it->second)
      if (model.node_ndof[static_cast<std::size_t>(n)] > 0) node.nodes.push_back(n);
    if (node.nodes.empty())
      throw FormatError(part.file.string(), field,
                        "group '" + spec.group + "' has no node attached to an element with properties");
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (Index n : node.nodes) c += mesh.x.row(n).transpose();
    node.x = spec.at ? *spec.at : Eigen::Vector3d(c / static_cast<double>(node.nodes.size()));
    node.dof = next;
    next += 6;
    model.interfaces.push_back(std::move(node));
  }
  model.num_dofs = next;

  // Attached masses, and below the output nodes: each on the mesh node nearest to its point,
  // which must be near the part.
  const double diagonal = used_node_diagonal(model);
  for (std::size_t i = 0; i < part.point_masses.size(); ++i) {
    const auto& pm = part.point_masses[i];
    const std::string field = "point_masses[" + std::to_string(i) + "]";
    AttachedMass m;
    m.name = pm.name;
    m.mass = pm.mass;
    m.inertia = pm.inertia;
    if (!pm.interface.empty()) {
      m.interface = model.find_interface(pm.interface);
      const Eigen::Vector3d at = pm.at;  // defaults to zero when only an interface is given
      const Eigen::Vector3d centre = (at.isZero() ? model.interfaces[static_cast<std::size_t>(m.interface)].x : at) + pm.com_offset;
      m.offset = centre - model.interfaces[static_cast<std::size_t>(m.interface)].x;
    } else {
      double dist = 0;
      m.node = node_near_the_part(model, pm.at, diagonal, part.file.string(), field + ".at", dist);
      const bool rigid_body = !pm.com_offset.isZero() || !pm.inertia.isZero();
      if (model.node_ndof[static_cast<std::size_t>(m.node)] == 3) {
        if (rigid_body)
          throw FormatError(part.file.string(), field,
                            "the node nearest to 'at' (node " + std::to_string(mesh.node_tag(m.node)) +
                                ") belongs only to solid elements and has no rotations; a mass with com_offset or "
                                "inertia must hang on an interface (\"interface\": name) or a shell/beam node");
        m.offset.setZero();  // a plain point mass sits on the node
      } else {
        m.offset = pm.at + pm.com_offset - mesh.x.row(m.node).transpose();
      }
    }
    model.masses.push_back(m);
  }

  // Refused rather than exporting an unrelated node.
  for (std::size_t i = 0; i < part.output_nodes.size(); ++i) {
    const auto& o = part.output_nodes[i];
    OutputNode out;
    out.name = o.name;
    out.node = node_near_the_part(model, o.at, diagonal, part.file.string(), "output_nodes[" + std::to_string(i) + "].at",
                                  out.distance);
    model.outputs.push_back(out);
  }
  return model;
}

std::vector<Index> connected_pieces(const FeModel& model) {
  const auto& mesh = *model.mesh;
  std::vector<Index> parent(static_cast<std::size_t>(mesh.num_nodes()));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](Index a) {
    while (parent[static_cast<std::size_t>(a)] != a) {
      parent[static_cast<std::size_t>(a)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(a)])];
      a = parent[static_cast<std::size_t>(a)];
    }
    return a;
  };
  auto unite = [&](Index a, Index b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  };
  for (const auto& pb : model.blocks) {
    const auto& blk = mesh.blocks[pb.block];
    const int nn = num_nodes(blk.type);
    for (Index e = 0; e < blk.size(); ++e)
      for (int i = 1; i < nn; ++i) unite(blk.element(e)[0], blk.element(e)[i]);
  }
  for (const auto& itf : model.interfaces)
    for (std::size_t i = 1; i < itf.nodes.size(); ++i) unite(itf.nodes[0], itf.nodes[i]);
  std::vector<Index> roots;
  for (Index n = 0; n < mesh.num_nodes(); ++n)
    if (model.node_ndof[static_cast<std::size_t>(n)] > 0 && find(n) == n) roots.push_back(n);
  return roots;
}

}  // namespace ffr::preproc
