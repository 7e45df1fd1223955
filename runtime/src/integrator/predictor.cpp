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

#include <Eigen/Geometry>

namespace ffr::runtime {
namespace {

Matrix3d frame(const VectorXd& z, int offset) {
  Matrix3d A;
  for (int k = 0; k < 3; ++k) A.col(k) = z.segment<3>(offset + 3 + 3 * k);
  return A;
}

// The vector of the skew-symmetric part of S.
Vector3d axial(const Matrix3d& S) {
  return 0.5 * Vector3d(S(2, 1) - S(1, 2), S(0, 2) - S(2, 0), S(1, 0) - S(0, 1));
}

}  // namespace

void predict_frames(const Model& model, Data& data) {
  const double h = model.settings.step;
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const int o = model.bodies[i].offset;
    BodyData& bd = data.bodies[i];
    const Matrix3d A = frame(data.q0, o), Ad = frame(data.qd0, o), Add = frame(data.qdd0, o);
    // Global angular velocity and acceleration: A_dot A^T = omega~ and, since A_dot A_dot^T is
    // symmetric, alpha~ = skew(A_ddot A^T).
    const Vector3d omega = axial(Ad * A.transpose());
    const Vector3d alpha = axial(Add * A.transpose());
    if (data.have_previous) {  // a step before this one: step_alpha is its start's
      // Rotation vector of the step to third order, the rate of alpha from the last step (the
      // commutator terms vanish for a fixed axis and are of the order of the error otherwise).
      const Vector3d turn = h * omega + 0.5 * h * h * alpha + (h * h / 6) * (alpha - bd.step_alpha);
      const double angle = turn.norm();
      if (angle > 0) {
        const Matrix3d A_next = Eigen::AngleAxisd(angle, turn / angle).toRotationMatrix() * A;
        for (int k = 0; k < 3; ++k) data.q.segment<3>(o + 3 + 3 * k) = A_next.col(k);
      }
    }
    bd.step_alpha = alpha;
  }
}

}  // namespace ffr::runtime
