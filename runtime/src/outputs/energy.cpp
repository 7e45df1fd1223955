#include "ffr/runtime/energy.hpp"

#include "ffr/runtime/dynamics.hpp"
#include "ffr/runtime/kinematics.hpp"
#include "../forces/forces.hpp"
#include "../model/known_frame.hpp"

namespace ffr::runtime {

Energy energy(const Model& model, Data& data) {
  update_bodies(model, data);
  mass_matrices(model, data);
  update_markers(model, data);
  Energy e;
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const Body& b = model.bodies[i];
    const BodyData& bd = data.bodies[i];
    const auto zd = data.state.qd.segment(b.offset, b.ncoord());
    e.kinetic += 0.5 * zd.dot(bd.M * zd);
    const Vector3d r0 = data.state.q.segment<3>(b.offset);
    e.potential -= model.gravity.dot(b.mass * r0 + bd.A * bd.md);
    if (b.nq) {
      const auto y = data.state.q.segment(b.offset + 12, b.nq);
      e.potential += 0.5 * y.dot(b.Ke * y);
      // The strain energy of Ke/M1 (FORMULATION.md 7) and the prestress's y^T f0 + 1/2 y^T K1 y.
      BodyData& bdw = data.bodies[i];  // work vectors: energy() allocates nothing
      // 1/2 s^T Ke s - 1/2 y^T Ke y = y.g + 1/2 g.(s - y) (modal_stress_terms: g, s).
      if (b.modal_stress) {
        modal_stress_terms(b, bdw, y);
        const auto g = bdw.Py.col(0), s = bdw.Py.col(1);
        e.potential += y.dot(g) + 0.5 * (g.dot(s) - g.dot(y));
      }
      if (b.prestress) {
        bdw.wq.noalias() = b.prestress->K1 * y;
        e.potential += y.dot(b.prestress->f0) + 0.5 * y.dot(bdw.wq);
      }
      if (b.beam) e.potential += ancf_beam_energy(*b.beam, y);
      if (b.plate) e.potential += ancf_plate_energy(*b.plate, y);
    }
  }
  for (const GeBeam& gb : model.ge_beams) e.potential += ge_beam_energy(model, gb, data);
  for (const SpringDamper& s : model.springs) e.potential += detail::spring_energy(model, s, data);
  for (const Bushing& bu : model.bushings) e.potential += detail::bushing_energy(model, bu, data);
  for (const Tire& ty : model.tires) e.potential += detail::tire_energy(model, ty, data);
  for (std::size_t i = 0; i < model.friction_dampers.size(); ++i) {
    e.potential += detail::friction_energy(model, model.friction_dampers[i], data.state.friction[i], data);
    e.dissipated += data.state.friction[i].dissipated;
  }
  return e;
}

namespace {

// int (r_dot - r0_dot) dm = A_dot md + A Pdm y_dot: a body's momentum relative to its origin's motion.
Vector3d relative_momentum(const Body& b, const BodyData& bd, const VectorXd& qd) {
  Vector3d p = bd.Ad * bd.md;
  if (b.nq) p += bd.A * (b.Pdm * qd.segment(b.offset + 12, b.nq));
  return p;
}

}  // namespace

Vector3d linear_momentum(const Model& model, Data& data) {
  update_bodies(model, data);
  Vector3d p = Vector3d::Zero();
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const Body& b = model.bodies[i];
    p += b.mass * data.state.qd.segment<3>(b.offset) + relative_momentum(b, data.bodies[i], data.state.qd);
  }
  return p;
}

Vector3d angular_momentum(const Model& model, Data& data) {
  update_bodies(model, data);
  Vector3d H = Vector3d::Zero();
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const Body& b = model.bodies[i];
    const BodyData& bd = data.bodies[i];
    const Vector3d r0 = data.state.q.segment<3>(b.offset), r0d = data.state.qd.segment<3>(b.offset);
    const Vector3d pb = relative_momentum(b, bd, data.state.qd);
    H += b.mass * r0.cross(r0d) + r0.cross(pb) + (bd.A * bd.md).cross(r0d);
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) H += bd.Jc(a, c) * Vector3d(bd.A.col(a)).cross(Vector3d(bd.Ad.col(c)));
    if (b.nq) {
      const auto yd = data.state.qd.segment(b.offset + 12, b.nq);
      // (update_bodies leaves S_a of an ancf beam's known frame to this.)
      if (detail::frame_known(model, b))
        deformed_inertia(b, data.bodies[i], data.state.q.segment(b.offset + 12, b.nq));
      for (int a = 0; a < 3; ++a) H += Vector3d(bd.A.col(a)).cross(bd.A * (bd.S[a] * yd));
      if (b.has_rotary_coupling) H += bd.A * (b.PsiI.transpose() * yd);
    }
  }
  return H;
}

}  // namespace ffr::runtime
