// Q, K and C of the whole system: bodies, then force elements. A driven body's own terms are
// not computed while it is eliminated (nothing reads them: its motion is given); the force
// elements still act on the integrated bodies they join it to.
#include "ffr/runtime/dynamics.hpp"
#include "forces.hpp"
#include "../integrator/tangent_blocks.hpp"

namespace ffr::runtime {

void generalized_forces(const Model& model, Data& data, double t) {
  data.Q.setZero();
  // The interface loads before the bodies (their stiffening reads them): the joints', then each
  // force element's, taken from what it adds to Q, so the elements come first.
  interface_loads(model, data);
  // An element between two points of one body gives each end's load itself (add_end_loads).
  Eigen::Matrix<double, 12, 2> ends;
  for (const SpringDamper& s : model.springs) {
    const InterfaceLoadCapture at(model, data, s.m1, s.m2);
    const bool same = detail::same_body_interfaces(model, data, s.m1, s.m2);
    detail::spring_forces(model, s, data, same ? &ends : nullptr);
    at.add_to_interfaces(model, data);
    if (same) detail::add_end_loads(model, data, s.m1, s.m2, ends);
  }
  for (const Bushing& b : model.bushings) {
    const InterfaceLoadCapture at(model, data, b.m1, b.m2);
    const bool same = detail::same_body_interfaces(model, data, b.m1, b.m2);
    detail::bushing_forces(model, b, data, true, false, same ? &ends : nullptr);
    at.add_to_interfaces(model, data);
    if (same) detail::add_end_loads(model, data, b.m1, b.m2, ends);
  }
  for (std::size_t i = 0; i < model.friction_dampers.size(); ++i) {
    const FrictionDamper& f = model.friction_dampers[i];
    const InterfaceLoadCapture at(model, data, f.m1, f.m2);
    const bool same = detail::same_body_interfaces(model, data, f.m1, f.m2);
    detail::friction_forces(model, f, data.state.friction[i], data, same ? &ends : nullptr);
    at.add_to_interfaces(model, data);
    if (same) detail::add_end_loads(model, data, f.m1, f.m2, ends);
  }
  for (const Tire& ty : model.tires) {
    const InterfaceLoadCapture at(model, data, ty.marker, -1);
    detail::tire_forces(model, ty, data);
    at.add_to_interfaces(model, data);
  }
  detail::point_loads(model, data, t, true, false);
  detail::external_loads(model, data, true, false);
  for (const GeBeam& gb : model.ge_beams) ge_beam_forces(model, gb, data, true, false);
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    if (!data.integrated[i]) continue;
    const Body& b = model.bodies[i];
    const int o = b.offset, nb = b.ncoord();
    auto Qb = data.Q.segment(o, nb);
    if (b.full_mass)
      fe_inertia_forces(b, data.bodies[i], data.state.qd.segment(o, nb), Qb);
    else
      body_inertia_forces(b, data.bodies[i], data.state.qd.segment(o, nb), Qb);
    body_applied_forces(b, data.bodies[i], model.gravity, data.state.q.segment(o, nb), data.state.qd.segment(o, nb), Qb);
  }
}

namespace {

// K += bushing_K, C += bushing_C over the bushings' blocks (Data::bushing_blocks).
void add_kept_bushing_tangent(Data& data) {
  for (const auto& [r0, nr, c0, nc] : data.bushing_blocks) {
    data.K.block(r0, c0, nr, nc) += data.bushing_K.block(r0, c0, nr, nc);
    data.C.block(r0, c0, nr, nc) += data.bushing_C.block(r0, c0, nr, nc);
  }
}

// The bushings' terms of K and C (cleared over their blocks): built and kept, or the kept ones
// added while they may serve another step (Data::bushing_K, NewtonPolicy::bushing_tangent_steps).
void bushing_tangents(const Model& model, Data& data) {
  if (model.bushings.empty()) return;
  const int steps = model.settings.policy.newton.bushing_tangent_steps;
  if (steps <= 1) {  // nothing to keep: built where it is used
    for (const Bushing& b : model.bushings) detail::bushing_forces(model, b, data, false, true);
    return;
  }
  if (data.first_tangent_of_step && data.bushing_tangent_age >= 0 && data.bushing_tangent_age + 1 < steps) {
    ++data.bushing_tangent_age;
    add_kept_bushing_tangent(data);
    return;
  }
  // Built alone in the kept matrices, then added: K and C hold other terms already.
  for (const auto& [r0, nr, c0, nc] : data.bushing_blocks) {
    data.bushing_K.block(r0, c0, nr, nc).setZero();
    data.bushing_C.block(r0, c0, nr, nc).setZero();
  }
  data.K.swap(data.bushing_K);
  data.C.swap(data.bushing_C);
  for (const Bushing& b : model.bushings) detail::bushing_forces(model, b, data, false, true);
  data.K.swap(data.bushing_K);
  data.C.swap(data.bushing_C);
  data.bushing_tangent_age = 0;
  add_kept_bushing_tangent(data);
}

}  // namespace

void force_tangents(const Model& model, Data& data, double t) {
  // Zero outside the tangent blocks already (tangent_blocks.hpp): only these are cleared where
  // that pays.
  if (data.tangent_blocks_pay) {
    detail::for_each_tangent_block(model, data, false, [&](int r0, int nr, int c0, int nc) {
      data.K.block(r0, c0, nr, nc).setZero();
      data.C.block(r0, c0, nr, nc).setZero();
    });
  } else {
    data.K.setZero();
    data.C.setZero();
  }
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    if (!data.integrated[i]) continue;
    const Body& b = model.bodies[i];
    const int o = b.offset, nb = b.ncoord();
    auto Kb = data.K.block(o, o, nb, nb);
    auto Cb = data.C.block(o, o, nb, nb);
    if (b.full_mass)
      fe_inertia_tangents(b, data.bodies[i], data.state.qd.segment(o, nb), Kb, Cb);
    else
      body_inertia_tangents(b, data.bodies[i], data.state.qd.segment(o, nb), Kb, Cb);
    body_applied_tangents(b, data.bodies[i], model.gravity, data.state.q.segment(o, nb), data.state.qd.segment(o, nb), Kb, Cb);
  }
  for (const SpringDamper& s : model.springs) detail::spring_tangents(model, s, data);
  bushing_tangents(model, data);
  for (std::size_t i = 0; i < model.friction_dampers.size(); ++i)
    detail::friction_tangents(model, model.friction_dampers[i], data.state.friction[i], data);
  for (const Tire& ty : model.tires) detail::tire_tangents(model, ty, data);
  detail::point_loads(model, data, t, false, true);
  detail::external_loads(model, data, false, true);
  for (const GeBeam& gb : model.ge_beams) ge_beam_forces(model, gb, data, false, true);
}

}  // namespace ffr::runtime
