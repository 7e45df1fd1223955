#include "reissner_beam.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ffr::runtime::test {

Eigen::VectorXd ReissnerBeam::reference() const {
  Eigen::VectorXd u(ndof());
  for (int i = 0; i <= n; ++i) {
    const double s = L * i / n;
    u.segment<3>(3 * i) << x0 + s * std::cos(phi0), y0 + s * std::sin(phi0), phi0;
  }
  return u;
}

namespace {

// Strains of one element and their first and second derivatives with respect to the element's
// six coordinates (xa, ya, tha, xb, yb, thb).
struct ElementStrains {
  double G1, G2, k;
  Eigen::Matrix<double, 6, 1> dG1, dG2, dk;
  Eigen::Matrix<double, 6, 6> ddG1, ddG2;
};

ElementStrains strains(const Eigen::Matrix<double, 6, 1>& ue, double L0) {
  ElementStrains s;
  const Eigen::Vector2d rp = (ue.segment<2>(3) - ue.segment<2>(0)) / L0;
  const double th = 0.5 * (ue(2) + ue(5));
  const Eigen::Vector2d e1(std::cos(th), std::sin(th)), e2(-std::sin(th), std::cos(th));
  s.G1 = rp.dot(e1) - 1;
  s.G2 = rp.dot(e2);
  s.k = (ue(5) - ue(2)) / L0;
  s.dG1.setZero();
  s.dG2.setZero();
  s.dk.setZero();
  s.dG1.segment<2>(0) = -e1 / L0;
  s.dG1.segment<2>(3) = e1 / L0;
  s.dG1(2) = s.dG1(5) = 0.5 * rp.dot(e2);
  s.dG2.segment<2>(0) = -e2 / L0;
  s.dG2.segment<2>(3) = e2 / L0;
  s.dG2(2) = s.dG2(5) = -0.5 * rp.dot(e1);
  s.dk(2) = -1 / L0;
  s.dk(5) = 1 / L0;
  s.ddG1.setZero();
  s.ddG2.setZero();
  for (int t : {2, 5}) {
    s.ddG1.block<2, 1>(0, t) = -0.5 * e2 / L0;
    s.ddG1.block<2, 1>(3, t) = 0.5 * e2 / L0;
    s.ddG2.block<2, 1>(0, t) = 0.5 * e1 / L0;
    s.ddG2.block<2, 1>(3, t) = -0.5 * e1 / L0;
    for (int r : {2, 5}) {
      s.ddG1(r, t) = -0.25 * rp.dot(e1);
      s.ddG2(r, t) = -0.25 * rp.dot(e2);
    }
  }
  for (int t : {2, 5})
    for (int r : {0, 1, 3, 4}) {
      s.ddG1(t, r) = s.ddG1(r, t);
      s.ddG2(t, r) = s.ddG2(r, t);
    }
  return s;
}

// Solves T x = b for a symmetric positive definite T whose nonzeros lie within `band` of the
// diagonal (the beam's nodes couple only their neighbours): banded Cholesky, O(n band^2).
Eigen::VectorXd banded_spd_solve(Eigen::MatrixXd T, const Eigen::VectorXd& b, int band) {
  const int n = static_cast<int>(T.rows());
  for (int j = 0; j < n; ++j) {
    for (int k = std::max(0, j - band); k < j; ++k) T(j, j) -= T(j, k) * T(j, k);
    if (!(T(j, j) > 0)) throw std::runtime_error("Reissner beam oracle: tangent not positive definite");
    T(j, j) = std::sqrt(T(j, j));
    for (int i = j + 1; i <= std::min(n - 1, j + band); ++i) {
      for (int k = std::max(0, i - band); k < j; ++k) T(i, j) -= T(i, k) * T(j, k);
      T(i, j) /= T(j, j);
    }
  }
  Eigen::VectorXd x = b;
  for (int i = 0; i < n; ++i) {
    for (int k = std::max(0, i - band); k < i; ++k) x(i) -= T(i, k) * x(k);
    x(i) /= T(i, i);
  }
  for (int i = n - 1; i >= 0; --i) {
    for (int k = i + 1; k <= std::min(n - 1, i + band); ++k) x(i) -= T(k, i) * x(k);
    x(i) /= T(i, i);
  }
  return x;
}

}  // namespace

void ReissnerBeam::internal(const Eigen::VectorXd& u, Eigen::VectorXd& f, Eigen::MatrixXd* K) const {
  const double L0 = L / n;
  f = Eigen::VectorXd::Zero(ndof());
  if (K) *K = Eigen::MatrixXd::Zero(ndof(), ndof());
  for (int e = 0; e < n; ++e) {
    // Curvature relative to the straight reference: theta is absolute, so k = dtheta/ds.
    ElementStrains s = strains(u.segment<6>(3 * e), L0);
    if (green_axial) {  // Gamma = G1 + G1^2 / 2: dGamma = (1 + G1) dG1, ddGamma = dG1 dG1^T + (1 + G1) ddG1
      s.ddG1 = s.dG1 * s.dG1.transpose() + (1 + s.G1) * s.ddG1;
      s.dG1 *= 1 + s.G1;
      s.G1 += 0.5 * s.G1 * s.G1;
    }
    f.segment<6>(3 * e) += L0 * (EA * s.G1 * s.dG1 + GA * s.G2 * s.dG2 + EI * s.k * s.dk);
    if (K)
      K->block<6, 6>(3 * e, 3 * e) += L0 * (EA * s.dG1 * s.dG1.transpose() + GA * s.dG2 * s.dG2.transpose() +
                                            EI * s.dk * s.dk.transpose() + EA * s.G1 * s.ddG1 + GA * s.G2 * s.ddG2);
  }
}

