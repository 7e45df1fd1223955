#pragma once
// An independent oracle for the runtime's stiffened flexible bodies: a planar geometrically
// exact beam (Reissner 1972, "On one-dimensional finite-strain beam theory: the plane problem",
// ZAMP 23; Simo & Vu-Quoc 1986, "On the dynamics of flexible beams under large overall
// motions - the plane case", J. Appl. Mech. 53), written from the theory alone: no runtime code.
//
// Nodes carry (x, y, theta) in the global plane. Two-node elements, one-point (reduced)
// quadrature, which is free of shear locking: at the midpoint r' = (r_b - r_a)/L0,
// theta_m = (theta_a + theta_b)/2, and the strains are
//   axial  G1 = r' . e1(theta_m) - 1,   shear G2 = r' . e2(theta_m),   curvature k = (theta_b - theta_a)/L0
// with e1 = (cos, sin), e2 = (-sin, cos); U_e = L0/2 (EA G1^2 + GA G2^2 + EI k^2). In these
// coordinates the kinetic energy is exactly 1/2 (rho A int |r_dot|^2 + rho I int theta_dot^2): a
// constant mass matrix (consistent for the translations, lumped for the rotation).
// Time integration: the trapezoidal rule (Newmark beta = 1/4, gamma = 1/2) with Newton on the
// free coordinates; prescribed coordinates follow given functions of time.
#include <Eigen/Dense>

#include <functional>
#include <vector>

namespace ffr::runtime::test {

struct ReissnerBeam {
  // Section and material.
  double EA = 0, GA = 0, EI = 0, rhoA = 0, rhoI = 0;
  // Undeformed straight beam from (x0, y0) along the angle phi0, n elements of length L / n.
  double L = 1, x0 = 0, y0 = 0, phi0 = 0;
  int n = 20;
  // The axial energy's strain: false, G1 (the theory above, a linear force-stretch law); true,
  // the Green strain of the stretch, Gamma = ((1 + G1)^2 - 1) / 2 = G1 + G1^2 / 2, EA Gamma^2 / 2
  // (the axial law of the ANCF beams of Berzeri & Shabana, for large stretches).
  bool green_axial = false;

  int ndof() const { return 3 * (n + 1); }
  /// Reference configuration (x, y, theta per node).
  Eigen::VectorXd reference() const;
  /// Internal force (gradient of the strain energy) and its tangent.
  void internal(const Eigen::VectorXd& u, Eigen::VectorXd& f, Eigen::MatrixXd* K) const;
  double strain_energy(const Eigen::VectorXd& u) const;
  /// Constant mass matrix.
  Eigen::MatrixXd mass() const;
};

/// A coordinate prescribed as a function of time: value, rate, acceleration.
struct Prescribed {
  int dof = 0;
  std::function<Eigen::Vector3d(double)> motion;
};

/// Trapezoidal integration of M a + f_int(u) = f_ext(t, u) with prescribed coordinates.
struct BeamIntegrator {
  const ReissnerBeam& beam;
  Eigen::MatrixXd M;                 ///< beam mass plus point masses (add to it before start)
  std::vector<Prescribed> prescribed;
  /// Dead loads at coordinates (optional): f_ext(t).
  std::function<Eigen::VectorXd(double)> load;
  double t = 0;
  Eigen::VectorXd u, v, a;

  explicit BeamIntegrator(const ReissnerBeam& b);
  /// Sets t, u, v, the prescribed coordinates, and consistent accelerations.
  void start(double t0, const Eigen::VectorXd& u0, const Eigen::VectorXd& v0);
  /// One step of h; throws std::runtime_error when Newton fails.
  void step(double h);
  double kinetic_energy() const { return 0.5 * v.dot(M * v); }

 private:
  std::vector<int> free_;
  std::vector<char> is_prescribed_;
  void apply_prescribed(double time);
  Eigen::VectorXd external(double time) const;
};

}  // namespace ffr::runtime::test
