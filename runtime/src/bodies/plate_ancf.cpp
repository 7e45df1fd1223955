// The ANCF thin plate element (FORMULATION.md section 16): its shape functions, its elastic and
// damping forces and their exact tangents.
#include "plate_shape.hpp"

#include "ffr/runtime/plate.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <optional>

namespace ffr::runtime {
namespace {

using Vec15 = Eigen::Matrix<double, 15, 1>;
using Mat15 = Eigen::Matrix<double, 15, 15>;
using Vec48 = Eigen::Matrix<double, 48, 1>;
using Mat48 = Eigen::Matrix<double, 48, 48>;
using Mat15x48 = Eigen::Matrix<double, 15, 48>;
using Mat3 = Eigen::Matrix3d;
using Vec3 = Eigen::Vector3d;

Mat3 skew(const Vec3& a) {
  Mat3 m;
  m << 0, -a(2), a(1), a(2), 0, -a(0), -a(1), a(0), 0;
  return m;
}

// The energy density of one Gauss point as a function of v = (r_x, r_y, r_xx, r_yy, r_xy): its
// value, gradient g (15) and Hessian H (15 x 15), and the Kelvin-Voigt matrix D = J^T C J of the
// strain and curvature rates (15 x 15).
struct Density {
  double U = 0;
  Vec15 g;
  Mat15 H, D;
};

void density(const AncfPlate& p, const Vec15& v, bool hessian, bool damping, Density& d) {
  const Vec3 a = v.segment<3>(0), b = v.segment<3>(3);
  const double h = p.thickness;
  const double Em = p.E / (1 - p.nu * p.nu), G = p.E / (2 * (1 + p.nu));
  const double Db = p.E * h * h * h / (12 * (1 - p.nu * p.nu));
  d.g.setZero();
  if (hessian) d.H.setZero();
  if (damping) d.D.setZero();

  // Membrane: eps = (exx, eyy, gxy), C_m = h [[Em, Em nu, 0], [Em nu, Em, 0], [0, 0, G]].
  const double exx = 0.5 * (a.squaredNorm() - 1), eyy = 0.5 * (b.squaredNorm() - 1), gxy = a.dot(b);
  const double sxx = h * Em * (exx + p.nu * eyy), syy = h * Em * (eyy + p.nu * exx), txy = h * G * gxy;
  d.U = 0.5 * (sxx * exx + syy * eyy + txy * gxy);
  d.g.segment<3>(0) = sxx * a + txy * b;
  d.g.segment<3>(3) = syy * b + txy * a;
  if (hessian || damping) {
    // J_eps^T C_m J_eps over (a, b): rows d exx = (a, 0), d eyy = (0, b), d gxy = (b, a).
    Eigen::Matrix<double, 6, 6> JCJ;
    JCJ.block<3, 3>(0, 0) = h * Em * a * a.transpose() + h * G * b * b.transpose();
    JCJ.block<3, 3>(3, 3) = h * Em * b * b.transpose() + h * G * a * a.transpose();
    JCJ.block<3, 3>(0, 3) = h * Em * p.nu * a * b.transpose() + h * G * b * a.transpose();
    JCJ.block<3, 3>(3, 0) = JCJ.block<3, 3>(0, 3).transpose();
    if (hessian) {
      d.H.topLeftCorner<6, 6>() = JCJ;
      d.H.block<3, 3>(0, 0).diagonal().array() += sxx;
      d.H.block<3, 3>(3, 3).diagonal().array() += syy;
      d.H.block<3, 3>(0, 3).diagonal().array() += txy;
      d.H.block<3, 3>(3, 0).diagonal().array() += txy;
    }
    if (damping) d.D.topLeftCorner<6, 6>() = p.tau * JCJ;
  }

  // Bending: kappa_i = X_i . n, X = (r_xx, r_yy, r_xy), n = m / s, m = a x b, s = |m|;
  // C_b = D [[1, nu, 0], [nu, 1, 0], [0, 0, 2 (1 - nu)]].
  const Vec3 m = a.cross(b);
  const double s = m.norm();
  const Vec3 n = m / s;
  const Mat3 P = Mat3::Identity() - n * n.transpose();
  const Mat3 Ma = -skew(b), Mb = skew(a);  // dm/da, dm/db
  Mat3 Cb;
  Cb << 1, p.nu, 0, p.nu, 1, 0, 0, 0, 2 * (1 - p.nu);
  Cb *= Db;
  Vec3 kappa;
  Eigen::Matrix<double, 3, 15> Jk = Eigen::Matrix<double, 3, 15>::Zero();  // d kappa / dv
  Vec3 u[3];                                                                // d kappa_i / dm
  for (int i = 0; i < 3; ++i) {
    const Vec3 X = v.segment<3>(6 + 3 * i);
    kappa(i) = X.dot(n);
    u[i] = P * X / s;
    Jk.block<1, 3>(i, 0) = (Ma.transpose() * u[i]).transpose();
    Jk.block<1, 3>(i, 3) = (Mb.transpose() * u[i]).transpose();
    Jk.block<1, 3>(i, 6 + 3 * i) = n.transpose();
  }
  const Vec3 M = Cb * kappa;  // the bending moments per unit length
  d.U += 0.5 * kappa.dot(M);
  d.g.noalias() += Jk.transpose() * M;
  if (hessian) {
    d.H.noalias() += Jk.transpose() * Cb * Jk;
    // M_i times the second derivative of kappa_i = X_i . n(m(a, b)).
    for (int i = 0; i < 3; ++i) {
      const Vec3 X = v.segment<3>(6 + 3 * i);
      const double xn = X.dot(n);
      // Hessian of X . (m / |m|) in m, and of u . (a x b) in (a, b).
      const Mat3 Hn = (-(X * n.transpose() + n * X.transpose()) - xn * Mat3::Identity() + 3 * xn * n * n.transpose()) / (s * s);
      Eigen::Matrix<double, 15, 15> Hi = Eigen::Matrix<double, 15, 15>::Zero();
      Hi.block<3, 3>(0, 0) = Ma.transpose() * Hn * Ma;
      Hi.block<3, 3>(3, 3) = Mb.transpose() * Hn * Mb;
      Hi.block<3, 3>(0, 3) = Ma.transpose() * Hn * Mb - skew(u[i]);
      Hi.block<3, 3>(3, 0) = Hi.block<3, 3>(0, 3).transpose();
      // The mixed terms in X_i and m: d2 (X . n) / dX dm = P / s.
      const Mat3 Pa = P / s * Ma, Pb = P / s * Mb;
      Hi.block<3, 3>(6 + 3 * i, 0) = Pa;
      Hi.block<3, 3>(6 + 3 * i, 3) = Pb;
      Hi.block<3, 3>(0, 6 + 3 * i) = Pa.transpose();
      Hi.block<3, 3>(3, 6 + 3 * i) = Pb.transpose();
      d.H.noalias() += M(i) * Hi;
    }
  }
  if (damping) d.D.noalias() += p.tau * Jk.transpose() * Cb * Jk;
}

// The coordinates of element (ei, ej) in y: its four nodes (i, j), (i+1, j), (i, j+1),
// (i+1, j+1), twelve each; element index 12 l + 3 t + c is global index start(l) + 3 t + c.
// The Gauss point's operator B = Dr (x) I3 (v = B qe) by its 5 x 16 factor Dr: the derivative rows
// x, y, xx, yy, xy of the 16 shape functions; B(3 i + c, 3 k + c) = Dr(i, k).
using Mat5x16 = Eigen::Matrix<double, 5, 16>;

// Adds w B^T H B to K through B's Kronecker factor: G = H B column blocks, then B^T G row blocks
// (about a third of the dense product's multiply-adds, none by B's zeros).
void add_BtHB(const Mat5x16& Dr, const Mat15& H, double w, Mat15x48& G, Mat48& K) {
  G.setZero();
  for (int m = 0; m < 16; ++m)
    for (int j = 0; j < 5; ++j) G.middleCols<3>(3 * m) += Dr(j, m) * H.middleCols<3>(3 * j);
  for (int k = 0; k < 16; ++k)
    for (int i = 0; i < 5; ++i) K.middleRows<3>(3 * k) += (w * Dr(i, k)) * G.middleRows<3>(3 * i);
}

void element_starts(const AncfPlate& p, int ei, int ej, int (&start)[4]) {
  for (int l = 0; l < 4; ++l) start[l] = 12 * p.node(ei + (l & 1), ej + (l >> 1));
}

// One element: adds its forces to Qy and tangents to K, C; returns its strain energy.
double element(const AncfPlate& p, int ei, int ej, const Eigen::Ref<const Eigen::VectorXd>& y,
               const Eigen::Ref<const Eigen::VectorXd>& yd, Eigen::Ref<Eigen::VectorXd>* Qy, Eigen::Ref<Eigen::MatrixXd>* K,
               Eigen::Ref<Eigen::MatrixXd>* C, bool damp) {
  int start[4];
  element_starts(p, ei, ej, start);
  Vec48 qe, qde;
  for (int l = 0; l < 4; ++l) {
    qe.segment<12>(12 * l) = p.q0.segment<12>(start[l]) + y.segment<12>(start[l]);
    qde.segment<12>(12 * l) = yd.segment<12>(start[l]);
  }
  const bool damping = damp && p.tau > 0;
  const double lx = p.dx(), ly = p.dy();
  Vec48 fe = Vec48::Zero();
  Mat48 Ke, Ce;
  if (K) Ke.setZero();
  if (C) Ce.setZero();
  Density d;
  Mat15x48 G;  // add_BtHB's work
  double U = 0;
  for (int gi = 0; gi < plate_shape::kGauss; ++gi)
    for (int gj = 0; gj < plate_shape::kGauss; ++gj) {
      const double w = plate_shape::kW[gi] * plate_shape::kW[gj] * lx * ly;
      const plate_shape::Shape sh = plate_shape::shape(plate_shape::kXi[gi], plate_shape::kXi[gj], lx, ly);
      // v = B qe, B = Dr (x) I3 (add_BtHB).
      Mat5x16 Dr;
      Dr << sh.dx.transpose(), sh.dy.transpose(), sh.dxx.transpose(), sh.dyy.transpose(), sh.dxy.transpose();
      const auto apply = [&Dr](const Vec48& x) {  // B x
        Vec15 r = Vec15::Zero();
        for (int k = 0; k < 16; ++k)
          for (int i = 0; i < 5; ++i) r.segment<3>(3 * i) += Dr(i, k) * x.segment<3>(3 * k);
        return r;
      };
      const auto add_transposed = [&Dr, &fe](double a, const Vec15& g) {  // fe += a B^T g
        for (int k = 0; k < 16; ++k)
          for (int i = 0; i < 5; ++i) fe.segment<3>(3 * k) += (a * Dr(i, k)) * g.segment<3>(3 * i);
      };
      const Vec15 v = apply(qe);
      density(p, v, K != nullptr, damping, d);
      U += w * d.U;
      add_transposed(w, d.g);
      if (K) add_BtHB(Dr, d.H, w, G, Ke);
      if (damping) {
        add_transposed(w, d.D * apply(qde));
        if (C) add_BtHB(Dr, d.D, w, G, Ce);
      }
    }
  if (Qy)
    for (int l = 0; l < 4; ++l) Qy->segment<12>(start[l]) -= fe.segment<12>(12 * l);
  for (int l = 0; l < 4; ++l)
    for (int m = 0; m < 4; ++m) {
      if (K) K->block<12, 12>(start[l], start[m]) += Ke.block<12, 12>(12 * l, 12 * m);
      if (C && damping) C->block<12, 12>(start[l], start[m]) += Ce.block<12, 12>(12 * l, 12 * m);
    }
  return U;
}

}  // namespace

double ancf_plate_forces(const AncfPlate& plate, const Eigen::Ref<const Eigen::VectorXd>& y,
                         const Eigen::Ref<const Eigen::VectorXd>& yd, Eigen::Ref<Eigen::VectorXd> Qy, Eigen::MatrixXd* K,
                         Eigen::MatrixXd* C) {
  std::optional<Eigen::Ref<Eigen::MatrixXd>> Kr, Cr;
  if (K) Kr.emplace(*K);
  if (C) Cr.emplace(*C);
  double U = 0;
  for (int ej = 0; ej < plate.ny; ++ej)
    for (int ei = 0; ei < plate.nx; ++ei)
      U += element(plate, ei, ej, y, yd, &Qy, K ? &*Kr : nullptr, C ? &*Cr : nullptr, true);
  return U;
}

void ancf_plate_tangents(const AncfPlate& plate, const Eigen::Ref<const Eigen::VectorXd>& y,
                         const Eigen::Ref<const Eigen::VectorXd>& yd, Eigen::Ref<Eigen::MatrixXd> K,
                         Eigen::Ref<Eigen::MatrixXd> C) {
  for (int ej = 0; ej < plate.ny; ++ej)
    for (int ei = 0; ei < plate.nx; ++ei) element(plate, ei, ej, y, yd, nullptr, &K, &C, true);
}

double ancf_plate_energy(const AncfPlate& plate, const Eigen::Ref<const Eigen::VectorXd>& y) {
  double U = 0;
  for (int ej = 0; ej < plate.ny; ++ej)
    for (int ei = 0; ei < plate.nx; ++ei) U += element(plate, ei, ej, y, y, nullptr, nullptr, nullptr, false);
  return U;
}

std::string plate_coordinate_name(const AncfPlate& plate, int k) {
  const int node = k / 12, t = (k % 12) / 3;
  const char* what[4] = {" position ", " slope r_x ", " slope r_y ", " twist r_xy "};
  return "node n" + std::to_string(node % (plate.nx + 1)) + "_" + std::to_string(node / (plate.nx + 1)) + what[t] + "xyz"[k % 3];
}

}  // namespace ffr::runtime
