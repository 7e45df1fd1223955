// The 2-node Timoshenko beam kernel (see beam.hpp for the model and the interpolation).

#include "beam_local.hpp"

#include "../shell/material_check.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace ffr::preproc {

namespace {
const std::string kWho = "beam LINE2";
}

Eigen::Matrix3d beam_frame(const Eigen::MatrixX3d& xe, const Eigen::Vector3d& y_axis) {
  if (xe.rows() != 2) structural::fail(kWho, "expected 2 node rows, got " + std::to_string(xe.rows()));
  structural::check_finite(kWho, xe, "node coordinates");
  const Eigen::Vector3d d = (xe.row(1) - xe.row(0)).transpose();
  const double L = d.norm();
  if (!(L > 1e-12 * std::max(1.0, xe.cwiseAbs().maxCoeff())))
    structural::fail(kWho, "zero length (coincident nodes)");
  if (!y_axis.allFinite() || y_axis.norm() == 0) structural::fail(kWho, "y_axis must be a non-zero vector");
  const Eigen::Vector3d ex = d / L;
  Eigen::Vector3d ey = y_axis - y_axis.dot(ex) * ex;
  if (ey.norm() <= 1e-6 * y_axis.norm())
    structural::fail(kWho, "y_axis is parallel to the element axis; it must fix the section's y direction");
  ey.normalize();
  Eigen::Matrix3d R;
  R.row(0) = ex.transpose();
  R.row(1) = ey.transpose();
  R.row(2) = ex.cross(ey).transpose();
  return R;
}

namespace beam {

void check_input(const Eigen::MatrixX3d& xe, const BeamSection& s) {
  structural::check_positive(kWho, "section A", s.A);
  structural::check_positive(kWho, "section Iy", s.Iy);
  structural::check_positive(kWho, "section Iz", s.Iz);
  structural::check_positive(kWho, "section J", s.J);
  structural::check_non_negative(kWho, "shear factor ky", s.ky);
  structural::check_non_negative(kWho, "shear factor kz", s.kz);
  structural::check_material(kWho, s.material);
  beam_frame(xe, s.y_axis);
}

ShapeParams shape_params(const Eigen::MatrixX3d& xe, const BeamSection& s) {
  ShapeParams p;
  p.L = (xe.row(1) - xe.row(0)).norm();
  const double G = s.material.E / (2 * (1 + s.material.nu));
  const double L2 = p.L * p.L;
  p.phi_y = s.ky > 0 ? 12 * s.material.E * s.Iz / (G * s.ky * s.A * L2) : 0;
  p.phi_z = s.kz > 0 ? 12 * s.material.E * s.Iy / (G * s.kz * s.A * L2) : 0;
  return p;
}

Eigen::Matrix<double, 12, 12> local_stiffness(const ShapeParams& p, const BeamSection& s) {
  const double E = s.material.E, G = E / (2 * (1 + s.material.nu)), L = p.L;
  Eigen::Matrix<double, 12, 12> K = Eigen::Matrix<double, 12, 12>::Zero();
  auto put = [&K](int i, int j, double v) { K(i, j) += v; };
  auto bar = [&](int a, int b, double k) {
    put(a, a, k), put(b, b, k), put(a, b, -k), put(b, a, -k);
  };
  bar(0, 6, E * s.A / L);
  bar(3, 9, G * s.J / L);
  // One bending plane on DOFs (t1, r1, t2, r2); sgn = +1 for (v, rz), -1 for (w, ry).
  auto plane = [&](const int (&c)[4], double EI, double f, double sgn) {
    const double k = EI / ((1 + f) * L * L * L);
    const double m[4][4] = {{12, 6 * L, -12, 6 * L},
                            {6 * L, (4 + f) * L * L, -6 * L, (2 - f) * L * L},
                            {-12, -6 * L, 12, -6 * L},
                            {6 * L, (2 - f) * L * L, -6 * L, (4 + f) * L * L}};
    const double sg[4] = {1, sgn, 1, sgn};
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) put(c[i], c[j], k * m[i][j] * sg[i] * sg[j]);
  };
  plane({1, 5, 7, 11}, E * s.Iz, p.phi_y, 1);
  plane({2, 4, 8, 10}, E * s.Iy, p.phi_z, -1);
  return K;
}

Eigen::Matrix<double, 12, 12> local_transform(const Eigen::Matrix3d& R) {
  Eigen::Matrix<double, 12, 12> T = Eigen::Matrix<double, 12, 12>::Zero();
  for (int b = 0; b < 4; ++b) T.block<3, 3>(3 * b, 3 * b) = R;
  return T;
}

}  // namespace beam

ElementMatrices beam_element(const Eigen::MatrixX3d& xe, const BeamSection& s) {
  beam::check_input(xe, s);
  const Eigen::Matrix3d R = beam_frame(xe, s.y_axis);
  const beam::ShapeParams p = beam::shape_params(xe, s);
  const Eigen::Matrix<double, 12, 12> T = beam::local_transform(R);

  ElementMatrices out;
  out.dofs_per_node = 6;
  out.K = T.transpose() * beam::local_stiffness(p, s) * T;

  // Mass samples: 4 Gauss points along x 4 moment-matching section points.
  const double ay = std::sqrt(2 * s.Iz / s.A), az = std::sqrt(2 * s.Iy / s.A);
  const Eigen::Vector2d section_pts[4] = {{ay, 0}, {-ay, 0}, {0, az}, {0, -az}};
  const Eigen::Vector3d x1 = xe.row(0).transpose();
  out.M = Eigen::MatrixXd::Zero(12, 12);
  for (int g = 0; g < 4; ++g) {
    const Eigen::Matrix<double, 6, 12> H = beam::interpolation(p, beam::kGauss4X[g]);
    for (const auto& yz : section_pts) {
      const Eigen::Vector3d r(0, yz.x(), yz.y());  // local offset of the point from the centroid
      MassSample smp;
      smp.w = s.material.rho * s.A * p.L * beam::kGauss4W[g] / 4;
      smp.c = x1 + R.transpose() * (Eigen::Vector3d(beam::kGauss4X[g] * p.L, 0, 0) + r);
      const Eigen::Matrix<double, 3, 12> Nl = H.topRows<3>() - structural::skew(r) * H.bottomRows<3>();
      smp.N = R.transpose() * Nl * T;
      out.M.noalias() += smp.w * smp.N.transpose() * smp.N;
      out.samples.push_back(std::move(smp));
    }
  }
  return out;
}

}  // namespace ffr::preproc
