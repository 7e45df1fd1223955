// spring_chain(): lumped masses on Euler-Bernoulli beam segments, free-free or clamped,
// reduced to its lowest elastic modes by a dense eigen-solve (see synthetic.hpp).
#include "ffr/formats/synthetic.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace ffr::formats::synthetic {

Sid add_chain_stiffening(Sid sid, const ChainModel& model);  // chain_stiffening.cpp

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("synthetic::spring_chain: " + what);
}

// Per node 5 DOFs before condensation: u, v, w, theta_y, theta_z (no torsion).
constexpr int kDofs = 5;

// Assembles the 5n x 5n stiffness of the chain of exact Euler-Bernoulli elements.
MatrixXd assemble_beam(const ChainParams& P) {
  const int n = P.points;
  const double h = P.length / (n - 1);
  MatrixXd K = MatrixXd::Zero(kDofs * n, kDofs * n);
  // Bending in the x-y plane on (v1, theta_z1, v2, theta_z2), theta_z = dv/dx.
  Eigen::Matrix4d b;
  b << 12, 6 * h, -12, 6 * h, 6 * h, 4 * h * h, -6 * h, 2 * h * h, -12, -6 * h, 12, -6 * h, 6 * h, 2 * h * h, -6 * h,
      4 * h * h;
  b /= h * h * h;
  // In the x-z plane theta_y = -dw/dx: the same matrix with the w-theta couplings negated.
  const Eigen::Vector4d flip(1, -1, 1, -1);
  const Eigen::Matrix4d bz = flip.asDiagonal() * b * flip.asDiagonal();
  for (int e = 0; e + 1 < n; ++e) {
    const int a = kDofs * e, c = kDofs * (e + 1);
    const int ax[2] = {a, c};
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) K(ax[i], ax[j]) += (i == j ? 1.0 : -1.0) * P.EA / h;
    const int vy[4] = {a + 1, a + 4, c + 1, c + 4};  // v, theta_z
    const int wz[4] = {a + 2, a + 3, c + 2, c + 3};  // w, theta_y
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        K(vy[i], vy[j]) += P.EIz * b(i, j);
        K(wz[i], wz[j]) += P.EIy * bz(i, j);
      }
  }
  return K;
}

// Rigid-body translational modes of a free chain: 3 translations, rotations about y and z.
MatrixXd rigid_modes(const ChainModel& m) {
  const auto n = static_cast<Eigen::Index>(m.points.size());
  MatrixXd R = MatrixXd::Zero(3 * n, 5);
  for (Eigen::Index p = 0; p < n; ++p) {
    const double s = m.points[p].c.x() - m.params.start.x();
    for (int a = 0; a < 3; ++a) R(3 * p + a, a) = 1;
    R(3 * p + 2, 3) = -s;  // rotation about y: e_y x (s e_x) = -s e_z
    R(3 * p + 1, 4) = s;   // rotation about z: e_z x (s e_x) =  s e_y
  }
  return R;
}

// Sign convention for determinism: the largest-magnitude entry of each mode is positive.
void fix_signs(MatrixXd& Phi, MatrixXd& Psi) {
  for (Eigen::Index k = 0; k < Phi.cols(); ++k) {
    Eigen::Index i;
    Phi.col(k).cwiseAbs().maxCoeff(&i);
    if (Phi(i, k) < 0) {
      Phi.col(k) *= -1;
      Psi.col(k) *= -1;
    }
  }
}

}  // namespace

Eigen::Matrix3d centrifugal_matrix(int j) {
  // w x (w x c) = (w w^T - |w|^2 I) c; C_j is the coefficient of omega_bar_j.
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  if (j < 3) {
    C = -Eigen::Matrix3d::Identity();
    C(j, j) = 0;
    return C;
  }
  const int a = j == kXY ? 0 : j == kYZ ? 1 : 0;
  const int b = j == kXY ? 1 : j == kYZ ? 2 : 2;
  C(a, b) = C(b, a) = 1;
  return C;
}

