#include "ffr/formats/sid.hpp"

#include <stdexcept>

namespace ffr::formats {

const char* to_string(ModeType t) { return t == ModeType::Normal ? "normal" : "constraint"; }

ModeType mode_type_from_string(const std::string& s) {
  if (s == "normal") return ModeType::Normal;
  if (s == "constraint") return ModeType::Constraint;
  throw std::invalid_argument("unknown mode type '" + s + "' (expected normal or constraint)");
}

Index Sid::find_node(const std::string& name) const {
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].name == name) return static_cast<Index>(i);
  return -1;
}

void Sid::resize(Index n) {
  refmod.frequency_hz = Eigen::VectorXd::Zero(n);
  refmod.mode_type.assign(static_cast<std::size_t>(n), ModeType::Normal);
  const auto sn = static_cast<std::size_t>(n);
  mdCM.M1 = MatX3::Zero(n, 3);
  J.M1.assign(sn, Eigen::Matrix3d::Zero());
  Ct.M0 = MatX3::Zero(n, 3);
  Cr.M0 = MatX3::Zero(n, 3);
  Cr.M1.assign(sn, MatX3::Zero(n, 3));
  Me = Eigen::MatrixXd::Zero(n, n);
  Ke = Eigen::MatrixXd::Zero(n, n);
  De = Eigen::MatrixXd::Zero(n, n);
  if (!KeM1.empty()) KeM1.assign(sn, Eigen::MatrixXd::Zero(n, n));
  Gr.assign(sn, Eigen::Matrix3d::Zero());
  Ge.assign(sn, MatX3::Zero(n, 3));
  Oe.M0 = MatX6::Zero(n, 6);
  Oe.M1.assign(sn, MatX6::Zero(n, 6));
  ksigma.M0 = Eigen::VectorXd::Zero(n);
  ksigma.M1 = Eigen::MatrixXd::Zero(n, n);
  integrals.Pdm = Eigen::Matrix3Xd::Zero(3, n);
  for (auto& r : integrals.rPdm) r = Eigen::Matrix3Xd::Zero(3, n);
  for (auto& row : integrals.PPdm)
    for (auto& m : row) m = Eigen::MatrixXd::Zero(n, n);
  rotary.PsiI = MatX3::Zero(n, 3);
  rotary.PsiIPsi = Eigen::MatrixXd::Zero(n, n);
  if (stiffening) {
    stiffening->K0t.assign(sn, MatX3::Zero(n, 3));
    stiffening->K0r.assign(sn, MatX3::Zero(n, 3));
    stiffening->K0om.assign(sn, MatX6::Zero(n, 6));
    for (auto& i : stiffening->interfaces) {
      i.K0F.assign(sn, MatX3::Zero(n, 3));
      i.K0M.assign(sn, MatX3::Zero(n, 3));
    }
  }
  for (auto& node : nodes) {
    node.phi = Eigen::Matrix3Xd::Zero(3, n);
    node.psi = Eigen::Matrix3Xd::Zero(3, n);
  }
  visual.modes.assign(sn, decltype(visual.vertices)::Zero(visual.vertices.rows(), 3));
}

}  // namespace ffr::formats
