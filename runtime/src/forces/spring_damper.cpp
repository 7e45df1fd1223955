// Spring-damper between two marker points: tension F = f(l - l0) + g(l_dot) + preload along the
// line of the points (line_force.hpp), f and g linear (k, c) or tables (their slopes the
// tangent's dF/dl and dF/dl_dot).
#include "forces.hpp"
#include "line_force.hpp"

namespace ffr::runtime::detail {
namespace {

struct Tension {
  double F = 0, kl = 0, cl = 0;
};

Tension tension(const SpringDamper& s, const LineState& st) {
  Tension r;
  const double x = st.l - s.length0;
  double d2;
  if (s.force_table.empty()) {
    r.F = s.k * x;
    r.kl = s.k;
  } else {
    double f;
    s.force_table.eval(x, 0, f, r.kl, d2);
    r.F = f;
  }
  if (s.damping_table.empty()) {
    r.F += s.c * st.ldot;
    r.cl = s.c;
  } else {
    double g;
    s.damping_table.eval(st.ldot, 0, g, r.cl, d2);
    r.F += g;
  }
  r.F += s.preload;
  return r;
}

}  // namespace

double spring_force(const Model& model, const SpringDamper& s, const Data& data) {
  const LineState st = line_state(model, s.m1, s.m2, data);
  return st.valid ? tension(s, st).F : 0.0;
}

void spring_forces(const Model& model, const SpringDamper& s, Data& data, Eigen::Matrix<double, 12, 2>* ends) {
  const LineState st = line_state(model, s.m1, s.m2, data);
  add_line_force(model, s.m1, s.m2, st, st.valid ? tension(s, st).F : 0.0, data, ends);
}

double spring_energy(const Model& model, const SpringDamper& s, const Data& data) {
  const LineState st = line_state(model, s.m1, s.m2, data);
  const double x = (st.valid ? st.l : 0.0) - s.length0;
  // The elastic part's work from the free length: 1/2 k x^2, or the integral of the table from
  // zero deflection; the preload's P x.
  const double elastic =
      s.force_table.empty() ? 0.5 * s.k * x * x : s.force_table.integral(x, 0) - s.force_table.integral(0.0, 0);
  return elastic + s.preload * x;
}

void spring_tangents(const Model& model, const SpringDamper& s, Data& data) {
  const LineState st = line_state(model, s.m1, s.m2, data);
  if (!st.valid) return;
  const Tension r = tension(s, st);
  add_line_tangents(model, s.m1, s.m2, st, r.F, r.kl, r.cl, data);
}

}  // namespace ffr::runtime::detail
