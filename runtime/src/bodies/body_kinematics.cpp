// Frame, deformed inertia integrals and rates of each body (FORMULATION.md sections 2-4).
#include "ffr/runtime/kinematics.hpp"

#include "../integrator/dense_products.hpp"
#include "../model/known_frame.hpp"

#include <algorithm>

namespace ffr::runtime {

Vector3d body_omega(const Matrix3d& A, const Matrix3d& Ad) {
  const auto u = A.col(0), v = A.col(1), w = A.col(2);
  const auto ud = Ad.col(0), vd = Ad.col(1), wd = Ad.col(2);
  return 0.5 * Vector3d(w.dot(vd) - v.dot(wd), u.dot(wd) - w.dot(ud), v.dot(ud) - u.dot(vd));
}

Eigen::Matrix<double, 3, 9> gbar(const Matrix3d& A) {
  Eigen::Matrix<double, 3, 9> G = Eigen::Matrix<double, 3, 9>::Zero();
  const Vector3d u = A.col(0), v = A.col(1), w = A.col(2);
  G.block<1, 3>(0, 3) = 0.5 * w.transpose();
  G.block<1, 3>(0, 6) = -0.5 * v.transpose();
  G.block<1, 3>(1, 0) = -0.5 * w.transpose();
  G.block<1, 3>(1, 6) = 0.5 * u.transpose();
  G.block<1, 3>(2, 0) = 0.5 * v.transpose();
  G.block<1, 3>(2, 3) = -0.5 * u.transpose();
  return G;
}

namespace {

// y9 = PPdm_stack x ([9 nq], the nine PPdm[a][c] x). An ancf beam's PPdm[a][c] joins only
// coordinate a of a node's position or slope with coordinate c of the same or a neighbouring
// node's (make_beam_body, beam_ancf.cpp): six entries a row on a third of the rows, which its
// product visits alone. Why: the dense product of a 16-element beam's 918 x 102 matrix was an
// eighth of its step.
void stacked_times(const Body& b, const double* x, double* y9) {
  const Eigen::Index n9 = 9 * b.nq;
  if (!b.beam) {
    detail::times(b.PPdm_stack.data(), n9, n9, b.nq, x, y9, false);
    return;
  }
  const int nq = b.nq, nodes = nq / 6;
  std::fill(y9, y9 + n9, 0.0);
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c) {
      const double* P = b.PPdm_stack.data() + (3 * a + c) * nq;  // PPdm[a][c](i, j) = P[i + j n9]
      double* y = y9 + (3 * a + c) * nq;
      for (int n = 0; n < nodes; ++n)
        for (int v = 0; v < 2; ++v) {
          const int i = 6 * n + 3 * v + a;
          double sum = 0;
          for (int m = std::max(0, n - 1); m <= std::min(nodes - 1, n + 1); ++m)
            for (int u = 0; u < 2; ++u) {
              const int j = 6 * m + 3 * u + c;
              sum += P[i + j * n9] * x[j];
            }
          y[i] = sum;
        }
    }
}

// The parts of a body's kinematics that depend on the velocities: the frame's rate, the angular
// velocity and the products PPdm y_dot (A must be current).
void body_rates(const Body& b, const Data& data, BodyData& bd) {
  const int o = b.offset;
  for (int a = 0; a < 3; ++a) bd.Ad.col(a) = data.state.qd.segment<3>(o + 3 + 3 * a);
  bd.omega = body_omega(bd.A, bd.Ad);
  // PPdm y_dot feeds only the inertia forces, which a beam's held frame does not have, nor a
  // body whose inertia comes from its FE mass matrix (body_fe_inertia.cpp).
  if (b.nq == 0 || b.beam || b.full_mass) return;
  // One product with the stacked matrices instead of nine small ones, whose calls cost more
  // than their multiply-adds (through the vectorised kernel of the step's products).
  stacked_times(b, data.state.qd.data() + o + 12, bd.Pyd.data());
}

}  // namespace

void update_body_rates(const Model& model, Data& data) {
  for (std::size_t i = 0; i < model.bodies.size(); ++i) body_rates(model.bodies[i], data, data.bodies[i]);
}

void update_bodies(const Model& model, Data& data, Scope scope) {
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    if (scope == Scope::Unknowns && !data.integrated[i]) continue;
    const Body& b = model.bodies[i];
    BodyData& bd = data.bodies[i];
    const int o = b.offset;
    for (int a = 0; a < 3; ++a) {
      bd.A.col(a) = data.state.q.segment<3>(o + 3 + 3 * a);
      bd.Add.col(a) = data.state.qdd.segment<3>(o + 3 + 3 * a);
    }
    body_rates(b, data, bd);
    bd.alpha = body_omega(bd.A, bd.Add);
    bd.acc.noalias() = bd.A.transpose() * (data.state.qdd.segment<3>(o) - model.gravity);
    if (b.nq == 0) {
      bd.md = b.rdm;
      bd.Jc = b.J0;
      continue;
    }
    // A body whose inertia comes from its FE mass matrix gets md, S and Jc from those products
    // (fe_mass_matrix, which every evaluation calls before anything reads them).
    if (b.full_mass) continue;
    const auto y = data.state.q.segment(o + 12, b.nq);
    bd.md = b.rdm;
    bd.md.noalias() += b.Pdm * y;
    // An ancf beam's known frame (known_frame.hpp) stays at rest at the global frame: its S_a and
    // Jc weigh only the frame's accelerations and rates, which are zero, and its frame's rows,
    // which are not unknowns. So they are left to the outputs that read them (energy.cpp); they
    // were a sixth of a 16-element beam's step.
    if (detail::frame_known(model, b)) continue;
    deformed_inertia(b, bd, y);
  }
}

void deformed_inertia(const Body& b, BodyData& bd, const Eigen::Ref<const VectorXd>& y) {
  // S_a = rPdm[a] + P_a(y), row c of P_a(y) being (PPdm[a][c]^T y)^T = (PPdm[c][a] y)^T =
  // column 3c+a of Py, all nine from one product (as in body_rates).
  stacked_times(b, y.data(), bd.Py.data());
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c) bd.S[a].row(c) = b.rPdm[a].row(c) + bd.Py.col(3 * c + a).transpose();
  // Jc(a,c) = J0 + R(a,c) + R(c,a) + y^T PPdm[a][c] y with R(a,c) = rPdm[a].row(c) y.
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c)
      bd.Jc(a, c) = b.J0(a, c) + b.rPdm[a].row(c).dot(y) + b.rPdm[c].row(a).dot(y) + bd.Py.col(3 * c + a).dot(y);
}

}  // namespace ffr::runtime
