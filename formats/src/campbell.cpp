#include "ffr/formats/campbell.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace ffr::formats {

int spin_axis_from_string(const std::string& s) {
  if (s == "x" || s == "X") return 0;
  if (s == "y" || s == "Y") return 1;
  if (s == "z" || s == "Z") return 2;
  throw std::invalid_argument("spin axis must be x, y or z, not '" + s + "'");
}

SpinningSystem spinning_system(const Sid& s, int axis, double omega, const CampbellOptions& opt) {
  if (axis < 0 || axis > 2) throw std::invalid_argument("spin axis must be 0, 1 or 2");
  if (!std::isfinite(omega)) throw std::invalid_argument("spin speed must be finite");
  const Eigen::Index nq = s.nq();
  SpinningSystem sys;
  sys.M = s.Me;
  sys.C = opt.damping ? s.De : Eigen::MatrixXd::Zero(nq, nq);
  sys.K = s.Ke;
  // w = omega e_axis, so w_bar has the single entry omega^2 in column (axis, axis) = axis.
  const bool stiff = opt.stiffening && s.stiffening.has_value();
  for (Eigen::Index k = 0; k < nq; ++k)
    for (Eigen::Index i = 0; i < nq; ++i) {
      sys.C(i, k) += omega * s.Ge[k](i, axis);
      double kw = s.Oe.M1[k](i, axis);
      if (stiff) kw += s.stiffening->K0om[k](i, axis);
      sys.K(i, k) += omega * omega * kw;
    }
  // omega^2 overflows far below the largest double (1e155 rad/s), and Eigen's eigen-solver does
  // not converge on the infinite entries; the speed, not the solver, is at fault.
  if (!sys.K.allFinite() || !sys.C.allFinite()) {
    char speed[32];
    std::snprintf(speed, sizeof speed, "%g", omega);
    throw std::invalid_argument(std::string("spin speed ") + speed + " rad/s is too large: the spinning system's matrices overflow");
  }
  return sys;
}

Eigen::VectorXd spinning_frequencies_hz(const SpinningSystem& sys, Eigen::VectorXd* growth) {
  const Eigen::Index n = sys.M.rows();
  if (n == 0) return {};
  const Eigen::LLT<Eigen::MatrixXd> llt(sys.M);
  if (llt.info() != Eigen::Success) throw std::invalid_argument("Campbell: Me is not positive definite");
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  A.topRightCorner(n, n).setIdentity();
  A.bottomLeftCorner(n, n) = -llt.solve(sys.K);
  A.bottomRightCorner(n, n) = -llt.solve(sys.C);
  const Eigen::EigenSolver<Eigen::MatrixXd> es(A, false);
  if (es.info() != Eigen::Success) throw std::runtime_error("Campbell: eigenvalue solver did not converge");
  // Eigenvalues of a real matrix come in conjugate pairs (equal |Im|) and an even number of
  // real ones (|Im| = 0): sorted by |Im|, every second one is one mode's frequency.
  std::vector<std::complex<double>> ev(es.eigenvalues().data(), es.eigenvalues().data() + 2 * n);
  std::sort(ev.begin(), ev.end(), [](auto a, auto b) {
    return std::abs(a.imag()) != std::abs(b.imag()) ? std::abs(a.imag()) < std::abs(b.imag()) : a.real() < b.real();
  });
  Eigen::VectorXd f(n);
  if (growth) growth->resize(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const auto& l = ev[static_cast<std::size_t>(2 * k + 1)];
    f[k] = std::abs(l.imag()) / (2 * M_PI);
    if (growth) (*growth)[k] = std::max(l.real(), ev[static_cast<std::size_t>(2 * k)].real());
  }
  return f;
}

Campbell campbell(const Sid& sid, int axis, const std::vector<double>& speeds, const CampbellOptions& opt) {
  Campbell c;
  for (double w : speeds) {
    const Eigen::VectorXd f = spinning_frequencies_hz(spinning_system(sid, axis, w, opt));
    c.speeds_rad_s.push_back(w);
    c.frequency_hz.emplace_back(f.data(), f.data() + f.size());
  }
  return c;
}

}  // namespace ffr::formats
