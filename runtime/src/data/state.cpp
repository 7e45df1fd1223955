// The State (state.hpp): its copies to and from Data and its flat form for the C API. The copies
// are assignments of equal-sized vectors, so they allocate nothing.
#include "ffr/runtime/state.hpp"

#include "ffr/runtime/data.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ffr::runtime {

State::State(const Model& model)
    : q(VectorXd::Zero(model.ncoord)),
      qd(VectorXd::Zero(model.ncoord)),
      qdd(VectorXd::Zero(model.ncoord)),
      lambda(VectorXd::Zero(model.nconstraints)),
      a(VectorXd::Zero(model.ncoord)),
      qdd_prev(VectorXd::Zero(model.ncoord)),
      step_alpha(model.bodies.size(), Vector3d::Zero()),
      angle_ref(model.joints.size(), 0.0),
      friction(model.friction_dampers.size()) {}

void save_state(const Data& d, State& s) { s = d.state; }

void restore_state(const State& s, Data& d) {
  d.state = s;
  // The factorised tangent (reuse_jacobian would keep it) and the bushings' kept part
  // (NewtonPolicy::bushing_tangent_steps) belong to another state: a rolled-back or restored
  // run starts from tangents built at its own.
  d.forget_tangents();
}

namespace {

// t, the six step coefficients, have_previous, predictor_far, newton_kappa, kappa_age,
// last_iterations: 12 scalars; then q, qd, qdd, a, qdd_prev (n each), lambda (m), step_alpha
// (3 per body), angle_ref (one per joint), friction (3 per friction damper).
constexpr int kScalars = 12;

}  // namespace

int packed_state_size(const Model& model) {
  return kScalars + 5 * model.ncoord + model.nconstraints + 3 * static_cast<int>(model.bodies.size()) +
         static_cast<int>(model.joints.size()) + 3 * static_cast<int>(model.friction_dampers.size());
}

void pack_state(const State& s, double* out) {
  double* p = out;
  for (double v : {s.t, s.k.h, s.k.h_prev, s.k.c1, s.k.c2, s.k.kv, s.k.kq, s.have_previous ? 1.0 : 0.0,
                   s.predictor_far ? 1.0 : 0.0, s.newton_kappa, static_cast<double>(s.kappa_age),
                   static_cast<double>(s.last_iterations)})
    *p++ = v;
  for (const VectorXd* v : {&s.q, &s.qd, &s.qdd, &s.a, &s.qdd_prev, &s.lambda}) p = std::copy(v->data(), v->data() + v->size(), p);
  for (const Vector3d& w : s.step_alpha) p = std::copy(w.data(), w.data() + 3, p);
  p = std::copy(s.angle_ref.begin(), s.angle_ref.end(), p);
  for (const FrictionState& f : s.friction)
    for (double v : {f.slip, f.dissipated, f.power}) *p++ = v;
}

void unpack_state(const Model& model, const double* in, int size, State& s) {
  const int expected = packed_state_size(model);
  if (size != expected)
    throw std::invalid_argument("the state has " + std::to_string(size) + " values, this model's has " + std::to_string(expected));
  // Every value but Newton's constant (infinite until first measured) must be finite.
  for (int i = 0; i < size; ++i)
    if (i != 9 && !std::isfinite(in[i])) throw std::invalid_argument("the state's value " + std::to_string(i) + " is not finite");
  const double* p = in;
  s.t = *p++;
  s.k.h = *p++;
  s.k.h_prev = *p++;
  s.k.c1 = *p++;
  s.k.c2 = *p++;
  s.k.kv = *p++;
  s.k.kq = *p++;
  s.have_previous = *p++ != 0;
  s.predictor_far = *p++ != 0;
  s.newton_kappa = *p++;
  s.kappa_age = static_cast<int>(*p++);
  s.last_iterations = static_cast<int>(*p++);
  for (VectorXd* v : {&s.q, &s.qd, &s.qdd, &s.a, &s.qdd_prev, &s.lambda}) {
    std::copy(p, p + v->size(), v->data());
    p += v->size();
  }
  for (Vector3d& w : s.step_alpha) {
    std::copy(p, p + 3, w.data());
    p += 3;
  }
  std::copy(p, p + s.angle_ref.size(), s.angle_ref.begin());
  p += s.angle_ref.size();
  for (FrictionState& f : s.friction) {
    f.slip = *p++;
    f.dissipated = *p++;
    f.power = *p++;
  }
}

}  // namespace ffr::runtime
