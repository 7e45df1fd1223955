// Load-time check that every body can turn: a flexible body whose mass lies on a line (points
// on an axis without rotary inertia) has no inertia for a rotation about that line. Unless a
// joint holds that rotation, the mass matrix is singular there and the first step would end
// in a non-finite state that names nothing; refused here naming the body instead. A bushing
// does not hold it: its stiffness keeps the step's matrix regular, but the start's consistent
// accelerations are solved with the mass and the joints alone (initial_conditions.cpp), and
// they came out non-finite (a lumped chain on a bushing with torsional stiffness, 1 ms step).
#include "parse.hpp"
#include "../number_text.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>

namespace ffr::runtime::detail {
namespace {

// Whether the joint holds the rotation of its body about `axis` (body components) relative to
// the other body. A universal joint is taken to hold it: which rotation it frees depends on the
// other body's axis, and refusing a model that can run would be worse than the late failure.
bool holds_rotation(const Joint& j, const Marker& own, const Vector3d& axis) {
  switch (j.type) {
    case JointType::Spherical: return false;
    case JointType::Revolute:
    case JointType::Cylindrical: return own.E.col(0).normalized().cross(axis).norm() > 1e-6;
    default: return true;
  }
}

}  // namespace

void check_bodies_can_turn(const Field& root, ParseContext& ctx) {
  const Model& m = ctx.model;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const Body& body = m.bodies[b];
    if (!body.flexible) continue;  // a rigid body's inertia was checked with its input
    if (body.held_frame()) continue;       // a beam's frame is held; its nodes carry no rotation to be singular
    // Inertia tensor about the centre of mass from the pseudo-inertia J0 (= int c c^T dm + ...).
    const Vector3d d = body.rdm / body.mass;
    const Matrix3d IO = body.J0.trace() * Matrix3d::Identity() - body.J0;
    const Matrix3d Ic = IO - body.mass * (d.squaredNorm() * Matrix3d::Identity() - d * d.transpose());
    const Eigen::SelfAdjointEigenSolver<Matrix3d> es(0.5 * (Ic + Ic.transpose()));
    const Vector3d p = es.eigenvalues();
    if (p(0) > 1e-12 * p(2)) continue;
    // The axis with its largest component positive and round-off below 1e-12 shown as 0.
    Vector3d axis = es.eigenvectors().col(0);
    Eigen::Index big = 0;
    axis.cwiseAbs().maxCoeff(&big);
    if (axis(big) < 0) axis = -axis;
    for (Eigen::Index k = 0; k < 3; ++k)
      if (std::abs(axis(k)) < 1e-12) axis(k) = 0;
    std::string joints;
    bool held = false;
    for (const Joint& j : m.joints)
      for (int mk : {j.m1, j.m2})
        if (m.markers[static_cast<std::size_t>(mk)].body == static_cast<int>(b)) {
          held = held || holds_rotation(j, m.markers[static_cast<std::size_t>(mk)], axis);
          joints += (joints.empty() ? "" : ", ") + std::string(to_string(j.type)) + " '" + j.name + "'";
        }
    bool bushed = false;
    for (const Bushing& k : m.bushings)
      for (int mk : {k.m1, k.m2}) bushed = bushed || m.markers[static_cast<std::size_t>(mk)].body == static_cast<int>(b);
    if (held) continue;
    root.at("bodies").at(b).fail(
        "body '" + body.name + "' (" + body.source + "): its principal moments of inertia about the centre of mass are " +
        num(p(0)) + ", " + num(p(1)) + ", " + num(p(2)) + " kg m^2, so a rotation about the axis [" + num(axis(0)) + ", " +
        num(axis(1)) + ", " + num(axis(2)) + "] (body frame) has no inertia, and " +
        (joints.empty() ? std::string("no joint holds it") : "its joints (" + joints + ") leave it free") +
        ": the equations of motion are singular" +
        (bushed ? std::string(" (a bushing does not hold it: the start's accelerations need inertia or a joint there)") : "") +
        ". Give the part rotary inertia (e.g. a beam's section inertia) or a joint that holds that rotation");
  }
}

}  // namespace ffr::runtime::detail
