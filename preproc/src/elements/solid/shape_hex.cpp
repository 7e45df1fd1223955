// Hexahedra on [-1,1]^3: trilinear HEX8, serendipity HEX20, triquadratic Lagrange HEX27.
// Node positions come from the gmsh reference coordinates (shape_families.cpp), so the
// formulas below never hard-code gmsh's numbering.
#include "shape_families.hpp"

namespace ffr::preproc::detail {

void shape_hex8(const Eigen::Vector3d& x, ShapeValues& N, ShapeGradients& dN) {
  const auto& ref = reference_nodes(ElementType::Hex8);
  for (int a = 0; a < 8; ++a) {
    const double fx = 1 + ref[a][0] * x[0], fy = 1 + ref[a][1] * x[1], fz = 1 + ref[a][2] * x[2];
    N[a] = 0.125 * fx * fy * fz;
    dN(a, 0) = 0.125 * ref[a][0] * fy * fz;
    dN(a, 1) = 0.125 * fx * ref[a][1] * fz;
    dN(a, 2) = 0.125 * fx * fy * ref[a][2];
  }
}

void shape_hex20(const Eigen::Vector3d& x, ShapeValues& N, ShapeGradients& dN) {
  const auto& ref = reference_nodes(ElementType::Hex20);
  for (int a = 0; a < 20; ++a) {
    const double xi = ref[a][0], yi = ref[a][1], zi = ref[a][2];
    if (a < 8) {  // corner: (1/8)(1+x xi)(1+y yi)(1+z zi)(x xi + y yi + z zi - 2)
      const double fx = 1 + xi * x[0], fy = 1 + yi * x[1], fz = 1 + zi * x[2];
      const double s = xi * x[0] + yi * x[1] + zi * x[2];
      N[a] = 0.125 * fx * fy * fz * (s - 2);
      dN(a, 0) = 0.125 * xi * fy * fz * (s - 2 + fx);
      dN(a, 1) = 0.125 * yi * fx * fz * (s - 2 + fy);
      dN(a, 2) = 0.125 * zi * fx * fy * (s - 2 + fz);
    } else {  // mid-edge: the zero reference coordinate gets the bubble (1 - t^2)
      double f[3], df[3];
      for (int j = 0; j < 3; ++j) {
        const double r = ref[a][j];
        if (r == 0) { f[j] = 1 - x[j] * x[j]; df[j] = -2 * x[j]; }
        else { f[j] = 1 + r * x[j]; df[j] = r; }
      }
      N[a] = 0.25 * f[0] * f[1] * f[2];
      dN(a, 0) = 0.25 * df[0] * f[1] * f[2];
      dN(a, 1) = 0.25 * f[0] * df[1] * f[2];
      dN(a, 2) = 0.25 * f[0] * f[1] * df[2];
    }
  }
}

namespace {
// Quadratic Lagrange polynomial on nodes {-1, 0, 1} for node position r, and its derivative.
void lagrange3(double r, double t, double& f, double& df) {
  if (r < 0) { f = 0.5 * t * (t - 1); df = t - 0.5; }
  else if (r > 0) { f = 0.5 * t * (t + 1); df = t + 0.5; }
  else { f = 1 - t * t; df = -2 * t; }
}
}  // namespace

void shape_hex27(const Eigen::Vector3d& x, ShapeValues& N, ShapeGradients& dN) {
  const auto& ref = reference_nodes(ElementType::Hex27);
  for (int a = 0; a < 27; ++a) {
    double f[3], df[3];
    for (int j = 0; j < 3; ++j) lagrange3(ref[a][j], x[j], f[j], df[j]);
    N[a] = f[0] * f[1] * f[2];
    dN(a, 0) = df[0] * f[1] * f[2];
    dN(a, 1) = f[0] * df[1] * f[2];
    dN(a, 2) = f[0] * f[1] * df[2];
  }
}

}  // namespace ffr::preproc::detail
