#include "simeon_rod.hpp"

#include <cmath>

namespace ffr::runtime::test {

formats::Sid simeon_rod_sid() {
  using D = SimeonData;
  const double PI = D::PI, L = D::L2;
  const double FACM = D::RHO * D::BB * D::HH * L;  // = rod mass
  const double FACK = D::EE * D::BB * D::HH / L;
  const double m = FACM;
  formats::Sid s;
  s.nodes.push_back({"A", Eigen::Vector3d::Zero(), {}, {}, Eigen::Matrix3d::Identity()});
  s.nodes.push_back({"M", Eigen::Vector3d(L / 2, 0, 0), {}, {}, Eigen::Matrix3d::Identity()});
  s.nodes.push_back({"B", Eigen::Vector3d(L, 0, 0), {}, {}, Eigen::Matrix3d::Identity()});
  s.resize(4);
  s.refmod.mass = m;
  s.refmod.reference = "simeon-crank";
  auto& I = s.integrals;
  I.rdm = Eigen::Vector3d(m * L / 2, 0, 0);
  // Rigid rotational inertia about A: m L^2/3 + m h^2/12 = J2 of crank.f.
  I.rrdm = Eigen::Vector3d(m * L * L / 3, m * D::HH * D::HH / 12, m * D::BB * D::BB / 12).asDiagonal();
  // c1 = int axial shapes, c2 = int lateral shapes (crank.f, times rho).
  I.Pdm.setZero();
  I.Pdm(0, 2) = m * 2.0 / 3.0;
  I.Pdm(0, 3) = m / 6.0;
  I.Pdm(1, 0) = m * 2.0 / PI;
  // c12 = int x axial, c21 = int x lateral.
  for (auto& r : I.rPdm) r.setZero();
  I.rPdm[0](0, 2) = m * L / 3.0;
  I.rPdm[0](0, 3) = m * L / 6.0;
  I.rPdm[0](1, 0) = m * L / PI;
  I.rPdm[0](1, 1) = -m * L * 0.5 / PI;
  for (auto& row : I.PPdm)
    for (auto& M : row) M.setZero();
  // MQ of crank.f.
  I.PPdm[1][1](0, 0) = FACM * 0.5;
  I.PPdm[1][1](1, 1) = FACM * 0.5;
  I.PPdm[0][0](2, 2) = FACM * 8.0;
  I.PPdm[0][0](2, 3) = I.PPdm[0][0](3, 2) = FACM * 1.0;
  I.PPdm[0][0](3, 3) = FACM * 2.0;
  // int axial_i lateral_j dm, consistent with crank.f's BQ = PPdm[x][y] - PPdm[x][y]^T.
  I.PPdm[0][1](2, 0) = m * 16.0 / (PI * PI * PI);
  I.PPdm[0][1](3, 0) = m * (1.0 / PI - 8.0 / (PI * PI * PI));
  I.PPdm[0][1](3, 1) = -m * 0.5 / PI;
  I.PPdm[1][0] = I.PPdm[0][1].transpose();
  s.Me = I.PPdm[0][0] + I.PPdm[1][1];
  s.Ke(0, 0) = FACK * std::pow(PI, 4) / 24.0 * std::pow(D::HH / L, 2);
  s.Ke(1, 1) = FACK * std::pow(PI, 4) * 2.0 / 3.0 * std::pow(D::HH / L, 2);
  s.Ke(2, 2) = FACK * 16.0 / 3.0;
  s.Ke(2, 3) = s.Ke(3, 2) = -FACK * 8.0 / 3.0;
  s.Ke(3, 3) = FACK * 7.0 / 3.0;
  for (int k = 0; k < 4; ++k) s.refmod.frequency_hz(k) = std::sqrt(s.Ke(k, k) / s.Me(k, k)) / (2 * M_PI);
  // Node slices: B moves axially with q4 only (the lateral shapes vanish at both ends).
  s.nodes[2].phi(0, 3) = 1.0;
  s.nodes[1].phi(1, 0) = std::sin(PI / 2);
  s.nodes[1].phi(1, 1) = std::sin(PI);
  s.nodes[1].phi(0, 2) = 1.0;
  s.provenance.generator = "ffr runtime tests (IVP Test Set crank.f)";
  return s;
}

std::vector<Eigen::MatrixXd> simeon_rod_ke_m1() {
  using D = SimeonData;
  const double L = D::L2, EA = D::EE * D::BB * D::HH, pi = M_PI;
  // Slopes of the four shapes (u', w') at xi = x / L.
  auto slopes = [&](double xi) {
    Eigen::Matrix<double, 2, 4> d = Eigen::Matrix<double, 2, 4>::Zero();
    d(1, 0) = pi * std::cos(pi * xi) / L;
    d(1, 1) = 2 * pi * std::cos(2 * pi * xi) / L;
    d(0, 2) = (4 - 8 * xi) / L;
    d(0, 3) = (4 * xi - 1) / L;
    return d;
  };
  // Composite 5-point Gauss-Legendre over 40 cells: the integrands are smooth.
  const double gx[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
  const double gw[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665, 0.2369268850561891};
  std::vector<Eigen::MatrixXd> M1(4, Eigen::MatrixXd::Zero(4, 4));
  const int cells = 40;
  for (int c = 0; c < cells; ++c)
    for (int g = 0; g < 5; ++g) {
      const double xi = (c + 0.5 + 0.5 * gx[g]) / cells, w = 0.5 * gw[g] * L / cells;
      const auto d = slopes(xi);
      for (int k = 0; k < 4; ++k) {
        const double N = EA * d(0, k);
        if (N == 0) continue;
        M1[static_cast<std::size_t>(k)] += w * N * (d.transpose() * d);
      }
    }
  return M1;
}

}  // namespace ffr::runtime::test
