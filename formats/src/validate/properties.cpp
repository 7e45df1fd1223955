// validate: symmetry, definiteness and physical plausibility of single members, and the
// integrity of the node and interface tables.
#include "context.hpp"

#include <Eigen/Eigenvalues>

#include <cstdio>
#include <set>

namespace ffr::formats::validation {
namespace {

Eigen::VectorXd eigenvalues(const Eigen::MatrixXd& A) {
  if (A.size() == 0) return Eigen::VectorXd();
  if (!A.allFinite()) return Eigen::VectorXd::Constant(A.rows(), NAN);
  const Eigen::MatrixXd S = 0.5 * (A + A.transpose());
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S, Eigen::EigenvaluesOnly).eigenvalues();
}

void symmetric(Context& cx, const std::string& name, const std::string& where, const Eigen::MatrixXd& A, double scale) {
  Worst w;
  w.add_matrix(A - A.transpose(), "[");
  cx.record(name + " symmetric", where, w, scale, cx.opt.identity_rtol, Check::Kind::Property);
}

// definite = true: every eigenvalue > 0; else >= -tol * scale.
void definite(Context& cx, const std::string& name, const std::string& where, const Eigen::MatrixXd& A, double scale,
              bool strict) {
  const Eigen::VectorXd e = eigenvalues(A);
  if (e.size() == 0) return cx.skip(name, where, "empty");
  const double lmin = e.minCoeff();
  const double abs = std::isnan(lmin) ? INFINITY : std::max(0.0, -lmin);
  const bool pass = strict ? lmin > 0 : abs <= cx.opt.identity_rtol * scale;
  char note[64];
  std::snprintf(note, sizeof note, "smallest eigenvalue %.6g", lmin);
  cx.record_value(name, where, abs, scale, pass, note, Check::Kind::Property);
}

// Principal moments of a physical inertia tensor: I3 <= I1 + I2.
void triangle(Context& cx, const std::string& name, const std::string& where, const Eigen::Matrix3d& J, double scale) {
  const Eigen::VectorXd e = eigenvalues(J);
  const double abs = std::isnan(e[0]) ? INFINITY : std::max(0.0, e[2] - e[0] - e[1]);
  cx.record_value(name, where, abs, scale, abs <= cx.opt.identity_rtol * scale, {}, Check::Kind::Property);
}

}  // namespace

