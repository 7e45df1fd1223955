#include "obstacle_course.hpp"

#include "ffr/preproc/elements/shell.hpp"

#include "fe_driver.hpp"

#include <cmath>

namespace ffr::test {

using preproc::ElementType;
using preproc::ShellSection;

namespace {

constexpr double kPi = 3.14159265358979323846;
enum Dof { UX, UY, UZ, RX, RY, RZ };

struct Model {
  Grid g;
  Assembler as;
  std::vector<bool> fixed;
  Eigen::VectorXd f;
  Model(Grid grid, ElementType type, const ShellSection& s)
      : g(std::move(grid)), as(static_cast<int>(g.x.rows())), fixed(6 * g.x.rows(), false),
        f(Eigen::VectorXd::Zero(6 * g.x.rows())) {
    for (const auto& e : type == ElementType::Quad4 ? g.quads() : g.triangles())
      as.add(e, preproc::shell_element(type, g.coords(e), s));
  }
  void fix(int node, std::initializer_list<Dof> dofs) {
    for (Dof d : dofs) fixed[6 * node + d] = true;
  }
  Eigen::VectorXd solve() const { return solve_static(as.K(), f, fixed); }
};

}  // namespace

double scordelis_lo(int n, ElementType type) {
  const double R = 25, L = 50, phi = 40 * kPi / 180, t = 0.25, q = 90;
  // Axis along x; u in [0, 1] runs from midspan (x = 0) to the diaphragm (x = L/2), v from the
  // crown to the free edge. Mid-surface (x, R sin a, R cos a).
  Grid g = make_grid(n, n, [&](double u, double v) {
    const double a = v * phi;
    return Eigen::Vector3d(u * L / 2, R * std::sin(a), R * std::cos(a));
  });
  // Self weight as the consistent load of the mass: rho t = q per unit area, g = 1 along -z.
  Model m(std::move(g), type, ShellSection{t, {4.32e8, 0.0, q / t}});
  Eigen::VectorXd down = Eigen::VectorXd::Zero(m.f.size());
  for (int i = 0; i < m.g.x.rows(); ++i) down(6 * i + UZ) = -1;
  m.f = m.as.M() * down;
  for (int k = 0; k <= n; ++k) {
    m.fix(m.g.node(n, k), {UY, UZ, RX});  // rigid diaphragm at x = L/2
    m.fix(m.g.node(0, k), {UX, RY, RZ});  // symmetry x = 0
    m.fix(m.g.node(k, 0), {UY, RX, RZ});  // symmetry y = 0 (crown)
  }
  const Eigen::VectorXd u = m.solve();
  return -u(6 * m.g.node(0, n) + UZ);
}

double pinched_cylinder(int n, ElementType type) {
  const double R = 300, L = 600, t = 3;
  // Axis along x, u from midspan to the diaphragm, v from the z = 0 plane (a = 0) to the
  // loaded generator at the top (a = 90 deg): (x, R cos a, R sin a).
  Grid g = make_grid(n, n, [&](double u, double v) {
    const double a = v * kPi / 2;
    return Eigen::Vector3d(u * L / 2, R * std::cos(a), R * std::sin(a));
  });
  Model m(std::move(g), type, ShellSection{t, {3e6, 0.3, 1}});
  for (int k = 0; k <= n; ++k) {
    m.fix(m.g.node(n, k), {UY, UZ, RX});  // diaphragm
    m.fix(m.g.node(0, k), {UX, RY, RZ});  // symmetry x = 0
    m.fix(m.g.node(k, 0), {UZ, RX, RY});  // symmetry z = 0
    m.fix(m.g.node(k, n), {UY, RX, RZ});  // symmetry y = 0
  }
  const int load = m.g.node(0, n);
  m.f(6 * load + UZ) = -0.25;  // a quarter of the unit load on the octant
  const Eigen::VectorXd u = m.solve();
  return -u(6 * load + UZ);
}

double pinched_hemisphere(int n, ElementType type) {
  const double R = 10, t = 0.04, hole = 18 * kPi / 180;
  // u: azimuth 0..90 deg from the x axis to the y axis; v: from the equator up to the hole.
  Grid g = make_grid(n, n, [&](double u, double v) {
    const double lam = u * kPi / 2, polar = kPi / 2 - v * (kPi / 2 - hole);
    return Eigen::Vector3d(R * std::sin(polar) * std::cos(lam), R * std::sin(polar) * std::sin(lam),
                           R * std::cos(polar));
  });
  Model m(std::move(g), type, ShellSection{t, {6.825e7, 0.3, 1}});
  for (int k = 0; k <= n; ++k) {
    m.fix(m.g.node(0, k), {UY, RX, RZ});  // symmetry y = 0
    m.fix(m.g.node(n, k), {UX, RY, RZ});  // symmetry x = 0
  }
  m.fix(m.g.node(n / 2, 0), {UZ});  // rigid vertical translation; the loads have no z part
  const int a = m.g.node(0, 0), b = m.g.node(n, 0);
  m.f(6 * a + UX) = 1.0;   // half of the outward load 2 on the symmetry plane
  m.f(6 * b + UY) = -1.0;  // half of the inward load 2
  const Eigen::VectorXd u = m.solve();
  return u(6 * a + UX);
}

double twisted_beam(int nw, int nl, bool in_plane, ElementType type) {
  const double L = 12, w = 1.1, t = 0.32;
  // Axis along x; the section's width direction turns from y (root) to z (tip).
  Grid g = make_grid(nl, nw, [&](double u, double v) {
    const double a = u * kPi / 2, s = (v - 0.5) * w;
    return Eigen::Vector3d(u * L, s * std::cos(a), s * std::sin(a));
  });
  Model m(std::move(g), type, ShellSection{t, {29e6, 0.22, 1}});
  for (int k = 0; k <= nw; ++k) m.fix(m.g.node(0, k), {UX, UY, UZ, RX, RY, RZ});
  // Unit tip load, consistently distributed along the tip edge (linear edge functions).
  const Dof dir = in_plane ? UZ : UY;  // tip width direction is z, thickness direction is y
  for (int k = 0; k < nw; ++k)
    for (int e : {k, k + 1}) m.f(6 * m.g.node(nl, e) + dir) += 0.5 / nw;
  const Eigen::VectorXd u = m.solve();
  double mean = 0;
  for (int k = 0; k <= nw; ++k) mean += u(6 * m.g.node(nl, k) + dir);
  return mean / (nw + 1);
}

}  // namespace ffr::test
