#include "ffr/preproc/reduce/node_data.hpp"

namespace ffr::preproc {

std::vector<formats::Node> node_data(const FeModel& model, const Eigen::MatrixXd& Phi) {
  const Index nq = Phi.cols();
  std::vector<formats::Node> nodes;
  for (const auto& itf : model.interfaces) {
    formats::Node n;
    n.name = itf.name;
    n.origin = itf.x;
    n.phi = Phi.middleRows(itf.dof, 3);
    n.psi = Phi.middleRows(itf.dof + 3, 3);
    nodes.push_back(std::move(n));
  }
  for (const auto& out : model.outputs) {
    formats::Node n;
    n.name = out.name;
    n.origin = model.mesh->x.row(out.node).transpose();
    const Index d0 = model.node_dof[static_cast<std::size_t>(out.node)];
    n.phi = Phi.middleRows(d0, 3);
    n.psi = model.node_ndof[static_cast<std::size_t>(out.node)] == 6 ? Eigen::Matrix3Xd(Phi.middleRows(d0 + 3, 3))
                                                                      : Eigen::Matrix3Xd::Zero(3, nq);
    nodes.push_back(std::move(n));
  }
  return nodes;
}

}  // namespace ffr::preproc
