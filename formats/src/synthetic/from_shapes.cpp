// from_shapes(): every SID member of a point-mass body by direct sums over the points.
// Each formula is the definition in SPEC.md sections 6-8 with the integral over the body
// replaced by a sum over points; see formats/SPEC.md for the sign conventions.
#include "ffr/formats/synthetic.hpp"

#include "ffr/version.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace ffr::formats::synthetic {
namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;

Matrix3d skew(const Vector3d& x) {
  Matrix3d s;
  s << 0, -x.z(), x.y(), x.z(), 0, -x.x(), -x.y(), x.x(), 0;
  return s;
}

// a^T (w w^T - |w|^2 I) b as coefficients of omega_bar = (xx, yy, zz, xy, yz, xz).
Eigen::Matrix<double, 1, 6> centrifugal_row(const Vector3d& a, const Vector3d& b) {
  const double ab = a.dot(b);
  Eigen::Matrix<double, 1, 6> r;
  r << a.x() * b.x() - ab, a.y() * b.y() - ab, a.z() * b.z() - ab, a.x() * b.y() + a.y() * b.x(),
      a.y() * b.z() + a.z() * b.y(), a.x() * b.z() + a.z() * b.x();
  return r;
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("synthetic::from_shapes: " + what);
}

// M-orthonormalises the columns of (Phi; Psi) in order (modified Gram-Schmidt with the
// point-mass inner product), so M-orthogonal input is only rescaled.
void orthonormalise(const std::vector<PointMass>& pts, MatrixXd& Phi, MatrixXd& Psi) {
  const Eigen::Index n = static_cast<Eigen::Index>(pts.size());
  auto inner = [&](Eigen::Index a, Eigen::Index b) {
    double s = 0;
    for (Eigen::Index p = 0; p < n; ++p) {
      s += pts[p].m * Phi.block<3, 1>(3 * p, a).dot(Phi.block<3, 1>(3 * p, b));
      s += Psi.block<3, 1>(3 * p, a).dot(pts[p].inertia * Psi.block<3, 1>(3 * p, b));
    }
    return s;
  };
  for (Eigen::Index k = 0; k < Phi.cols(); ++k) {
    const double before = inner(k, k);
    for (Eigen::Index j = 0; j < k; ++j) {
      const double c = inner(j, k);
      Phi.col(k) -= c * Phi.col(j);
      Psi.col(k) -= c * Psi.col(j);
    }
    const double nn = inner(k, k);
    require(before > 0 && nn > 1e-24 * before, "mode " + std::to_string(k) + " has no mass or depends on earlier modes");
    Phi.col(k) /= std::sqrt(nn);
    Psi.col(k) /= std::sqrt(nn);
  }
}

}  // namespace

