#include "ffr/preproc/reduce/damping.hpp"

#include <Eigen/Eigenvalues>

#include <sstream>
#include <stdexcept>

namespace ffr::preproc {

Eigen::MatrixXd damping_matrix(const DampingSpec& d, const Eigen::MatrixXd& Me, const Eigen::MatrixXd& Ke) {
  const Eigen::Index n = Me.rows();
  switch (d.kind) {
    case DampingSpec::Kind::None: return Eigen::MatrixXd::Zero(n, n);
    case DampingSpec::Kind::Rayleigh: return d.alpha * Me + d.beta * Ke;
    case DampingSpec::Kind::Ratio: {
      if (n == 0) return Eigen::MatrixXd::Zero(0, 0);
      Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Ke, Me);
      if (es.info() != Eigen::Success) throw std::runtime_error("modal damping: reduced eigen-solve failed");
      const Eigen::MatrixXd& V = es.eigenvectors();
      const Eigen::VectorXd w = es.eigenvalues().cwiseMax(0.0).cwiseSqrt();
      const Eigen::MatrixXd MV = Me * V;
      Eigen::MatrixXd D = MV * (2 * d.ratio * w).asDiagonal() * MV.transpose();
      return 0.5 * (D + D.transpose());
    }
  }
  return Eigen::MatrixXd::Zero(n, n);
}

std::string damping_text(const DampingSpec& d) {
  std::ostringstream o;
  o.precision(10);
  switch (d.kind) {
    case DampingSpec::Kind::None: return "none";
    case DampingSpec::Kind::Ratio: o << "ratio " << d.ratio; break;
    case DampingSpec::Kind::Rayleigh: o << "rayleigh alpha=" << d.alpha << " beta=" << d.beta; break;
  }
  return o.str();
}

}  // namespace ffr::preproc
