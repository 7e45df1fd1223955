// validate: identities that hold only for some mode types or references, to the accuracy of
// the eigen-solve (ValidateOptions::modal_rtol).
#include "context.hpp"

#include <Eigen/Eigenvalues>

#include <cstdio>
#include <string>

namespace ffr::formats::validation {

namespace {

// The stated damping model against De, in a basis-independent form so it holds for any
// reduction (Craig-Bampton bases are not the reduced system's eigenmodes):
//   "none": De = 0;  "rayleigh alpha=a beta=b": De = a Me + b Ke;
//   "ratio z": De = Me X diag(2 z w_r) X^T Me, (w_r^2, X) the Me-orthonormal eigenpairs of (Ke, Me).
void check_damping(Context& cx) {
  const Sid& s = cx.sid;
  const std::string name = "damping model: De as stated";
  const std::string& dm = s.provenance.damping_model;
  const Eigen::Index nq = s.nq();
  Eigen::MatrixXd expected;
  double z = 0, alpha = 0, beta = 0;
  if (dm == "none") {
    expected = Eigen::MatrixXd::Zero(nq, nq);
  } else if (std::sscanf(dm.c_str(), "rayleigh alpha=%lf beta=%lf", &alpha, &beta) == 2) {
    expected = alpha * s.Me + beta * s.Ke;
  } else if (std::sscanf(dm.c_str(), "ratio %lf", &z) == 1 && nq > 0) {
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(s.Ke, s.Me);
    if (es.info() != Eigen::Success) return cx.skip(name, "/sid/De/M0", "(Ke, Me) eigen-solve failed");
    const Eigen::MatrixXd MX = s.Me * es.eigenvectors();
    expected = MX * (2 * z * es.eigenvalues().cwiseMax(0.0).cwiseSqrt()).asDiagonal() * MX.transpose();
  } else {
    return cx.skip(name, "/sid/De/M0", "damping model '" + dm + "' is not one validate knows");
  }
  Worst w;
  w.add_matrix(s.De - expected, "[");
  const double scale = std::max(expected.size() ? expected.cwiseAbs().maxCoeff() : 0.0, s.De.size() ? s.De.cwiseAbs().maxCoeff() : 0.0);
  cx.record(name, "/sid/De/M0 /provenance@damping_model", w, scale > 0 ? scale : 1.0, cx.opt.modal_rtol);
}

}  // namespace

void check_modal(Context& cx) {
  const Sid& s = cx.sid;
  const Eigen::Index nq = s.nq();
  const double tol = cx.opt.modal_rtol;
  const auto& sc = cx.sc;
  const Eigen::VectorXd omega = 2 * M_PI * s.refmod.frequency_hz;

  {
    Worst w;
    for (Eigen::Index k = 0; k < nq; ++k)
      w.add(s.Me(k, k) > 0 ? omega[k] - std::sqrt(std::max(s.Ke(k, k), 0.0) / s.Me(k, k)) : INFINITY,
            index({k}));
    const double scale = nq ? omega.cwiseAbs().maxCoeff() : 1.0;
    cx.record("frequency_hz = sqrt(Ke_kk / Me_kk) / 2pi", "/refmod/frequency_hz /sid/Ke/M0 /sid/Me/M0", w,
              scale > 0 ? scale : 1.0, tol);
  }

  std::vector<Eigen::Index> normal, constraint;
  for (Eigen::Index k = 0; k < nq; ++k)
    (s.refmod.mode_type[k] == ModeType::Normal ? normal : constraint).push_back(k);
  const std::string me = "normal modes: Me = I", ke = "normal modes: Ke = diag(omega^2)";
  if (normal.empty()) {
    cx.skip(me, "/sid/Me/M0", "no normal modes");
    cx.skip(ke, "/sid/Ke/M0", "no normal modes");
  } else {
    Worst wm, wk;
    double wmax = 0;
    for (auto k : normal) wmax = std::max(wmax, omega[k] * omega[k]);
    for (auto k : normal)
      for (auto i : normal) {
        const std::string at = index({k, i});
        wm.add(s.Me(k, i) - (k == i ? 1.0 : 0.0), at);
        wk.add(s.Ke(k, i) - (k == i ? omega[k] * omega[k] : 0.0), at);
      }
    cx.record(me, "/sid/Me/M0", wm, 1.0, tol);
    cx.record(ke, "/sid/Ke/M0 /refmod/frequency_hz", wk, wmax > 0 ? wmax : sc.Ke, tol);
  }
  const std::string cb = "normal and constraint modes: Ke coupling = 0";
  if (normal.empty() || constraint.empty()) {
    cx.skip(cb, "/sid/Ke/M0", "needs both normal and constraint modes");
  } else {
    Worst w;
    for (auto k : normal)
      for (auto i : constraint) w.add(s.Ke(k, i), index({k, i}));
    cx.record(cb, "/sid/Ke/M0", w, sc.Ke, tol);
  }

  check_damping(cx);

  const std::string& ref = s.refmod.reference;
  const bool free = ref == "free";
  if (free) {
    Worst wt, wr;
    wt.add_matrix(s.Ct.M0, "[");
    wr.add_matrix(s.Cr.M0, "[");
    cx.record("free: Ct.M0 = 0", "/sid/Ct/M0", wt, sc.t1(), tol);
    cx.record("free: Cr.M0 = 0", "/sid/Cr/M0", wr, sc.r1(), tol);
  } else {
    cx.skip("free: Ct.M0 = 0", "/sid/Ct/M0", "reference is " + ref);
    cx.skip("free: Cr.M0 = 0", "/sid/Cr/M0", "reference is " + ref);
  }

  const std::string rv = "reference is free, clamped:<interface> or craig-bampton";
  const bool clamped = ref.rfind("clamped:", 0) == 0;
  const Interface* held = nullptr;
  if (clamped)
    for (const auto& i : s.interfaces)
      if (i.name == ref.substr(8)) held = &i;
  const bool valid = free || ref == "craig-bampton" || held;
  cx.record_value(rv, "/refmod/reference", valid ? 0 : 1, 1, valid, valid ? "" : "'" + ref + "'");
  const std::string cn = "clamped: the held interface node does not move";
  if (!held) {
    cx.skip(cn, "/nodes/phi /nodes/psi", clamped ? "no such interface" : "reference is " + ref);
  } else {
    const Node& n = s.nodes[static_cast<std::size_t>(held->node)];
    Worst w;
    w.add_matrix(n.phi / sc.phi, n.name + " phi[");
    w.add_matrix(n.psi * (sc.L / sc.phi), n.name + " psi[");
    cx.record(cn, "/nodes/phi /nodes/psi", w, 1.0, tol);
  }
}

}  // namespace ffr::formats::validation
