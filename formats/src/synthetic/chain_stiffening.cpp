// The unreduced chain's static solves and geometric stiffness, and the /stiffening members
// of its SID computed from them (see synthetic.hpp, ChainParams).
#include "ffr/formats/synthetic.hpp"

namespace ffr::formats::synthetic {

using Eigen::MatrixXd;
using Eigen::VectorXd;

VectorXd ChainModel::static_deflection(const VectorXd& f) const {
  // Modal flexibility over all elastic modes: exact for the clamped chain, and for the free
  // chain the inertia-relief solution (the load's rigid-body part drops out, u is
  // M-orthogonal to the rigid-body modes).
  const VectorXd q = (Phi.transpose() * f).cwiseQuotient(omega.cwiseAbs2());
  return Phi * q;
}

VectorXd ChainModel::axial_forces(const VectorXd& u) const {
  const auto n = static_cast<Eigen::Index>(points.size());
  const double h = params.length / (n - 1);
  VectorXd N(n - 1);
  for (Eigen::Index e = 0; e + 1 < n; ++e) N[e] = params.EA * (u[3 * (e + 1)] - u[3 * e]) / h;
  return N;
}

MatrixXd ChainModel::geometric_stiffness(const VectorXd& N) const {
  const auto n = static_cast<Eigen::Index>(points.size());
  const double h = params.length / (n - 1);
  MatrixXd KG = MatrixXd::Zero(3 * n, 3 * n);
  Eigen::Matrix3d perp = Eigen::Matrix3d::Identity();
  perp(0, 0) = 0;  // only transverse relative displacement stretches a tensioned segment
  for (Eigen::Index e = 0; e + 1 < n; ++e) {
    const Eigen::Matrix3d k = N[e] / h * perp;
    const Eigen::Index a = 3 * e, b = 3 * (e + 1);
    KG.block(a, a, 3, 3) += k;
    KG.block(b, b, 3, 3) += k;
    KG.block(a, b, 3, 3) -= k;
    KG.block(b, a, 3, 3) -= k;
  }
  // Fixed DOFs do not move: keep their rows and columns zero like K.
  if (params.clamped) {
    KG.topRows(3).setZero();
    KG.leftCols(3).setZero();
  }
  return KG;
}

VectorXd ChainModel::centrifugal_load(int j) const {
  const Eigen::Matrix3d C = centrifugal_matrix(j);
  VectorXd f(3 * points.size());
  for (std::size_t p = 0; p < points.size(); ++p) f.segment<3>(3 * p) = -points[p].m * (C * points[p].c);
  return f;
}

Sid add_chain_stiffening(Sid sid, const ChainModel& model) {
  const Eigen::Index nq = sid.nq();
  const auto n = static_cast<Eigen::Index>(model.points.size());
  const MatrixXd Phi = model.Phi.leftCols(nq);
  // K0[k](i) = Phi_i^T K_G(load) Phi_k as an [nq,nq] matrix indexed (k, i).
  auto project = [&](const VectorXd& f) -> MatrixXd {
    const MatrixXd KG = model.geometric_stiffness(model.axial_forces(model.static_deflection(f)));
    return Phi.transpose() * KG * Phi;  // symmetric
  };
  auto put = [&](std::vector<MatX3>& dst, int c, const MatrixXd& K0) {
    for (Eigen::Index k = 0; k < nq; ++k) dst[k].col(c) = K0.row(k).transpose();
  };

  Stiffening st;
  st.K0t.assign(nq, MatX3::Zero(nq, 3));
  st.K0r.assign(nq, MatX3::Zero(nq, 3));
  st.K0om.assign(nq, MatX6::Zero(nq, 6));
  for (int c = 0; c < 3; ++c) {
    VectorXd ft(3 * n), fr(3 * n);
    const Eigen::Vector3d e = Eigen::Vector3d::Unit(c);
    for (Eigen::Index p = 0; p < n; ++p) {
      ft.segment<3>(3 * p) = -model.points[p].m * e;
      fr.segment<3>(3 * p) = -model.points[p].m * e.cross(model.points[p].c);
    }
    put(st.K0t, c, project(ft));
    put(st.K0r, c, project(fr));
  }
  for (int j = 0; j < 6; ++j) {
    const MatrixXd K0 = project(model.centrifugal_load(j));
    for (Eigen::Index k = 0; k < nq; ++k) st.K0om[k].col(j) = K0.row(k).transpose();
  }
  for (const auto& itf : sid.interfaces) {
    Stiffening::Interface si;
    si.name = itf.name;
    si.K0F.assign(nq, MatX3::Zero(nq, 3));
    si.K0M.assign(nq, MatX3::Zero(nq, 3));
    // The interface's point: the exported node's position along the chain.
    const Eigen::Vector3d at = sid.nodes[itf.node].origin;
    Eigen::Index p = 0;
    for (Eigen::Index i = 0; i < n; ++i)
      if ((model.points[i].c - at).norm() < (model.points[p].c - at).norm()) p = i;
    for (int c = 0; c < 3; ++c) {
      VectorXd f = VectorXd::Zero(3 * n);
      f[3 * p + c] = 1;
      put(si.K0F, c, project(f));
      // A unit moment on the point's rotations: virtual work M.dtheta = M.(R du).
      VectorXd mom = VectorXd::Zero(3 * n);
      mom[3 * p + c] = 1;
      put(si.K0M, c, project(model.rotation_recovery.transpose() * mom));
    }
    st.interfaces.push_back(std::move(si));
  }
  sid.stiffening = std::move(st);
  // Ke.M1[k] = Phi^T K_G(N(Phi_k)) Phi: the segments' forces from mode k's own stretch.
  sid.KeM1.assign(static_cast<std::size_t>(nq), MatrixXd::Zero(nq, nq));
  for (Eigen::Index k = 0; k < nq; ++k) {
    const MatrixXd P = Phi.transpose() * model.geometric_stiffness(model.axial_forces(Phi.col(k))) * Phi;
    sid.KeM1[static_cast<std::size_t>(k)] = 0.5 * (P + P.transpose());
  }
  sid.provenance.mass_model["stiffening"] = "lumped point masses; string geometric stiffness of the segments";
  return sid;
}

}  // namespace ffr::formats::synthetic
