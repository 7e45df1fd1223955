// Tetrahedra in barycentric form: L0 = 1 - xi - eta - zeta, L1 = xi, L2 = eta, L3 = zeta.
#include "shape_families.hpp"

namespace ffr::preproc::detail {

namespace {
// dL_k / dxi_j
constexpr double kDL[4][3] = {{-1, -1, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
// gmsh TET10 edge nodes 4..9: edges (0,1) (1,2) (2,0) (3,0) (3,2) (3,1).
constexpr int kTet10Edge[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
void barycentric(const Eigen::Vector3d& x, double L[4]) {
  L[0] = 1 - x[0] - x[1] - x[2];
  L[1] = x[0]; L[2] = x[1]; L[3] = x[2];
}
}  // namespace

void shape_tet4(const Eigen::Vector3d& x, ShapeValues& N, ShapeGradients& dN) {
  double L[4];
  barycentric(x, L);
  for (int k = 0; k < 4; ++k) {
    N[k] = L[k];
    for (int j = 0; j < 3; ++j) dN(k, j) = kDL[k][j];
  }
}

void shape_tet10(const Eigen::Vector3d& x, ShapeValues& N, ShapeGradients& dN) {
  double L[4];
  barycentric(x, L);
  for (int k = 0; k < 4; ++k) {
    N[k] = L[k] * (2 * L[k] - 1);
    for (int j = 0; j < 3; ++j) dN(k, j) = (4 * L[k] - 1) * kDL[k][j];
  }
  for (int e = 0; e < 6; ++e) {
    const int a = kTet10Edge[e][0], b = kTet10Edge[e][1];
    N[4 + e] = 4 * L[a] * L[b];
    for (int j = 0; j < 3; ++j) dN(4 + e, j) = 4 * (kDL[a][j] * L[b] + L[a] * kDL[b][j]);
  }
}

}  // namespace ffr::preproc::detail
