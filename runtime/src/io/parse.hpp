#pragma once
// The model-file parser, split by section (internal).

#include "ffr/formats/json_input.hpp"
#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/model.hpp"

#include <filesystem>
#include <functional>

namespace ffr::runtime::detail {

// The model file is read like every user JSON file (formats/json_input.hpp): each access names
// its field, unknown keys are refused; parse_model turns its FormatError into a ModelError.
using Field = formats::JsonNode;

struct ParseContext {
  std::string file;               ///< model file name for messages
  std::filesystem::path base;     ///< directory for relative paths
  Model& model;
};

void parse_bodies(const Field& root, ParseContext& ctx);
void parse_joints(const Field& root, ParseContext& ctx);
void parse_forces(const Field& root, ParseContext& ctx);
/// "roads" (parse_roads.cpp); before the forces, whose tires name them.
void parse_roads(const Field& root, ParseContext& ctx);
void parse_motions(const Field& root, ParseContext& ctx);
void parse_outputs(const Field& root, ParseContext& ctx);
void parse_solver(const Field& root, ParseContext& ctx);
/// Refuses a flexible body with no inertia about an axis whose rotation no joint holds
/// (check_inertia.cpp); runs after the joints and forces are parsed.
void check_bodies_can_turn(const Field& root, ParseContext& ctx);
/// A beam from its "bodies" entry (parse_beams.cpp): an ancf beam's one body, or a geometrically
/// exact beam's node bodies (and its Model::ge_beams entry), appended to the model's bodies.
void parse_beam(const Field& b, const std::string& name, ParseContext& ctx);
/// Refuses joints, forces and loads at a beam that read what its nodes do not carry (a rotation
/// beyond the slope's direction) or that attach away from its nodes; runs after the forces.
void check_beam_attachments(const Field& root, ParseContext& ctx);
/// A plate body from its "bodies" entry (parse_plates.cpp).
Body parse_plate(const Field& b, const std::string& name, ParseContext& ctx);
/// Refuses joints, forces and loads at a plate that read what its nodes do not carry or that
/// attach away from its nodes; runs after the forces.
void check_plate_attachments(const Field& root, ParseContext& ctx);

/// What attaches to a body, as the attachment checks see it: a joint (its JSON entry and the
/// parsed joint), or a force element or load (its entry, kind, markers; m2 < 0 for a load).
enum class AttachmentKind { Spring, FrictionDamper, Bushing, Force, Torque };
struct AttachedElement {
  const Field& where;
  AttachmentKind kind;
  int m1, m2;
};
/// Calls joint(entry, joint) for every joint (not couplers) and force(attachment) for every
/// spring-damper, friction damper, bushing and point load, matching the JSON entries with the
/// parsed elements in order (attachments.cpp).
void visit_attachments(const Field& root, const Model& m, const std::function<void(const Field&, const Joint&)>& joint,
                       const std::function<void(const AttachedElement&)>& force);

/// Body index by name (kGround for "ground"); fails naming `f` if unknown.
int body_ref(const Field& f, const Model& m);
/// A unit-length axis from a field (fails on a zero vector).
Vector3d unit_axis(const Field& f);
/// An orthonormal triad [e f g] with e along `axis`.
Matrix3d triad(const Vector3d& axis);
/// A table {"t": [...], "value": [...], "interpolation": ...} with `ncomp` components per time;
/// without "interpolation", `default_kind` (linear for loads and characteristics, PCHIP for
/// motions: MODEL_FILE.md "Tables").
Table parse_table(const Field& f, int ncomp, Interpolation default_kind);
/// "linear", "pchip" or "spline".
Interpolation interpolation(const Field& f);

/// Where something attaches: a body and either a node or a global point.
struct Attachment {
  int body = kGround;
  int node = -1;
  Vector3d point = Vector3d::Zero();  ///< global (initial configuration)
  /// With a node: the point's offset from it (body frame), carried rigidly by the node's
  /// translation and small rotation (MODEL_FILE.md "Joints").
  Vector3d offset = Vector3d::Zero();
};
/// The offset key (offset1/offset2) of a side with a node: its value, the node's position moved by it.
void node_offset(const Field& parent, const char* key, const Model& m, Attachment& a);
/// Node index of body by the name in field f (fails if the body is rigid or has no such node).
/// A geometrically exact beam's node is a body of its own: `body` becomes that node's body.
int node_ref(const Field& f, const Model& m, int& body);
/// The index into Model::ge_beams of the beam whose node `body` is (-1: none).
int ge_beam_of(const Model& m, int body);
/// Node `f` (n0 .. nN, start, end) of geometrically exact beam g: sets `body` to its node body
/// and returns its one node slice (0).
int ge_beam_node(const Field& f, const Model& m, int g, int& body);
/// Global initial position of a node.
Vector3d node_position(const Model& m, int body, int node);
/// The common point of a two-body connection (joint or bushing) from at / node1 / node2.
/// within_flexible: body1 may be body2 when it is flexible and joined at two different nodes
/// (a bushing between two nodes of one body).
void connection_points(const Field& j, const Model& m, Attachment& a1, Attachment& a2, bool within_flexible = false);
/// Adds a marker for an attachment with the global triad E; returns its index.
int add_marker(Model& m, const Attachment& a, const Matrix3d& E);

}  // namespace ffr::runtime::detail
