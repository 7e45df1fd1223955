#pragma once
// Modal damping of the reduced body from the part's damping model.
#include "ffr/preproc/part/part.hpp"

#include <Eigen/Core>
#include <string>

namespace ffr::preproc {

/// De for the basis with modal mass Me and stiffness Ke:
///  - ratio zeta: 2 zeta omega_j in the body's own eigenbasis V (V^T Me V = I, V^T Ke V = diag
///    omega^2), transformed back: De = Me V diag(2 zeta omega) V^T Me. For mass-normalised
///    eigenmodes (V = I) this is diag(2 zeta omega_j); it also holds for a Craig–Bampton basis.
///  - Rayleigh: alpha Me + beta Ke.
Eigen::MatrixXd damping_matrix(const DampingSpec& d, const Eigen::MatrixXd& Me, const Eigen::MatrixXd& Ke);

/// Text of the model for provenance: "none", "ratio 0.02", "rayleigh alpha=.. beta=..".
std::string damping_text(const DampingSpec& d);

}  // namespace ffr::preproc
