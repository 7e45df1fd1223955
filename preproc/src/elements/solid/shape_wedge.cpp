// Prisms (gmsh "Prism"): triangle (r, s) with unit legs times zeta in [-1, 1].
#include "shape_families.hpp"

namespace ffr::preproc::detail {

namespace {
constexpr double kDL[3][2] = {{-1, -1}, {1, 0}, {0, 1}};  // dL_t / d(r, s)
void tri(const Eigen::Vector3d& x, double L[3]) {
  L[0] = 1 - x[0] - x[1];
  L[1] = x[0];
  L[2] = x[1];
}
}  // namespace

void shape_wedge6(const Eigen::Vector3d& x, ShapeValues& N, ShapeGradients& dN) {
  double L[3];
  tri(x, L);
  for (int a = 0; a < 6; ++a) {
    const int t = a % 3;
    const double zi = a < 3 ? -1.0 : 1.0, fz = 0.5 * (1 + zi * x[2]);
    N[a] = L[t] * fz;
    dN(a, 0) = kDL[t][0] * fz;
    dN(a, 1) = kDL[t][1] * fz;
    dN(a, 2) = 0.5 * zi * L[t];
  }
}

// WEDGE15 (gmsh order): corners 0-2 at zeta=-1 and 3-5 at zeta=+1; 6 (0,1), 7 (0,2), 9 (1,2)
// on the bottom triangle; 12 (3,4), 13 (3,5), 14 (4,5) on the top; 8, 10, 11 on the vertical
// edges above vertices 0, 1, 2.
void shape_wedge15(const Eigen::Vector3d& x, ShapeValues& N, ShapeGradients& dN) {
  double L[3];
  tri(x, L);
  const double z = x[2], bz = 1 - z * z;
  for (int a = 0; a < 6; ++a) {  // 1/2 L (2L-1)(1 + z zi) - 1/2 L (1 - z^2)
    const int t = a % 3;
    const double zi = a < 3 ? -1.0 : 1.0, fz = 1 + zi * z;
    N[a] = 0.5 * L[t] * (2 * L[t] - 1) * fz - 0.5 * L[t] * bz;
    const double dLfac = 0.5 * (4 * L[t] - 1) * fz - 0.5 * bz;
    dN(a, 0) = dLfac * kDL[t][0];
    dN(a, 1) = dLfac * kDL[t][1];
    dN(a, 2) = 0.5 * L[t] * (2 * L[t] - 1) * zi + L[t] * z;
  }
  constexpr int kTriEdge[6][3] = {{6, 0, 1}, {7, 0, 2}, {9, 1, 2}, {12, 0, 1}, {13, 0, 2}, {14, 1, 2}};
  for (const auto& e : kTriEdge) {  // 2 La Lb (1 + z zi)
    const int n = e[0], p = e[1], q = e[2];
    const double zi = n < 12 ? -1.0 : 1.0, fz = 1 + zi * z;
    N[n] = 2 * L[p] * L[q] * fz;
    for (int j = 0; j < 2; ++j) dN(n, j) = 2 * (kDL[p][j] * L[q] + L[p] * kDL[q][j]) * fz;
    dN(n, 2) = 2 * L[p] * L[q] * zi;
  }
  constexpr int kVertical[3][2] = {{8, 0}, {10, 1}, {11, 2}};
  for (const auto& e : kVertical) {  // L (1 - z^2)
    const int n = e[0], t = e[1];
    N[n] = L[t] * bz;
    dN(n, 0) = kDL[t][0] * bz;
    dN(n, 1) = kDL[t][1] * bz;
    dN(n, 2) = -2 * z * L[t];
  }
}

}  // namespace ffr::preproc::detail
