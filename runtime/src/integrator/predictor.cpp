// The frames' part of the step predictor (FORMULATION.md section 9): each body's frame turned
// by the rotation its angular velocity and acceleration predict, instead of the polynomial
// predictor's frame vectors.
//
// Why: the polynomial predictor q + h qd + h^2 (3/4 qdd - 1/4 qdd_prev) puts a frame turning by
// omega h per step off by ~(omega h)^4 / 4 of its length, and off the unit sphere (a crank at
// 150 rad/s, h = 1 ms: 2.6e-4 of the model length in its frame and motion rows). A rotation
// keeps the frame orthonormal and is exact for a body turning at a constant rate about a fixed
// axis. On the benchmark's slider-crank it takes the second factorisation, which Newton needed
// in 76 % of the steps, down to 44 % (tools/bench/runtime_step/RESULTS.md).
#include "ffr/runtime/integrator.hpp"
#include "ffr/runtime/kinematics.hpp"

#include <Eigen/Geometry>

namespace ffr::runtime {
namespace {

// A body's frame [u v w] (or its rate, its acceleration): the nine coordinates after r0,
// stored column after column.
Eigen::Map<const Matrix3d> frame(const VectorXd& z, int offset) { return Eigen::Map<const Matrix3d>(z.data() + offset + 3); }

}  // namespace

void predict_frames(const Model& model, Data& data) {
  const double h = data.state.k.h;
  const double r = h / data.state.k.h_prev;  // this step over the last (adaptive steps)
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    if (!data.integrated[i]) continue;  // a driven body is placed by drive_bodies
    const int o = model.bodies[i].offset;
    const Matrix3d A = frame(data.q0, o);
    // Global angular velocity and acceleration from the body-frame ones (A^T A_dot = omega~ and,
    // A_dot^T A_dot being symmetric, alpha~ = skew(A^T A_ddot)).
    const Vector3d omega = A * body_omega(A, frame(data.qd0, o));
    const Vector3d alpha = A * body_omega(A, frame(data.qdd0, o));
    if (data.state.have_previous) {  // a step before this one: step_alpha is its start's
      // Rotation vector of the step to third order, the rate of alpha from the last step (the
      // commutator terms vanish for a fixed axis and are of the order of the error otherwise).
      const Vector3d turn = h * omega + 0.5 * h * h * alpha + (r * h * h / 6) * (alpha - data.state.step_alpha[i]);
      const double angle = turn.norm();
      if (angle > 0) {
        const Matrix3d A_next = Eigen::AngleAxisd(angle, turn / angle).toRotationMatrix() * A;
        Eigen::Map<Matrix3d>(data.state.q.data() + o + 3) = A_next;
      }
    }
    data.state.step_alpha[i] = alpha;
  }
}

}  // namespace ffr::runtime
