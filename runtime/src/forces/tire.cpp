// Tyre: a disc wheel in point contact with a road (FORMULATION.md section 8, tyres).
//
// The road under the wheel centre c is replaced by its tangent plane at s = c . d (d the travel
// direction, u up): normal n = (u - h'(s) d) / sqrt(1 + h'^2), the centre's distance from the
// plane D = (c . u - h(s)) / sqrt(1 + h'^2). The disc (centre c, unit spin axis a, radius R) reaches
// deepest into the plane at c - R r/|r|, r = n - (n . a) a, so the deflection is
// delta = R |r| - D. The normal force is Fn = max(0, k delta + c_v delta_dot) while delta > 0:
// lift-off allowed, never pulling. In the contact frame t = a x n / |r| (rolling direction for a
// positive spin about a), l = n x t, the wheel's material point at the contact point P = c - R r/|r|
// + delta n slides at v_P = c_dot + omega x (P - c); with V = sqrt((c_dot . t)^2 + v_tol^2)
//   Fx = -C_kappa (v_P . t) / V,  Fy = -C_alpha (v_P . l) / V    (C_kappa kappa, C_alpha tan(alpha))
// and (Fx, Fy) scaled onto the circle mu Fn when longer. The force Fn n + Fx t + Fy l acts at P: at
// the wheel centre with the torque (P - c) x F.
//
// The marker's point p and axes e_k (a = e_0) carry the force: F does virtual work F . dp, a torque
// tau does tau . dtheta with dtheta = 1/2 sum_k e_k x de_k, so Q = J_p^T F + sum_k J_k^T g_k with
// g_k = 1/2 tau x e_k. The law is a function of x = [p, e_k] and x_dot = [p_dot, e_k_dot] (24
// numbers; omega = 1/2 sum_k e_k x e_k_dot); its derivatives dg/dx, dg/dx_dot come exactly from
// forward-mode automatic differentiation of the same code (Eigen's AutoDiffScalar, fixed size: no
// allocation), and the tangent is
//   K = J^T (dg/dx J + dg/dx_dot dJ/dz z_dot) - d(J^T g)/dz|_g,   C = J^T dg/dx_dot J   (negated)
// where the last two pieces are nonzero only for a wheel on a node of a flexible body
// (force_helpers.hpp).
//
// The deflection rate is taken over the tangent plane held still: delta_dot = -c_dot . n +
// R d|r|/dt at fixed n. Why not the full time derivative: it adds the turning of the plane as
// the wheel travels over the road's curvature h'', and h'' jumps at every point of a PCHIP
// profile, so the damper's force would jump where the wheel passes a point; Newton cycled there
// (a quarter car whose wheel reached a profile point at a step's end). The term is of order
// D h' h'' V (0.5 % of the damper's force in the quarter-car test). Without it the force is
// continuous over a C1 road, and the tangent below is exact off the friction circle.
#include "force_helpers.hpp"
#include "forces.hpp"

#include <unsupported/Eigen/AutoDiff>

#include <array>
#include <cmath>

