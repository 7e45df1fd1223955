#pragma once
// Node data of the SID: every interface node (under the interface's name) and every output
// node (the nearest mesh node), with its position and mode slices phi (translations) and psi
// (small rotations; zero for a node without rotational DOFs).
#include "ffr/formats/sid.hpp"
#include "ffr/preproc/model/fe_model.hpp"

#include <vector>

namespace ffr::preproc {

std::vector<formats::Node> node_data(const FeModel& model, const Eigen::MatrixXd& Phi);

}  // namespace ffr::preproc
