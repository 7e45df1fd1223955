// Friction damper: Coulomb friction of magnitude F along the line of two points, opposing the
// rate of change of their distance (FORMULATION.md section 8, friction dampers).
//
// Without a series spring the stick-slip switch is regularised over |l_dot| < v_tol:
//   T = F clamp(l_dot / v_tol, -1, 1)
// (a viscous damper of F / v_tol inside the band; exact Coulomb outside). With a series spring
// k_s (a rubber bearing) the friction element is a Jenkins element with slip s: the spring
// carries T = k_s (l - l0 - s), and s moves only while |T| = F. Its step is the return mapping
// from the slip s_n of the last accepted step: trial e = l - l0 - s_n; if k_s |e| <= F it
// sticks (T = k_s e, dT/dl = k_s), else it slips to |T| = F (s = l - l0 - sign(e) F / k_s,
// dT/dl = 0). That is exact stick and slip for a stretch that does not reverse within a step.
// The slip is committed after each accepted step (commit_friction), with the energy it
// dissipated, F |s_n+1 - s_n|; the regularised damper's dissipation is the trapezoidal rule on
// its power T l_dot.
#include "forces.hpp"
#include "ffr/runtime/kinematics.hpp"
#include "line_force.hpp"

#include <algorithm>
#include <cmath>

namespace ffr::runtime::detail {
namespace {

// kl, cl: the tangent's dT/dl, dT/dl_dot. Both laws are saturations (T = F sat(x / x_tol)), for
// which Newton with the exact slope cycles: from an iterate in the flat part (slope 0) it lands
// beyond the band on the other side, and back. The secant slope T / x (the exact one inside the
// band, F / |x| outside) makes the iteration converge monotonically to the same solution (a
// Kacanov iteration; the force itself is exact).
struct FrictionTension {
  double T = 0, kl = 0, cl = 0, slip = 0;
};

FrictionTension friction_tension(const FrictionDamper& f, const FrictionState& fs, const LineState& st) {
  FrictionTension r;
  if (f.series_stiffness > 0) {
    const double e = st.l - f.length0 - fs.slip;
    if (f.series_stiffness * std::abs(e) <= f.force) {
      r.T = f.series_stiffness * e;
      r.kl = f.series_stiffness;
      r.slip = fs.slip;
    } else {
      r.T = std::copysign(f.force, e);
      r.kl = f.force / std::abs(e);
      r.slip = st.l - f.length0 - std::copysign(f.force / f.series_stiffness, e);
    }
    return r;
  }
  const double u = st.ldot / f.velocity_tolerance;
  if (std::abs(u) < 1) {
    r.T = f.force * u;
    r.cl = f.force / f.velocity_tolerance;
  } else {
    r.T = std::copysign(f.force, u);
    r.cl = f.force / std::abs(st.ldot);
  }
  return r;
}

}  // namespace

double friction_force(const Model& model, const FrictionDamper& f, const FrictionState& fs, const Data& data) {
  const LineState st = line_state(model, f.m1, f.m2, data);
  return st.valid ? friction_tension(f, fs, st).T : 0.0;
}

void friction_forces(const Model& model, const FrictionDamper& f, const FrictionState& fs, Data& data,
                     Eigen::Matrix<double, 12, 2>* ends) {
  const LineState st = line_state(model, f.m1, f.m2, data);
  add_line_force(model, f.m1, f.m2, st, st.valid ? friction_tension(f, fs, st).T : 0.0, data, ends);
}

void friction_tangents(const Model& model, const FrictionDamper& f, const FrictionState& fs, Data& data) {
  const LineState st = line_state(model, f.m1, f.m2, data);
  if (!st.valid) return;
  const FrictionTension r = friction_tension(f, fs, st);
  add_line_tangents(model, f.m1, f.m2, st, r.T, r.kl, r.cl, data);
}

double friction_energy(const Model& model, const FrictionDamper& f, const FrictionState& fs, const Data& data) {
  if (!(f.series_stiffness > 0)) return 0.0;
  const LineState st = line_state(model, f.m1, f.m2, data);
  if (!st.valid) return 0.0;
  const double e = friction_tension(f, fs, st).T / f.series_stiffness;
  return 0.5 * f.series_stiffness * e * e;
}

void commit_friction(const Model& model, Data& data, double h) {
  // The tyres' sliding only chooses the next step's first tangent (tire.cpp), never a force: the
  // markers as the step left them (its rates before the projections) do.
  commit_tire_sliding(model, data);
  if (model.friction_dampers.empty()) return;
  // The projections changed the rates after the markers were last updated.
  update_bodies(model, data);
  update_markers(model, data);
  for (std::size_t i = 0; i < model.friction_dampers.size(); ++i) {
    const FrictionDamper& f = model.friction_dampers[i];
    FrictionState& fs = data.state.friction[i];
    const LineState st = line_state(model, f.m1, f.m2, data);
    if (!st.valid) continue;
    const FrictionTension r = friction_tension(f, fs, st);
    if (f.series_stiffness > 0) {
      fs.dissipated += f.force * std::abs(r.slip - fs.slip);
      fs.slip = r.slip;
    } else {
      const double power = r.T * st.ldot;
      if (h > 0) fs.dissipated += 0.5 * h * (fs.power + power);
      fs.power = power;
    }
  }
}

}  // namespace ffr::runtime::detail
