// Q, K and C of the whole system: bodies, then force elements. A driven body's own terms are
// not computed while it is eliminated (nothing reads them: its motion is given); the force
// elements still act on the integrated bodies they join it to.
#include "ffr/runtime/dynamics.hpp"
#include "forces.hpp"

namespace ffr::runtime {

void generalized_forces(const Model& model, Data& data, double t) {
  data.Q.setZero();
  interface_loads(model, data);  // before the bodies: their stiffening reads them
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    if (!data.integrated[i]) continue;
    const Body& b = model.bodies[i];
    const int o = b.offset, nb = b.ncoord();
    auto Qb = data.Q.segment(o, nb);
    if (b.full_mass)
      fe_inertia_forces(b, data.bodies[i], data.qd.segment(o, nb), Qb);
    else
      body_inertia_forces(b, data.bodies[i], data.qd.segment(o, nb), Qb);
    body_applied_forces(b, data.bodies[i], model.gravity, data.q.segment(o, nb), data.qd.segment(o, nb), Qb);
  }
  for (const SpringDamper& s : model.springs) detail::spring_forces(model, s, data);
  for (const Bushing& b : model.bushings) detail::bushing_forces(model, b, data, true, false);
  detail::point_loads(model, data, t, true, false);
  detail::external_loads(model, data, true, false);
}

void force_tangents(const Model& model, Data& data, double t) {
  data.K.setZero();
  data.C.setZero();
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    if (!data.integrated[i]) continue;
    const Body& b = model.bodies[i];
    const int o = b.offset, nb = b.ncoord();
    auto Kb = data.K.block(o, o, nb, nb);
    auto Cb = data.C.block(o, o, nb, nb);
    if (b.full_mass)
      fe_inertia_tangents(b, data.bodies[i], data.qd.segment(o, nb), Cb);
    else
      body_inertia_tangents(b, data.bodies[i], data.qd.segment(o, nb), Kb, Cb);
    body_applied_tangents(b, data.bodies[i], model.gravity, Kb, Cb);
  }
  for (const SpringDamper& s : model.springs) detail::spring_tangents(model, s, data);
  for (const Bushing& b : model.bushings) detail::bushing_forces(model, b, data, false, true);
  detail::point_loads(model, data, t, false, true);
  detail::external_loads(model, data, false, true);
}

}  // namespace ffr::runtime