Chain spring_chain(const ChainParams& P) {
  require(P.points >= 2, "need at least 2 points");
  require(std::isfinite(P.length) && P.length > 0, "length must be positive");
  require(std::isfinite(P.mass) && P.mass > 0, "mass must be positive");
  require(P.EA > 0 && P.EIy > 0 && P.EIz > 0 && std::isfinite(P.EA + P.EIy + P.EIz), "stiffnesses must be positive");
  require(P.start.allFinite(), "start must be finite");
  const int n = P.points;
  const double h = P.length / (n - 1);

  ChainModel model;
  model.params = P;
  for (int p = 0; p < n; ++p) {
    PointMass pm;
    pm.m = P.mass / (n - 1) * (p == 0 || p == n - 1 ? 0.5 : 1.0);
    pm.c = P.start + Eigen::Vector3d(p * h, 0, 0);
    model.points.push_back(pm);
  }

  // Free DOFs of the 5-DOF model; condense the rotations (massless) onto the translations.
  const MatrixXd K5 = assemble_beam(P);
  std::vector<int> trans, rot;
  for (int p = P.clamped ? 1 : 0; p < n; ++p) {
    for (int a = 0; a < 3; ++a) trans.push_back(kDofs * p + a);
    for (int a = 3; a < 5; ++a) rot.push_back(kDofs * p + a);
  }
  const auto nt = static_cast<Eigen::Index>(trans.size()), nr = static_cast<Eigen::Index>(rot.size());
  MatrixXd Ktt(nt, nt), Ktr(nt, nr), Krr(nr, nr);
  for (Eigen::Index i = 0; i < nt; ++i) {
    for (Eigen::Index j = 0; j < nt; ++j) Ktt(i, j) = K5(trans[i], trans[j]);
    for (Eigen::Index j = 0; j < nr; ++j) Ktr(i, j) = K5(trans[i], rot[j]);
  }
  for (Eigen::Index i = 0; i < nr; ++i)
    for (Eigen::Index j = 0; j < nr; ++j) Krr(i, j) = K5(rot[i], rot[j]);
  const Eigen::LLT<MatrixXd> Krr_llt(Krr);  // positive definite: translations held, no torsion
  require(Krr_llt.info() == Eigen::Success, "internal: rotational stiffness not positive definite");
  const MatrixXd Rec = -Krr_llt.solve(Ktr.transpose());  // theta = Rec u_free
  const MatrixXd Kc = Ktt + Ktr * Rec;

  // Embed into the 3n translational numbering.
  model.M = MatrixXd::Zero(3 * n, 3 * n);
  for (int p = 0; p < n; ++p) model.M.block(3 * p, 3 * p, 3, 3) = model.points[p].m * Eigen::Matrix3d::Identity();
  model.K = MatrixXd::Zero(3 * n, 3 * n);
  model.rotation_recovery = MatrixXd::Zero(3 * n, 3 * n);
  std::vector<Index> free3;
  for (int t : trans) free3.push_back(3 * (t / kDofs) + t % kDofs);
  model.free_dofs = free3;
  for (Eigen::Index i = 0; i < nt; ++i)
    for (Eigen::Index j = 0; j < nt; ++j) model.K(free3[i], free3[j]) = Kc(i, j);
  for (Eigen::Index r = 0; r < nr; ++r) {
    const int node = rot[r] / kDofs, axis = rot[r] % kDofs == 3 ? 1 : 2;  // theta_y, theta_z
    for (Eigen::Index j = 0; j < nt; ++j) model.rotation_recovery(3 * node + axis, free3[j]) = Rec(r, j);
  }

  // Eigenproblem Kc x = lambda Mc x with Mc diagonal: y = Mc^{1/2} x.
  VectorXd msqrt(nt);
  for (Eigen::Index i = 0; i < nt; ++i) msqrt[i] = std::sqrt(model.M(free3[i], free3[i]));
  const MatrixXd A = msqrt.cwiseInverse().asDiagonal() * Kc * msqrt.cwiseInverse().asDiagonal();
  MatrixXd Z = MatrixXd::Identity(nt, nt);  // basis of the space the elastic modes live in
  if (!P.clamped) {
    // Remove the rigid-body modes exactly: work in the orthogonal complement of M^{1/2} R.
    MatrixXd R = rigid_modes(model);
    MatrixXd Y(nt, R.cols());
    for (Eigen::Index i = 0; i < nt; ++i) Y.row(i) = msqrt[i] * R.row(free3[i]);
    const Eigen::HouseholderQR<MatrixXd> qr(Y);
    Z = (qr.householderQ() * MatrixXd::Identity(nt, nt)).rightCols(nt - R.cols());
  }
  const Eigen::SelfAdjointEigenSolver<MatrixXd> es(Z.transpose() * A * Z);
  require(es.info() == Eigen::Success, "internal: eigen-solve failed");
  const Eigen::Index nel = Z.cols();
  require(P.modes >= 1 && P.modes <= nel, "modes must be in 1.." + std::to_string(nel));
  const MatrixXd Yel = Z * es.eigenvectors();
  model.omega = es.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  model.Phi = MatrixXd::Zero(3 * n, nel);
  for (Eigen::Index i = 0; i < nt; ++i) model.Phi.row(free3[i]) = Yel.row(i) / msqrt[i];
  model.Psi = model.rotation_recovery * model.Phi;
  fix_signs(model.Phi, model.Psi);

  std::vector<ExportedNode> nodes;
  for (const auto& [name, idx] : P.nodes) {
    const int p = idx < 0 ? n + idx : idx;
    require(p >= 0 && p < n, "exported node '" + name + "' is outside the chain");
    nodes.push_back({name, p});
  }
  const std::string first = P.nodes.empty() ? "A" : P.nodes.front().first;
  Sid sid = from_shapes(model.points, model.Phi.leftCols(P.modes), model.Psi.leftCols(P.modes),
                        model.omega.head(P.modes), nodes, P.clamped ? "clamped:" + first : "free", P.damping_ratio);
  for (std::size_t i = 0; i < nodes.size(); ++i)
    sid.interfaces.push_back({nodes[i].name, static_cast<Index>(i), "rigid", nodes[i].name});

  std::ostringstream o;
  o.precision(17);
  o << R"({"generator": "synthetic::spring_chain", "points": )" << n << R"(, "length": )" << P.length
    << R"(, "mass": )" << P.mass << R"(, "EA": )" << P.EA << R"(, "EIy": )" << P.EIy << R"(, "EIz": )" << P.EIz
    << R"(, "start": [)" << P.start.x() << ", " << P.start.y() << ", " << P.start.z() << R"(], "clamped": )"
    << (P.clamped ? "true" : "false") << R"(, "modes": )" << P.modes << R"(, "stiffening": )"
    << (P.stiffening ? "true" : "false") << "}";
  sid.provenance.reduction_method = P.clamped ? "clamped" : "free";
  sid.provenance.reduction_parameters = o.str();
  sid.provenance.element_counts["euler_bernoulli_segment"] = n - 1;
  sid.provenance.element_counts["point_mass"] = n;
  sid.provenance.mass_model["integrals"] = "lumped point masses (exact sums)";
  if (P.stiffening) sid = add_chain_stiffening(std::move(sid), model);
  return {std::move(sid), std::move(model)};
}

}  // namespace ffr::formats::synthetic