double ReissnerBeam::strain_energy(const Eigen::VectorXd& u) const {
  const double L0 = L / n;
  double U = 0;
  for (int e = 0; e < n; ++e) {
    ElementStrains s = strains(u.segment<6>(3 * e), L0);
    if (green_axial) s.G1 += 0.5 * s.G1 * s.G1;
    U += 0.5 * L0 * (EA * s.G1 * s.G1 + GA * s.G2 * s.G2 + EI * s.k * s.k);
  }
  return U;
}

Eigen::MatrixXd ReissnerBeam::mass() const {
  const double L0 = L / n;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(ndof(), ndof());
  for (int e = 0; e < n; ++e) {
    const int a = 3 * e, b = 3 * e + 3;
    for (int c = 0; c < 2; ++c) {
      M(a + c, a + c) += rhoA * L0 / 3;
      M(b + c, b + c) += rhoA * L0 / 3;
      M(a + c, b + c) += rhoA * L0 / 6;
      M(b + c, a + c) += rhoA * L0 / 6;
    }
    M(a + 2, a + 2) += rhoI * L0 / 2;
    M(b + 2, b + 2) += rhoI * L0 / 2;
  }
  return M;
}

BeamIntegrator::BeamIntegrator(const ReissnerBeam& b) : beam(b), M(b.mass()) {}

Eigen::VectorXd BeamIntegrator::external(double time) const {
  return load ? load(time) : Eigen::VectorXd::Zero(beam.ndof());
}

void BeamIntegrator::apply_prescribed(double time) {
  for (const auto& p : prescribed) {
    const Eigen::Vector3d m = p.motion(time);
    u(p.dof) = m(0);
    v(p.dof) = m(1);
    a(p.dof) = m(2);
  }
}

void BeamIntegrator::start(double t0, const Eigen::VectorXd& u0, const Eigen::VectorXd& v0) {
  t = t0;
  u = u0;
  v = v0;
  a = Eigen::VectorXd::Zero(beam.ndof());
  is_prescribed_.assign(static_cast<std::size_t>(beam.ndof()), 0);
  for (const auto& p : prescribed) is_prescribed_[static_cast<std::size_t>(p.dof)] = 1;
  free_.clear();
  for (int i = 0; i < beam.ndof(); ++i)
    if (!is_prescribed_[static_cast<std::size_t>(i)]) free_.push_back(i);
  apply_prescribed(t);
  // M_ff a_f = f_ext - f_int - M_fp a_p.
  Eigen::VectorXd fi;
  beam.internal(u, fi, nullptr);
  const Eigen::VectorXd r = external(t) - fi - M * a;
  const int nf = static_cast<int>(free_.size());
  Eigen::MatrixXd Mff(nf, nf);
  Eigen::VectorXd rf(nf);
  for (int i = 0; i < nf; ++i) {
    rf(i) = r(free_[i]);
    for (int j = 0; j < nf; ++j) Mff(i, j) = M(free_[i], free_[j]);
  }
  const Eigen::VectorXd af = Mff.ldlt().solve(rf);
  for (int i = 0; i < nf; ++i) a(free_[i]) = af(i);
}

void BeamIntegrator::step(double h) {
  const Eigen::VectorXd u0 = u, v0 = v, a0 = a;
  const double t1 = t + h;
  // Predictor: constant velocity (the stiff shear and rotation modes carry large accelerations
  // that a constant-acceleration predictor would throw far off).
  u = u0 + h * v0;
  v = v0;
  a = a0;
  apply_prescribed(t1);
  const int nf = static_cast<int>(free_.size());
  const Eigen::VectorXd fext = external(t1);
  Eigen::VectorXd fi;
  Eigen::MatrixXd K;
  double scale = 0, last_inc = 0;
  for (int it = 0; it < 40; ++it) {
    // a, v from u by the trapezoidal rule (free coordinates).
    for (int i : free_) {
      a(i) = 4 / (h * h) * (u(i) - u0(i) - h * v0(i)) - a0(i);
      v(i) = v0(i) + 0.5 * h * (a0(i) + a(i));
    }
    beam.internal(u, fi, &K);
    const Eigen::VectorXd r = M * a + fi - fext;
    Eigen::VectorXd rf(nf);
    Eigen::MatrixXd T(nf, nf);
    for (int i = 0; i < nf; ++i) {
      rf(i) = r(free_[i]);
      for (int j = 0; j < nf; ++j) T(i, j) = 4 / (h * h) * M(free_[i], free_[j]) + K(free_[i], free_[j]);
    }
    const Eigen::VectorXd du = banded_spd_solve(T, -rf, 5);
    for (int i = 0; i < nf; ++i) u(free_[i]) += du(i);
    if (it == 0) scale = std::max(1e-300, u.cwiseAbs().maxCoeff());
    const double inc = du.cwiseAbs().maxCoeff();
    // Converged, or stalled at round-off (the shear stiffness is large).
    const bool done = inc < 1e-13 * scale || (it >= 2 && inc < 1e-10 * scale && inc > 0.3 * last_inc);
    last_inc = inc;
    if (done) {
      for (int i : free_) {
        a(i) = 4 / (h * h) * (u(i) - u0(i) - h * v0(i)) - a0(i);
        v(i) = v0(i) + 0.5 * h * (a0(i) + a(i));
      }
      t = t1;
      return;
    }
  }
  throw std::runtime_error("Reissner beam oracle: Newton did not converge at t = " + std::to_string(t1));
}

}  // namespace ffr::runtime::test
