#include "chain_oracle.hpp"

#include <Eigen/Geometry>

namespace ffr::runtime::test {

using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

ChainOracle::ChainOracle(const formats::synthetic::ChainModel& chain, const Vector3d& axis, const Vector3d& gravity,
                         Stiffening stiffening, double J, const Table* drive)
    : c_(chain), e_(axis.normalized()), g_(gravity), stiff_(stiffening), J_(J), drive_(drive) {
  const int N = static_cast<int>(3 * chain.points.size());
  u_ = v_ = VectorXd::Zero(N);
  auto KG = [&](const VectorXd& f) { return chain.geometric_stiffness(chain.axial_forces(chain.static_deflection(f))); };
  for (int c = 0; c < 3; ++c) {
    VectorXd ft(N), fr(N);
    for (std::size_t p = 0; p < chain.points.size(); ++p) {
      ft.segment<3>(3 * p) = -chain.points[p].m * Vector3d::Unit(c);
      fr.segment<3>(3 * p) = -chain.points[p].m * Vector3d::Unit(c).cross(chain.points[p].c);
    }
    KGt_[c] = KG(ft);
    KGr_[c] = KG(fr);
  }
  for (int j = 0; j < 6; ++j) KGw_[j] = KG(chain.centrifugal_load(j));
  // Modal damping of ratio zeta on every mode: D = M Phi diag(2 zeta w) Phi^T M.
  const MatrixXd MPhi = chain.M * chain.Phi;
  D_ = MPhi * (2.0 * chain.params.damping_ratio * chain.omega).asDiagonal() * MPhi.transpose();
  if (drive_) {
    double d1, d2;
    drive_->eval(0, 0, theta_, d1, d2);
    w_ = d1;
  }
}

ChainOracle::Rate ChainOracle::rate(double t, double th, double w, const VectorXd& u, const VectorXd& v) const {
  const auto n = static_cast<int>(c_.points.size());
  const Eigen::Matrix3d R = Eigen::AngleAxisd(th, e_).toRotationMatrix();
  const Vector3d gb = R.transpose() * g_;
  double alpha = 0;
  if (drive_) {
    double v0, v1;
    drive_->eval(t, 0, v0, v1, alpha);
  }
  Rate r;
  r.th = w;
  r.u = v;
  r.v = VectorXd::Zero(3 * n);
  const Vector3d omega = w * e_;
  // Elastic forces; with stiffening K_G depends on the hub's angular acceleration, which for a
  // free hub depends on the elastic forces: two fixed-point passes settle it.
  VectorXd fe = c_.K * u + D_ * v;
  const bool load_cases = stiff_ == Stiffening::LoadCases;
  for (int pass = 0; pass < (load_cases ? 3 : 1); ++pass) {
    fe = c_.K * u + D_ * v;
    if (stiff_ == Stiffening::ExactAxial || stiff_ == Stiffening::VonKarman) add_exact_axial(u, fe);
    if (load_cases) {
      const Vector3d acc = -gb, al = alpha * e_;
      const double wb[6] = {omega(0) * omega(0), omega(1) * omega(1), omega(2) * omega(2),
                            omega(0) * omega(1), omega(1) * omega(2), omega(0) * omega(2)};
      MatrixXd KG = MatrixXd::Zero(3 * n, 3 * n);
      for (int c = 0; c < 3; ++c) KG += acc(c) * KGt_[c] + al(c) * KGr_[c];
      for (int j = 0; j < 6; ++j) KG += wb[j] * KGw_[j];
      fe += KG * u;
    }
    if (!drive_) {
      Vector3d moment = Vector3d::Zero();
      for (int p = 0; p < n; ++p) moment += (c_.points[p].c + u.segment<3>(3 * p)).cross(Vector3d(fe.segment<3>(3 * p)));
      alpha = e_.dot(moment) / J_;
    }
  }
  r.w = alpha;
  const Vector3d al = alpha * e_;
  for (int p = c_.params.clamped ? 1 : 0; p < n; ++p) {
    const double m = c_.points[p].m;
    const Vector3d x = c_.points[p].c + u.segment<3>(3 * p), ud = v.segment<3>(3 * p);
    r.v.segment<3>(3 * p) = -Vector3d(fe.segment<3>(3 * p)) / m + gb - 2 * omega.cross(ud) - al.cross(x) - omega.cross(omega.cross(x));
  }
  return r;
}

void ChainOracle::add_exact_axial(const VectorXd& u, VectorXd& fe) const {
  const auto n = static_cast<int>(c_.points.size());
  for (int e = 0; e + 1 < n; ++e) {
    const Vector3d d0 = c_.points[e + 1].c - c_.points[e].c;
    const double l0 = d0.norm(), k = c_.params.EA / l0;
    const Vector3d e0 = d0 / l0, du = u.segment<3>(3 * (e + 1)) - u.segment<3>(3 * e);
    Vector3d f;  // on point e + 1; minus on e
    if (stiff_ == Stiffening::VonKarman) {
      const Vector3d perp = du - e0 * e0.dot(du);
      const double stretch = e0.dot(du) + 0.5 * perp.squaredNorm() / l0;  // l0 eps
      f = k * (stretch * (e0 + perp / l0) - e0 * e0.dot(du));
    } else {
      const Vector3d d = d0 + du;
      const double l = d.norm();
      f = k * ((l - l0) / l * d - e0 * e0.dot(du));
    }
    fe.segment<3>(3 * (e + 1)) += f;
    fe.segment<3>(3 * e) -= f;
  }
}

void ChainOracle::step(double h) {
  const Rate k1 = rate(t_, theta_, w_, u_, v_);
  const Rate k2 = rate(t_ + h / 2, theta_ + h / 2 * k1.th, w_ + h / 2 * k1.w, u_ + h / 2 * k1.u, v_ + h / 2 * k1.v);
  const Rate k3 = rate(t_ + h / 2, theta_ + h / 2 * k2.th, w_ + h / 2 * k2.w, u_ + h / 2 * k2.u, v_ + h / 2 * k2.v);
  const Rate k4 = rate(t_ + h, theta_ + h * k3.th, w_ + h * k3.w, u_ + h * k3.u, v_ + h * k3.v);
  theta_ += h / 6 * (k1.th + 2 * k2.th + 2 * k3.th + k4.th);
  w_ += h / 6 * (k1.w + 2 * k2.w + 2 * k3.w + k4.w);
  u_ += h / 6 * (k1.u + 2 * k2.u + 2 * k3.u + k4.u);
  v_ += h / 6 * (k1.v + 2 * k2.v + 2 * k3.v + k4.v);
  t_ += h;
  if (drive_) {
    double d1, d2;
    drive_->eval(t_, 0, theta_, d1, d2);
    w_ = d1;
  }
}

}  // namespace ffr::runtime::test