Sid from_shapes(const std::vector<PointMass>& pts, const MatrixXd& Phi_in, const MatrixXd& Psi_in,
                const Eigen::VectorXd& omega, const std::vector<ExportedNode>& exported,
                const std::string& reference, double zeta) {
  const Eigen::Index n = static_cast<Eigen::Index>(pts.size());
  const Eigen::Index nq = Phi_in.cols();
  require(n > 0, "no points");
  require(Phi_in.rows() == 3 * n, "Phi must have 3n rows");
  require(Psi_in.size() == 0 || (Psi_in.rows() == 3 * n && Psi_in.cols() == nq), "Psi must be empty or [3n, nq]");
  require(omega.size() == nq, "omega must have nq entries");
  require(std::isfinite(zeta) && zeta >= 0, "damping ratio must be >= 0");
  for (Eigen::Index k = 0; k < nq; ++k) require(std::isfinite(omega[k]) && omega[k] >= 0, "omega must be finite and >= 0");
  for (const auto& p : pts) {
    require(std::isfinite(p.m) && p.m > 0, "every point mass must be positive");
    require(p.c.allFinite() && p.inertia.allFinite(), "non-finite point data");
    require((p.inertia - p.inertia.transpose()).norm() <= 1e-12 * (1 + p.inertia.norm()), "point inertia must be symmetric");
  }
  for (const auto& e : exported) require(e.point >= 0 && e.point < n, "exported node '" + e.name + "' has no point");

  MatrixXd Phi = Phi_in;
  MatrixXd Psi = Psi_in.size() ? Psi_in : MatrixXd::Zero(3 * n, nq);
  orthonormalise(pts, Phi, Psi);
  auto phi = [&](Eigen::Index p, Eigen::Index k) -> Vector3d { return Phi.block(3 * p, k, 3, 1); };
  auto psi = [&](Eigen::Index p, Eigen::Index k) -> Vector3d { return Psi.block(3 * p, k, 3, 1); };

  Sid s;
  for (const auto& e : exported) {
    Node node;
    node.name = e.name;
    s.nodes.push_back(node);
  }
  s.resize(nq);

  // refmod
  double m = 0;
  for (const auto& p : pts) m += p.m;
  s.refmod.mass = m;
  s.refmod.frequency_hz = omega / (2 * M_PI);
  s.refmod.reference = reference;

  // Primitive integrals (translational mass) and the rotary part.
  auto& I = s.integrals;
  for (Eigen::Index p = 0; p < n; ++p) {
    const auto& P = pts[p];
    I.rdm += P.m * P.c;
    I.rrdm += P.m * P.c * P.c.transpose();
    s.rotary.I += P.inertia;
    for (Eigen::Index k = 0; k < nq; ++k) {
      I.Pdm.col(k) += P.m * phi(p, k);
      for (int a = 0; a < 3; ++a) I.rPdm[a].col(k) += P.m * P.c[a] * phi(p, k);
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          for (Eigen::Index i = 0; i < nq; ++i) I.PPdm[a][b](k, i) += P.m * phi(p, k)[a] * phi(p, i)[b];
      s.rotary.PsiI.row(k) += (psi(p, k).transpose() * P.inertia);
      for (Eigen::Index i = 0; i < nq; ++i) s.rotary.PsiIPsi(k, i) += psi(p, k).dot(P.inertia * psi(p, i));
    }
  }

  // SID members, each straight from its definition.
  for (Eigen::Index p = 0; p < n; ++p) {
    const auto& P = pts[p];
    const Vector3d& c = P.c;
    s.mdCM.M0 += P.m * c;
    s.J.M0 += P.m * (c.squaredNorm() * Matrix3d::Identity() - c * c.transpose()) + P.inertia;
    for (Eigen::Index k = 0; k < nq; ++k) {
      const Vector3d fk = phi(p, k);
      s.mdCM.M1.row(k) += P.m * fk.transpose();
      s.J.M1[k] += P.m * (2 * c.dot(fk) * Matrix3d::Identity() - c * fk.transpose() - fk * c.transpose());
      s.Ct.M0.row(k) += P.m * fk.transpose();
      s.Cr.M0.row(k) += P.m * c.cross(fk).transpose() + (P.inertia * psi(p, k)).transpose();
      s.Gr[k] += -2 * P.m * skew(c) * skew(fk);
      s.Oe.M0.row(k) += P.m * centrifugal_row(fk, c);
      for (Eigen::Index i = 0; i < nq; ++i) {
        const Vector3d fi = phi(p, i);
        s.Me(k, i) += P.m * fk.dot(fi) + psi(p, k).dot(P.inertia * psi(p, i));
        s.Cr.M1[k].row(i) += P.m * fk.cross(fi).transpose();
        s.Ge[k].row(i) += 2 * P.m * fk.cross(fi).transpose();
        s.Oe.M1[k].row(i) += P.m * centrifugal_row(fi, fk);
      }
    }
  }
  for (Eigen::Index k = 0; k < nq; ++k) {
    s.Ke(k, k) = omega[k] * omega[k];
    s.De(k, k) = 2 * zeta * omega[k];
  }

  for (std::size_t e = 0; e < exported.size(); ++e) {
    auto& node = s.nodes[e];
    const Eigen::Index p = exported[e].point;
    node.origin = pts[p].c;
    node.phi = Phi.middleRows(3 * p, 3);
    node.psi = Psi.middleRows(3 * p, 3);
  }

  auto& pv = s.provenance;
  pv.generator = kGenerator;
  pv.reduction_method = "synthetic";
  std::ostringstream params;
  params << R"({"generator": "synthetic::from_shapes", "points": )" << n << R"(, "modes": )" << nq << "}";
  pv.reduction_parameters = params.str();
  std::ostringstream damping;
  damping.precision(17);
  damping << "ratio " << zeta;
  pv.damping_model = zeta > 0 ? damping.str() : "none";
  pv.mass_model["integrals"] = "point masses (exact sums)";
  pv.mass_model["rotary"] = "point inertias (exact sums)";
  return s;
}

}  // namespace ffr::formats::synthetic
