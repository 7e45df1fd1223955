// PYRAMID5 with the rational basis (Bedrosian 1992; see solid_shape.hpp). Derivatives are
// singular only at the apex (zeta = 1), where no quadrature point lies.
#include "shape_families.hpp"

namespace ffr::preproc::detail {

void shape_pyramid5(const Eigen::Vector3d& x, ShapeValues& N, ShapeGradients& dN) {
  const auto& ref = reference_nodes(ElementType::Pyramid5);
  const double R = 1 - x[2];
  for (int a = 0; a < 4; ++a) {
    const double xi = ref[a][0], yi = ref[a][1];
    const double P = R + xi * x[0], Q = R + yi * x[1];
    N[a] = 0.25 * P * Q / R;
    dN(a, 0) = 0.25 * xi * Q / R;
    dN(a, 1) = 0.25 * yi * P / R;
    dN(a, 2) = 0.25 * (-(P + Q) / R + P * Q / (R * R));
  }
  N[4] = x[2];
  dN(4, 0) = 0;
  dN(4, 1) = 0;
  dN(4, 2) = 1;
}

}  // namespace ffr::preproc::detail
