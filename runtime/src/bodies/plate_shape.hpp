#pragma once
// The shape functions of the 48-coordinate ANCF plate element (FORMULATION.md 16): products of
// cubic Hermite polynomials (the Bogner-Fox-Schmit rectangle). Shape k = 4 l + t belongs to local
// node l (at xi = l & 1, eta = l >> 1) and its vector t (0 r, 1 r_x, 2 r_y, 3 r_xy).
#include <Eigen/Core>

namespace ffr::runtime::plate_shape {

// Gauss-Legendre points on [0, 1]. Four per direction integrate the mass (degree 6 in each) and
// the small-strain stiffness exactly.
constexpr int kGauss = 4;
constexpr double kXi[kGauss] = {0.069431844202974, 0.330009478207572, 0.669990521792428, 0.930568155797026};
constexpr double kW[kGauss] = {0.173927422568727, 0.326072577431273, 0.326072577431273, 0.173927422568727};

using Vec16 = Eigen::Matrix<double, 16, 1>;
struct Shape {
  Vec16 s, dx, dy, dxx, dyy, dxy;
};

// The cubic Hermite functions of an interval of length l at xi: value at 0, slope at 0, value at
// 1, slope at 1 (the slopes scaled by l), and their first and second derivatives in x = l xi.
inline void hermite(double xi, double l, double (&h)[4], double (&d)[4], double (&dd)[4]) {
  const double x2 = xi * xi, x3 = x2 * xi;
  h[0] = 1 - 3 * x2 + 2 * x3;
  h[1] = l * (xi - 2 * x2 + x3);
  h[2] = 3 * x2 - 2 * x3;
  h[3] = l * (x3 - x2);
  d[0] = (-6 * xi + 6 * x2) / l;
  d[1] = 1 - 4 * xi + 3 * x2;
  d[2] = (6 * xi - 6 * x2) / l;
  d[3] = 3 * x2 - 2 * xi;
  dd[0] = (-6 + 12 * xi) / (l * l);
  dd[1] = (-4 + 6 * xi) / l;
  dd[2] = (6 - 12 * xi) / (l * l);
  dd[3] = (-2 + 6 * xi) / l;
}

inline Shape shape(double xi, double eta, double lx, double ly) {
  double hx[4], dx[4], ddx[4], hy[4], dy[4], ddy[4];
  hermite(xi, lx, hx, dx, ddx);
  hermite(eta, ly, hy, dy, ddy);
  Shape S;
  for (int l = 0; l < 4; ++l) {
    const int a = l & 1, b = l >> 1;
    for (int t = 0; t < 4; ++t) {
      // The x factor is node a's value (t = 0, 2) or slope (t = 1, 3) function; the y factor
      // node b's value (t = 0, 1) or slope (t = 2, 3) function.
      const int fx = 2 * a + (t & 1), fy = 2 * b + (t >> 1);
      const int k = 4 * l + t;
      S.s(k) = hx[fx] * hy[fy];
      S.dx(k) = dx[fx] * hy[fy];
      S.dy(k) = hx[fx] * dy[fy];
      S.dxx(k) = ddx[fx] * hy[fy];
      S.dyy(k) = hx[fx] * ddy[fy];
      S.dxy(k) = dx[fx] * dy[fy];
    }
  }
  return S;
}

}  // namespace ffr::runtime::plate_shape