void check_properties(Context& cx) {
  const Sid& s = cx.sid;
  const auto& sc = cx.sc;
  const double m = s.refmod.mass;
  cx.record_value("mass positive", "/refmod/mass", m > 0 ? 0.0 : std::abs(m) + 1, 1.0, m > 0 && std::isfinite(m), {},
                  Check::Kind::Property);

  const double sJ = sc.m * sc.L * sc.L;
  symmetric(cx, "Me", "/sid/Me/M0", s.Me, sc.q2());
  symmetric(cx, "Ke", "/sid/Ke/M0", s.Ke, sc.Ke);
  symmetric(cx, "De", "/sid/De/M0", s.De, s.De.size() ? std::max(s.De.cwiseAbs().maxCoeff(), 1e-300) : 1.0);
  symmetric(cx, "J.M0", "/sid/J/M0", s.J.M0, sJ);
  symmetric(cx, "rrdm", "/integrals/rrdm", s.integrals.rrdm, sJ);
  symmetric(cx, "rotary.I", "/integrals/rotary/I", s.rotary.I, sJ);
  symmetric(cx, "rotary.PsiIPsi", "/integrals/rotary/PsiIPsi", s.rotary.PsiIPsi, sc.q2());

  definite(cx, "Me positive definite", "/sid/Me/M0", s.Me, sc.q2(), true);
  definite(cx, "Ke positive semi-definite", "/sid/Ke/M0", s.Ke, sc.Ke, false);
  definite(cx, "De positive semi-definite", "/sid/De/M0", s.De,
           s.De.size() ? std::max(s.De.cwiseAbs().maxCoeff(), 1e-300) : 1.0, false);
  definite(cx, "J.M0 positive semi-definite", "/sid/J/M0", s.J.M0, sJ, false);  // a line of points has J_xx = 0
  triangle(cx, "J.M0 principal moments: triangle inequality", "/sid/J/M0", s.J.M0, sJ);
  if (m > 0) {
    const Eigen::Vector3d d = s.mdCM.M0;
    const Eigen::Matrix3d Jc = s.J.M0 - (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose()) / m;
    definite(cx, "J about the centre of mass positive semi-definite", "/sid/J/M0 /sid/mdCM/M0", Jc, sJ, false);
    triangle(cx, "J about the centre of mass: triangle inequality", "/sid/J/M0 /sid/mdCM/M0", Jc, sJ);
    const Eigen::Matrix3d cov = s.integrals.rrdm - s.integrals.rdm * s.integrals.rdm.transpose() / m;
    definite(cx, "rrdm - rdm rdm^T / m positive semi-definite", "/integrals/rrdm /integrals/rdm", cov, sJ, false);
  }
  definite(cx, "rotary.I positive semi-definite", "/integrals/rotary/I", s.rotary.I, sJ, false);
  // No triangle inequality for the rotary part: it is not a body (a shell's drilling
  // regularisation is inertia about the normal only); only the total J must be physical.
  definite(cx, "rotary.PsiIPsi positive semi-definite", "/integrals/rotary/PsiIPsi", s.rotary.PsiIPsi, sc.q2(), false);

  {
    Worst w;
    for (Eigen::Index k = 0; k < s.nq(); ++k)
      if (!(s.refmod.frequency_hz[k] >= 0)) w.add(std::isfinite(s.refmod.frequency_hz[k]) ? s.refmod.frequency_hz[k] : NAN, index({k}));
    cx.record_value("frequency_hz >= 0", "/refmod/frequency_hz", w.abs, 1.0, w.abs == 0, w.at.empty() ? "" : "at " + w.at,
                    Check::Kind::Property);
  }
  {
    // A normal mode is an elastic eigenmode (rigid-body modes are never stored): its
    // frequency is positive. Zeros here are what a dataset read back as fill values gives.
    std::string at;
    for (Eigen::Index k = 0; k < s.nq() && at.empty(); ++k)
      if (s.refmod.mode_type[static_cast<std::size_t>(k)] == ModeType::Normal && !(s.refmod.frequency_hz[k] > 0))
        at = "at " + index({k});
    cx.record_value("normal modes: frequency_hz > 0", "/refmod/frequency_hz /refmod/mode_type", at.empty() ? 0 : 1, 1.0,
                    at.empty(), at, Check::Kind::Property);
  }

  // Node and interface tables.
  {
    std::set<std::string> names;
    std::string dup;
    for (const auto& n : s.nodes)
      if (!names.insert(n.name).second || n.name.empty()) dup = n.name.empty() ? "(empty name)" : n.name;
    cx.record_value("node names unique and non-empty", "/nodes/name", dup.empty() ? 0 : 1, 1, dup.empty(), dup,
                    Check::Kind::Property);
    std::set<std::string> inames;
    dup.clear();
    for (const auto& i : s.interfaces)
      if (!inames.insert(i.name).second || i.name.empty()) dup = i.name.empty() ? "(empty name)" : i.name;
    cx.record_value("interface names unique and non-empty", "/interfaces/name", dup.empty() ? 0 : 1, 1, dup.empty(), dup,
                    Check::Kind::Property);
    Worst w;
    for (std::size_t p = 0; p < s.nodes.size(); ++p) {
      const Eigen::Matrix3d& A = s.nodes[p].AP0;
      w.add_matrix(A.transpose() * A - Eigen::Matrix3d::Identity(), s.nodes[p].name + "[");
      w.add(A.determinant() - 1, s.nodes[p].name + " det");
    }
    cx.record("AP0 are rotation matrices", "/nodes/AP0", w, 1.0, cx.opt.identity_rtol, Check::Kind::Property);
  }

  // Ke.M1[k] is a projected geometric stiffness: symmetric in (i,j) like K_G, but not in k.
  if (s.KeM1.empty()) {
    cx.skip("Ke.M1 symmetric in (i,j)", "/sid/Ke/M1", "no /sid/Ke/M1 in this file");
  } else {
    Worst w;
    double big = 0;
    for (std::size_t k = 0; k < s.KeM1.size(); ++k) {
      w.add_matrix(s.KeM1[k] - s.KeM1[k].transpose(), open_index({Eigen::Index(k)}));
      if (s.KeM1[k].size()) big = std::max(big, s.KeM1[k].cwiseAbs().maxCoeff());
    }
    cx.record("Ke.M1 symmetric in (i,j)", "/sid/Ke/M1", w, big > 0 && std::isfinite(big) ? big : 1.0,
              cx.opt.identity_rtol, Check::Kind::Property);
  }

  if (!s.stiffening) {
    cx.skip("stiffening symmetric in (k,i)", "/stiffening", "no /stiffening in this file");
    return;
  }
  Worst w;
  double big = 0;
  auto sym = [&](const auto& stack, const std::string& name) {
    for (std::size_t k = 0; k < stack.size(); ++k)
      for (std::size_t i = 0; i < stack.size(); ++i) {
        w.add_matrix(stack[k].row(i) - stack[i].row(k), open_index({Eigen::Index(k), Eigen::Index(i)}, name));
        big = std::max(big, stack[k].row(i).cwiseAbs().maxCoeff());
      }
  };
  sym(s.stiffening->K0t, "K0t");
  sym(s.stiffening->K0r, "K0r");
  sym(s.stiffening->K0om, "K0om");
  for (const auto& i : s.stiffening->interfaces) {
    sym(i.K0F, i.name + "/K0F");
    sym(i.K0M, i.name + "/K0M");
  }
  cx.record("stiffening symmetric in (k,i)", "/stiffening", w, big > 0 ? big : 1.0, cx.opt.identity_rtol);
}

}  // namespace ffr::formats::validation
