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
// With Stiffening::ExactAxial there is no K_G: the segments' axial springs are geometrically
// exact instead, each pulling along its present direction with k (l - l0) (l its present
// length; K u keeps the bending and the linear axial part, so the springs add
// k ((l - l0) d / l - e0 e0^T du)): the tension of any load and the foreshortening of large
// deflections come from the deformation itself, as for a body with its own modal stress
// (Ke/M1). With Stiffening::VonKarman the same springs carry the second-order strain
// eps = e0 . du / l0 + |du_perp|^2 / (2 l0^2) instead (du_perp = du - e0 (e0 . du)), the energy
// k l0^2 eps^2 / 2: the moderate-rotation theory of a body's own modal stress (formats/SPEC.md
// 10.1), exactly, where the exact springs differ from it at fourth order in the rotations.

#include "ffr/formats/synthetic.hpp"
#include "ffr/runtime/table.hpp"

#include <Eigen/Core>

namespace ffr::runtime::test {

class ChainOracle {
 public:
  /// axis: unit hub axis (global = hub frame at theta = 0); gravity global; J > 0 free hub,
  /// otherwise theta(t) from `drive`.
  enum class Stiffening { None, LoadCases, ExactAxial, VonKarman };
  ChainOracle(const formats::synthetic::ChainModel& chain, const Eigen::Vector3d& axis, const Eigen::Vector3d& gravity,
              Stiffening stiffening, double J, const Table* drive);

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
  Stiffening stiff_;
  /// The exact axial springs' forces beyond K's linear axial part, added to fe.
  void add_exact_axial(const Eigen::VectorXd& u, Eigen::VectorXd& fe) const;
  double J_;
  const Table* drive_;
  Eigen::MatrixXd KGt_[3], KGr_[3], KGw_[6], D_;
  double t_ = 0, theta_ = 0, w_ = 0;
  Eigen::VectorXd u_, v_;
};

}  // namespace ffr::runtime::test
