#pragma once
// Modal stress recovery (the part file's "stress", PART_FILE.md): each mode's Cauchy stress at
// chosen mesh nodes, stored in the SID's optional /stress group (formats/SPEC.md section 12.1).
//
// Nodal values, the way CalculiX and Abaqus make them: in every solid element the stress of the
// mode's displacement is evaluated at the stiffness-rule points (solid_stress: sigma = D B u,
// HEX8 with its incompatible modes), fitted by the element's linear (corner) shape functions in
// the least-squares sense through those points (exact interpolation where the counts agree:
// TET10's 4 points, HEX8's 2x2x2, WEDGE6's 6; a one-point rule gives the constant) and evaluated
// at the element's nodes; a node's value is the plain mean over the solid elements that hold it.
// For a TET10 with straight edges the element's stress is linear, so the fit reproduces it
// exactly and the midside value is the mean of the edge's corners.
// Shell elements (QUAD4, TRI3 and their second-order splits) carry stress on three layers per
// node: top (z = +t/2 along the node's normal), middle and bottom, from their resultants at the
// in-plane integration points extrapolated to the corners the same way (shell_stress_map,
// elements/shell.hpp), rotated to body axes and averaged over the shell elements at the node
// after orienting each connected shell surface consistently. Beams carry none (their section
// has no single stress at a node).
#include "ffr/formats/modal_stress.hpp"
#include "ffr/preproc/model/fe_model.hpp"

#include <string>
#include <vector>

namespace ffr::preproc {

/// The mesh nodes a part's stress request selects: the nodes of `part.stress->group`, or the
/// solid and shell nodes of the outer surface (the /visual vertices) for "surface". Throws
/// formats::FormatError naming the part file and the field for a group that is not in the mesh,
/// a node of the group that belongs to no solid or shell element (a beam's node), or a
/// selection without such nodes.
std::vector<Index> stress_nodes(const FeModel& model);

/// Each mode's nodal stress at `nodes` (mesh node indices, each in a solid or shell element):
/// one row per solid node, three (top, middle, bottom; ModalStress::layer and ::normal set) per
/// shell node, in the order of `nodes`. Phi has one row per full DOF and one column per mode.
formats::ModalStress recover_modal_stress(const FeModel& model, const Eigen::MatrixXd& Phi, const std::vector<Index>& nodes);

}  // namespace ffr::preproc
