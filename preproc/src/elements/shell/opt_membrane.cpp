// TRI3 membrane with drilling freedoms: Felippa's optimal ANDES triangle "OPT"
// (C. A. Felippa, "A study of optimal membrane triangles with drilling freedoms", CMAME 192
// (2003) 2125–2168; equation numbers below refer to it). Implemented from the paper's
// equations as a strain field, which also gives the membrane forces at any point:
//   eps(L) = [ B  +  (3/2) sqrt(beta0) Te (L1 Q1 + L2 Q2 + L3 Q3) Ttu ] d
// with B = L^T / V the basic strain–displacement matrix of the force-lumping matrix L
// (eq. 22, alpha_b = 3/2), Ttu the hierarchical (deviatoric) corner rotations
// theta_i - theta_CST (eq. 16), Te the strain-gauge rosette map from the natural strains along
// the sides to Cartesian strains (eq. 12), and Q_i the natural strains at corner i (eq. 29).
// Because Q1 + Q2 + Q3 = 0 the higher-order part is energy-orthogonal to the basic one, so
// K = V B^T D B + (3/4) beta0 Ttu^T (A t sum_midpoints Q^T Te^T D Te Q) Ttu (eq. 32), and the
// patch test holds for any beta. The OPT signature: beta = (1, 2, 1, 0, 1, -1, -1, -1, -2),
// beta0 = max((1 - 4 nu^2)/2, 0.01); exact in-plane pure bending of rectangular units of any
// aspect ratio (the optimality criterion of the paper).
// Local DOFs per node (u, v, rz).

#include "local_part.hpp"
#include "shape2d.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace ffr::preproc::shell {

LocalPart opt_membrane(const Eigen::Matrix<double, 3, 2>& xy, const Material& m, double t) {
  const Eigen::Matrix3d D = plane_stress(m.E, m.nu) * t;
  constexpr double alpha_b = 1.5;
  constexpr double beta[10] = {0, 1, 2, 1, 0, 1, -1, -1, -1, -2};  // beta[1..9]
  const double beta0 = std::max(0.5 * (1 - 4 * m.nu * m.nu), 0.01);

  const double x1 = xy(0, 0), x2 = xy(1, 0), x3 = xy(2, 0);
  const double y1 = xy(0, 1), y2 = xy(1, 1), y3 = xy(2, 1);
  const double x12 = x1 - x2, x21 = -x12, x23 = x2 - x3, x32 = -x23, x31 = x3 - x1, x13 = -x31;
  const double y12 = y1 - y2, y21 = -y12, y23 = y2 - y3, y32 = -y23, y31 = y3 - y1, y13 = -y31;
  const double A = 0.5 * (y21 * x13 - x21 * y13);

  // Basic strain-displacement matrix B = L^T / V (eq. 22).
  Eigen::Matrix<double, 3, 9> B;
  B << y23, 0, alpha_b / 6 * y23 * (y13 - y21), y31, 0, alpha_b / 6 * y31 * (y21 - y32), y12, 0,
      alpha_b / 6 * y12 * (y32 - y13),  //
      0, x32, alpha_b / 6 * x32 * (x31 - x12), 0, x13, alpha_b / 6 * x13 * (x12 - x23), 0, x21,
      alpha_b / 6 * x21 * (x23 - x31),  //
      x32, y23, alpha_b / 3 * (x31 * y13 - x12 * y21), x13, y31, alpha_b / 3 * (x12 * y21 - x23 * y32), x21, y12,
      alpha_b / 3 * (x23 * y32 - x31 * y13);
  B /= 2 * A;

  // Hierarchical rotations: theta_i minus the CST rotation (v,x - u,y)/2 (eq. 16).
  Eigen::Matrix<double, 3, 9> Ttu;
  for (int i = 0; i < 3; ++i) {
    Ttu.row(i) << x32, y32, 0, x13, y13, 0, x21, y21, 0;
    Ttu.row(i) /= 4 * A;
    Ttu(i, 3 * i + 2) = 1;
  }

  const double l21 = x21 * x21 + y21 * y21, l32 = x32 * x32 + y32 * y32, l13 = x13 * x13 + y13 * y13;
  Eigen::Matrix3d Te;  // Cartesian (exx, eyy, gxy) = Te (e_21, e_32, e_13) (eq. 12)
  Te.col(0) << y23 * y13 * l21, x23 * x13 * l21, (y23 * x31 + x32 * y13) * l21;
  Te.col(1) << y31 * y21 * l32, x31 * x21 * l32, (y31 * x12 + x13 * y21) * l32;
  Te.col(2) << y12 * y32 * l13, x12 * x32 * l13, (y12 * x23 + x21 * y32) * l13;
  Te /= 4 * A * A;

  // Natural strains at the corners from the hierarchical rotations (eq. 29).
  auto Q = [&](int a, int b, int c, int d, int e, int f, int g, int h, int k) {
    Eigen::Matrix3d q;
    q << beta[a] / l21, beta[b] / l21, beta[c] / l21, beta[d] / l32, beta[e] / l32, beta[f] / l32, beta[g] / l13,
        beta[h] / l13, beta[k] / l13;
    return Eigen::Matrix3d(q * (2 * A / 3));
  };
  const Eigen::Matrix3d Q1 = Q(1, 2, 3, 4, 5, 6, 7, 8, 9);
  const Eigen::Matrix3d Q2 = Q(9, 7, 8, 3, 1, 2, 6, 4, 5);
  const Eigen::Matrix3d Q3 = Q(5, 6, 4, 8, 9, 7, 2, 3, 1);

  const double bt = 1.5 * std::sqrt(beta0);
  LocalPart part;
  part.K = Eigen::MatrixXd::Zero(9, 9);
  const Rule2 rule = tri_rule3();
  for (std::size_t g = 0; g < rule.xi.size(); ++g) {
    const Eigen::Vector3d L = tri3_N(rule.xi[g].x(), rule.xi[g].y());
    const Eigen::Matrix<double, 3, 9> Bg = B + bt * Te * (L(0) * Q1 + L(1) * Q2 + L(2) * Q3) * Ttu;
    const double dA = 2 * A * rule.w[g];
    part.K += dA * Bg.transpose() * D * Bg;
    part.xi.push_back(rule.xi[g]);
    part.area.push_back(dA);
    part.B.push_back(Bg);
  }
  part.K = 0.5 * (part.K + part.K.transpose()).eval();
  return part;
}

}  // namespace ffr::preproc::shell
