// The joints, force elements and loads of a model file matched with their parsed elements, for
// the checks of what may attach to beam and plate nodes (parse_beams.cpp, parse_plates.cpp).
#include "parse.hpp"

namespace ffr::runtime::detail {

void visit_attachments(const Field& root, const Model& m, const std::function<void(const Field&, const Joint&)>& joint,
                       const std::function<void(const AttachedElement&)>& force) {
  // The joints list also holds couplers, which are not in Model::joints: entries are matched in order.
  const std::size_t njson = root.has("joints") ? root.at("joints").size() : 0;
  for (std::size_t i = 0, j = 0; i < njson && j < m.joints.size(); ++i) {
    const Field f = root.at("joints").at(i);
    if (f.at("type").string() == "coupler") continue;
    joint(f, m.joints[j++]);
  }
  if (!root.has("forces")) return;
  const Field forces = root.at("forces");
  // The forces list mixes kinds; their markers are found again by kind, in the order parsed.
  std::size_t ispring = 0, ibush = 0, ifric = 0, iload = 0;
  for (std::size_t i = 0; i < forces.size(); ++i) {
    const Field f = forces.at(i);
    const std::string type = f.at("type").string();
    if (type == "spring_damper") {
      const SpringDamper& s = m.springs[ispring++];
      force({f, AttachmentKind::Spring, s.m1, s.m2});
    } else if (type == "friction_damper") {
      const FrictionDamper& s = m.friction_dampers[ifric++];
      force({f, AttachmentKind::FrictionDamper, s.m1, s.m2});
    } else if (type == "bushing") {
      const Bushing& s = m.bushings[ibush++];
      force({f, AttachmentKind::Bushing, s.m1, s.m2});
    } else if (type == "point_force" || type == "point_torque") {
      const PointLoad& l = m.loads[iload++];
      force({f, l.torque ? AttachmentKind::Torque : AttachmentKind::Force, l.marker, -1});
    }
  }
}

}  // namespace ffr::runtime::detail
