#pragma once
// An independent model of the synthetic spring chain (formats/synthetic.hpp) attached at its
// clamped point A to a hub turning about a fixed axis through A: the full, unreduced nodal
// equations in the hub frame, written directly from Newton's law for the point masses
//   m_p (u_dd + 2 w x u_d + a x x + w x (w x x)) + ((K + K_G) u + D u_d)_p = m_p R^T g,   x = c + u
// and, when the hub turns freely with inertia J about axis e,
//   J theta_dd = e . sum_p x_p x ((K + K_G) u + D u_d)_p    (the clamp moment drives the hub),
// integrated with classical RK4. No modes, no shape integrals, no natural coordinates.
// D is the chain's modal damping (ratio zeta on every mode). K_G is the geometric stiffness of the inertial loads (frame acceleration minus gravity,
// angular acceleration, centrifugal), built from the chain's own static solves.

#include "ffr/formats/synthetic.hpp"
#include "ffr/runtime/table.hpp"

#include <Eigen/Core>

namespace ffr::runtime::test {

class ChainOracle {
 public:
  /// axis: unit hub axis (global = hub frame at theta = 0); gravity global; J > 0 free hub,
  /// otherwise theta(t) from `drive`.
  ChainOracle(const formats::synthetic::ChainModel& chain, const Eigen::Vector3d& axis, const Eigen::Vector3d& gravity,
              bool stiffening, double J, const Table* drive);

  void step(double h);  ///< one RK4 step
  double time() const { return t_; }
  double theta() const { return theta_; }
  /// Displacement of point p in the hub frame.
  Eigen::Vector3d displacement(int p) const { return u_.segment<3>(3 * p); }

 private:
  struct Rate {
    double th, w;
    Eigen::VectorXd u, v;
  };
  Rate rate(double t, double th, double w, const Eigen::VectorXd& u, const Eigen::VectorXd& v) const;

  const formats::synthetic::ChainModel& c_;
  Eigen::Vector3d e_, g_;
  bool stiff_;
  double J_;
  const Table* drive_;
  Eigen::MatrixXd KGt_[3], KGr_[3], KGw_[6], D_;
  double t_ = 0, theta_ = 0, w_ = 0;
  Eigen::VectorXd u_, v_;
};

}  // namespace ffr::runtime::test
