#include "beam_shape.hpp"

namespace ffr::preproc::beam {

namespace {

// Values (d = 0) or d/dxi (d = 1) of (N1..N4) and (G1..G4) for one bending plane.
void plane_functions(double L, double f, double x, int d, double N[4], double G[4]) {
  const double c = 1 / (1 + f);
  if (d == 0) {
    N[0] = c * (2 * x * x * x - 3 * x * x - f * x + 1 + f);
    N[1] = c * L * (x * x * x - (2 + f / 2) * x * x + (1 + f / 2) * x);
    N[2] = c * (-2 * x * x * x + 3 * x * x + f * x);
    N[3] = c * L * (x * x * x - (1 - f / 2) * x * x - f / 2 * x);
    G[0] = c * 6 * (x * x - x) / L;
    G[1] = c * (3 * x * x - (4 + f) * x + 1 + f);
    G[2] = -G[0];
    G[3] = c * (3 * x * x - (2 - f) * x);
  } else {
    N[0] = c * (6 * x * x - 6 * x - f);
    N[1] = c * L * (3 * x * x - 2 * (2 + f / 2) * x + (1 + f / 2));
    N[2] = c * (-6 * x * x + 6 * x + f);
    N[3] = c * L * (3 * x * x - 2 * (1 - f / 2) * x - f / 2);
    G[0] = c * 6 * (2 * x - 1) / L;
    G[1] = c * (6 * x - (4 + f));
    G[2] = -G[0];
    G[3] = c * (6 * x - (2 - f));
  }
}

Eigen::Matrix<double, 6, 12> build(const ShapeParams& p, double x, int d) {
  Eigen::Matrix<double, 6, 12> H = Eigen::Matrix<double, 6, 12>::Zero();
  const double lin0 = d == 0 ? 1 - x : -1, lin1 = d == 0 ? x : 1;
  H(0, 0) = lin0;
  H(0, 6) = lin1;
  H(3, 3) = lin0;
  H(3, 9) = lin1;
  double N[4], G[4];
  plane_functions(p.L, p.phi_y, x, d, N, G);  // (v, rz) on columns v1 = 1, rz1 = 5, v2 = 7, rz2 = 11
  H(1, 1) = N[0], H(1, 5) = N[1], H(1, 7) = N[2], H(1, 11) = N[3];
  H(5, 1) = G[0], H(5, 5) = G[1], H(5, 7) = G[2], H(5, 11) = G[3];
  plane_functions(p.L, p.phi_z, x, d, N, G);  // (w, -ry) on columns w1 = 2, ry1 = 4, w2 = 8, ry2 = 10
  H(2, 2) = N[0], H(2, 4) = -N[1], H(2, 8) = N[2], H(2, 10) = -N[3];
  H(4, 2) = -G[0], H(4, 4) = G[1], H(4, 8) = -G[2], H(4, 10) = G[3];
  return H;
}

}  // namespace

Eigen::Matrix<double, 6, 12> interpolation(const ShapeParams& p, double xi) { return build(p, xi, 0); }

Eigen::Matrix<double, 6, 12> interpolation_ds(const ShapeParams& p, double xi) { return build(p, xi, 1) / p.L; }

}  // namespace ffr::preproc::beam
