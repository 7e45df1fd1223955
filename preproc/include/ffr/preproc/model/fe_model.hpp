#pragma once
// The finite-element model of a part: the mesh's element blocks that carry properties
// (solid material, shell section, beam section), DOF numbering, interface nodes, attached
// masses and output nodes. Built once from Mesh + PartSpec; nothing here depends on modes.
//
// DOF numbering ("full" DOFs): each mesh node used by an element with properties gets 3
// DOFs (solid only) or 6 DOFs (if any shell or beam element uses it: ux,uy,uz,rx,ry,rz).
// Interface nodes are extra 6-DOF nodes numbered after all mesh DOFs.

#include "ffr/preproc/elements/element.hpp"
#include "ffr/preproc/mesh/mesh.hpp"
#include "ffr/preproc/part/part.hpp"

#include <string>
#include <vector>

namespace ffr::preproc {

enum class ElementKind { Solid, Shell, Beam };

/// An element block with its properties.
struct PropertyBlock {
  ElementKind kind = ElementKind::Solid;
  std::size_t block = 0;      ///< index into Mesh::blocks
  std::size_t property = 0;   ///< index into PartSpec::materials / shells / beams
};

struct InterfaceNode {
  std::string name, group, coupling;
  Eigen::Vector3d x = Eigen::Vector3d::Zero();  ///< position of the 6-DOF interface node
  Index dof = -1;                                ///< its first full DOF
  std::vector<Index> nodes;                      ///< mesh nodes of the group (used nodes only)
};

struct AttachedMass {
  std::string name;
  Index node = -1;        ///< mesh node carrying it, or -1 if on an interface
  int interface = -1;     ///< index into FeModel::interfaces, or -1
  double mass = 0;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  ///< centre of the mass minus the node position
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero(); ///< about its own centre
};

struct OutputNode {
  std::string name;
  Index node = -1;        ///< mesh node
  double distance = 0;    ///< distance from the requested point to the node
};

struct FeModel {
  const Mesh* mesh = nullptr;
  const PartSpec* part = nullptr;
  std::vector<PropertyBlock> blocks;
  std::vector<Index> node_dof;   ///< first full DOF of each mesh node, -1 if unused
  std::vector<int> node_ndof;    ///< 0, 3 or 6 per mesh node
  std::vector<Index> dof_node;   ///< mesh node owning each mesh DOF (size mesh_dofs())
  std::vector<InterfaceNode> interfaces;
  std::vector<AttachedMass> masses;
  std::vector<OutputNode> outputs;
  Index num_dofs = 0;            ///< full DOFs including interface nodes

  Index mesh_dofs() const { return interfaces.empty() ? num_dofs : interfaces.front().dof; }
  int find_interface(const std::string& name) const;
  /// Full DOF of (node, component); component 3..5 requires a 6-DOF node.
  Index dof(Index node, int component) const { return node_dof[static_cast<std::size_t>(node)] + component; }
  /// Position of the node owning each full DOF and its component (for messages and rigid modes).
  void dof_owner(Index dof, Index& node_or_interface, int& component, bool& is_interface) const;
  /// Value at a full DOF of the six rigid-body motions: unit translations x, y, z, then unit
  /// rotations about the x, y, z axes through the origin (u = e_a x x, theta = e_a).
  Eigen::Matrix<double, 1, 6> rigid_motion(Index dof) const;
};

/// Builds the FE model. Throws formats::FormatError naming the part file and field for:
/// a property or interface group that is not in the mesh, a group of the wrong dimension
/// (material on a surface group, shell on a volume group, ...), an element in two property
/// groups, a part where no element has properties, an interface group with no used node,
/// an attached mass with offset or inertia on a node without rotations.
FeModel build_model(const Mesh& mesh, const PartSpec& part);

/// Connected pieces of the model (elements sharing nodes, interfaces joining their groups).
/// Returns the number of pieces and, for each piece, one mesh node in it.
std::vector<Index> connected_pieces(const FeModel& model);

}  // namespace ffr::preproc