namespace ffr::runtime::detail {
namespace {

using AD = Eigen::AutoDiffScalar<Eigen::Matrix<double, 24, 1>>;
template <class T>
using V3 = Eigen::Matrix<T, 3, 1>;

double val(double x) { return x; }
double val(const AD& x) { return x.value(); }

template <class T>
T dot(const V3<T>& a, const V3<T>& b) {
  return a(0) * b(0) + a(1) * b(1) + a(2) * b(2);
}
template <class T>
T dotc(const V3<T>& a, const Vector3d& b) {
  return a(0) * b(0) + a(1) * b(1) + a(2) * b(2);
}
template <class T>
V3<T> cross(const V3<T>& a, const V3<T>& b) {
  return V3<T>(a(1) * b(2) - a(2) * b(1), a(2) * b(0) - a(0) * b(2), a(0) * b(1) - a(1) * b(0));
}
template <class T>
V3<T> scaled(const V3<T>& a, const T& s) {
  return V3<T>(a(0) * s, a(1) * s, a(2) * s);
}
// c0 u + c1 v with constant vectors u, v.
template <class T>
V3<T> combine(const T& c0, const Vector3d& u, const T& c1, const Vector3d& v) {
  return V3<T>(c0 * u(0) + c1 * v(0), c0 * u(1) + c1 * v(1), c0 * u(2) + c1 * v(2));
}

// What the law gives: the force on the wheel at its centre and the torque about it, and the
// contact quantities the outputs report.
template <class T>
struct Contact {
  V3<T> F = V3<T>::Zero(), tau = V3<T>::Zero();
  double Fx = 0, Fy = 0, Fn = 0, kappa = 0, alpha = 0, delta = 0;
  bool sliding = false;  ///< the linear slip force beyond kSlidingBand times the friction circle
};

// Sliding "well beyond" the friction circle: the linear law's force above this multiple of
// mu Fn. Measured on the vehicle example's speed-up (its front tyres slide at 1.2 to 1.6 times
// the circle), Newton iterations over its first 5 s at h = 4 ms: 4667 with the secant slope
// throughout; with the exact slope in every tangent beyond 1.25, 1.1 and 1.02 times the circle
// 2809, 2425 and 2305 (but the incline and spin-up tests then failed, see contact()); in the
// step's first tangent only, beyond 1.1, 2526. The band keeps the exact slope off the kink.
constexpr double kSlidingBand = 1.1;

template <class T>
Contact<T> contact(const Tire& ty, const Road& rd, const V3<T>& c, const std::array<V3<T>, 3>& e, const V3<T>& cd,
                   const std::array<V3<T>, 3>& ed, bool exact_sliding = false) {
  using std::sqrt;
  Contact<T> r;
  const Vector3d& u = rd.up;
  const Vector3d& d = rd.direction;
  const double R = ty.radius;
  // The road's height and slope at s, with their derivatives through s (for AD).
  const T s = dotc(c, d);
  double h0, h1, h2;
  rd.profile.eval(val(s), 0, h0, h1, h2);
  const T ds = s - val(s);  // zero, carrying s's derivatives
  const T h = h0 + h1 * ds, hp = h1 + h2 * ds;  // (at a PCHIP point, the right-hand h'')
  const T ct = 1.0 / sqrt(1.0 + hp * hp);  // cosine of the road's slope
  const V3<T> n = combine<T>(ct, u, -hp * ct, d);
  const T height = dotc(c, u) - h;
  const T D = height * ct;
  const V3<T>& a = e[0];
  const T na = dot(n, a);
  const T rn2 = 1.0 - na * na;
  // A wheel lying flat on the road has no rolling contact (the loader refuses such an axis).
  if (!(val(rn2) > 1e-12)) return r;
  const T rn = sqrt(rn2);
  const T delta = R * rn - D;
  r.delta = val(delta);
  if (!(r.delta > 0)) return r;
  // The deflection rate over the tangent plane (n held: see above).
  const T Dd = dot(cd, n);
  const T nad = dot(n, ed[0]);
  const T deltad = -R * na * nad / rn - Dd;
  const T Fn = ty.vertical_stiffness * delta + ty.vertical_damping * deltad;
  if (!(val(Fn) > 0)) return r;  // leaving the road faster than the damper lets it push
  r.Fn = val(Fn);
  const T inv = 1.0 / rn;
  const V3<T> rhat = scaled<T>(n - scaled<T>(a, na), inv);
  const V3<T> rho = scaled<T>(rhat, T(-R)) + scaled<T>(n, delta);  // centre to contact point
  V3<T> F = scaled<T>(n, Fn);
  const bool slips = ty.longitudinal_stiffness > 0 || ty.cornering_stiffness > 0;
  if (slips) {
    const V3<T> t = scaled<T>(cross(a, n), inv);
    const V3<T> l = cross(n, t);
    const V3<T> w = scaled<T>(cross(e[0], ed[0]) + cross(e[1], ed[1]) + cross(e[2], ed[2]), T(0.5));
    const V3<T> vp = cd + cross(w, rho);
    const T vsx = dot(vp, t), vsy = dot(vp, l), Vx = dot(cd, t);
    const T V = sqrt(Vx * Vx + ty.velocity_tolerance * ty.velocity_tolerance);
    T Fx = -ty.longitudinal_stiffness * vsx / V, Fy = -ty.cornering_stiffness * vsy / V;
    const T Fmax = ty.friction * Fn;
    const T Fh2 = Fx * Fx + Fy * Fy;
    if (val(Fh2) > val(Fmax) * val(Fmax)) {
      // On the friction circle the tangent takes the secant slope in the slips, mu Fn / |F_lin|
      // times the linear law's (|F_lin| held; Fn's derivatives kept): with the exact slope (zero
      // along the sliding direction) Newton jumped across the circle and back, as for the friction
      // dampers (a wheel released on an incline, from rest); the secant (Kacanov) iteration
      // converges to the same, exact, force, but only linearly, at a rate set by how much the
      // secant overstates the slope (on the vehicle example's speed-up, with its front tyres
      // sliding, 0.5 an iteration and 8 iterations a step at h = 4 ms). So a tyre that slid well
      // beyond the circle at the last accepted state and still does takes the exact slope in the
      // step's first tangent (exact_sliding: Data::first_tangent_of_step, tire_sliding); the
      // refreshes a slow iteration asks for take the secant again.
      const double lin = std::sqrt(val(Fh2));
      r.sliding = lin > kSlidingBand * val(Fmax);
      const T sc = exact_sliding && r.sliding ? T(Fmax / sqrt(Fh2)) : T(Fmax / lin);
      Fx = Fx * sc;
      Fy = Fy * sc;
    }
    F += scaled<T>(t, Fx) + scaled<T>(l, Fy);
    r.Fx = val(Fx);
    r.Fy = val(Fy);
    r.kappa = -val(vsx) / val(V);
    r.alpha = std::atan(-val(vsy) / val(V));
  }
  r.F = F;
  r.tau = cross(rho, F);
  return r;
}

const Road& road_of(const Model& model, const Tire& ty) { return model.roads[static_cast<std::size_t>(ty.road)]; }

Contact<double> contact_now(const Model& model, const Tire& ty, const Data& data) {
  const MarkerData& md = data.markers[static_cast<std::size_t>(ty.marker)];
  return contact<double>(ty, road_of(model, ty), md.p, md.e, md.pd, md.ed);
}

}  // namespace

void tire_forces(const Model& model, const Tire& ty, Data& data) {
  const Marker& mk = model.markers[static_cast<std::size_t>(ty.marker)];
  const MarkerData& md = data.markers[static_cast<std::size_t>(ty.marker)];
  const Contact<double> r = contact_now(model, ty, data);
  if (r.Fn == 0) return;
  const int o = offset(model, mk.body), nb = ncoord(model, mk.body);
  auto Q = data.Q.segment(o, nb);
  Q.noalias() += md.Jp.transpose() * r.F;
  for (int k = 0; k < 3; ++k) Q.noalias() += md.Je[k].transpose() * (0.5 * r.tau.cross(md.e[k]));
}

void tire_tangents(const Model& model, const Tire& ty, Data& data) {
  const Marker& mk = model.markers[static_cast<std::size_t>(ty.marker)];
  const MarkerData& md = data.markers[static_cast<std::size_t>(ty.marker)];
  // Inputs: x = [p, e0, e1, e2] (derivatives 0..11), x_dot = [p_dot, e0_dot, ...] (12..23).
  V3<AD> c, cd;
  std::array<V3<AD>, 3> e, ed;
  for (int i = 0; i < 3; ++i) {
    c(i) = AD(md.p(i), 24, i);
    cd(i) = AD(md.pd(i), 24, 12 + i);
    for (int k = 0; k < 3; ++k) {
      e[k](i) = AD(md.e[k](i), 24, 3 + 3 * k + i);
      ed[k](i) = AD(md.ed[k](i), 24, 15 + 3 * k + i);
    }
  }
  const auto index = static_cast<std::size_t>(&ty - model.tires.data());
  const bool exact_sliding = data.first_tangent_of_step && data.tire_sliding[index];
  const Contact<AD> r = contact<AD>(ty, road_of(model, ty), c, e, cd, ed, exact_sliding);
  if (r.Fn == 0) return;
  // g = [F, 1/2 tau x e_k] and its derivatives G = [dg/dx, dg/dx_dot].
  Eigen::Matrix<double, 12, 24> G;
  Eigen::Matrix<double, 12, 1> g;
  for (int i = 0; i < 3; ++i) {
    g(i) = r.F(i).value();
    G.row(i) = r.F(i).derivatives().transpose();
  }
  for (int k = 0; k < 3; ++k) {
    const V3<AD> gk = scaled<AD>(cross(r.tau, e[k]), AD(0.5));
    for (int i = 0; i < 3; ++i) {
      g(3 + 3 * k + i) = gk(i).value();
      G.row(3 + 3 * k + i) = gk(i).derivatives().transpose();
    }
  }
  const int o = offset(model, mk.body), nb = ncoord(model, mk.body);
  auto J = data.tJ.leftCols(nb);
  auto W = data.tW.leftCols(nb);
  J.middleRows<3>(0) = md.Jp;
  for (int k = 0; k < 3; ++k) J.middleRows<3>(3 + 3 * k) = md.Je[k];
  auto K = data.K.block(o, o, nb, nb);
  auto C = data.C.block(o, o, nb, nb);
  W.noalias() = G.leftCols<12>() * J;
  if (on_node(model, mk)) {
    auto V = data.tV.leftCols(nb);
    const auto yd = data.state.qd.segment(o + 12, nb - 12);
    const Matrix3d& Ad = data.bodies[static_cast<std::size_t>(mk.body)].Ad;
    for (int q = 0; q < 4; ++q) jzd_derivative(slice(mk, q - 1), Ad, yd, V.middleRows<3>(3 * q));
    W.noalias() += G.rightCols<12>() * V;
    for (int q = 0; q < 4; ++q) add_jt_f_derivative(slice(mk, q - 1), Vector3d(g.segment<3>(3 * q)), -1.0, K);
  }
  K.noalias() -= J.transpose() * W;
  W.noalias() = G.rightCols<12>() * J;
  C.noalias() -= J.transpose() * W;
}

void tire_output(const Model& model, const Tire& ty, const Data& data, double* out) {
  const Contact<double> r = contact_now(model, ty, data);
  out[0] = r.Fx;
  out[1] = r.Fy;
  out[2] = r.Fn;
  out[3] = r.kappa;
  out[4] = r.alpha;
  out[5] = r.delta;
}

void commit_tire_sliding(const Model& model, Data& data) {
  for (std::size_t i = 0; i < model.tires.size(); ++i) data.tire_sliding[i] = contact_now(model, model.tires[i], data).sliding;
}

double tire_energy(const Model& model, const Tire& ty, const Data& data) {
  const double delta = contact_now(model, ty, data).delta;
  return delta > 0 ? 0.5 * ty.vertical_stiffness * delta * delta : 0.0;
}

}  // namespace ffr::runtime::detail
