#include "synthetic_bodies.hpp"

#include "ffr/formats/sid_io.hpp"

#include <random>

namespace ffr::runtime::test {

formats::Sid lumpy_body(int nq, unsigned seed, bool with_rotations, double damping) {
  using formats::synthetic::PointMass;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<PointMass> pts;
  const int n = 7;
  for (int p = 0; p < n; ++p) {
    PointMass pm;
    pm.m = 0.3 + 0.1 * p;
    pm.c = Eigen::Vector3d(0.15 * p, 0.05 * u(rng), 0.04 * u(rng));
    if (with_rotations) {
      const double i = 1e-3 * (1 + 0.2 * p);
      pm.inertia = Eigen::Vector3d(i, 0.8 * i, 0.6 * i).asDiagonal();
    }
    pts.push_back(pm);
  }
  Eigen::MatrixXd Phi(3 * n, nq), Psi(3 * n, nq);
  for (int p = 0; p < n; ++p) {
    const double s = static_cast<double>(p) / (n - 1);
    for (int k = 0; k < nq; ++k) {
      const double a = std::sin((k + 1) * 1.3 * s + 0.2 * k), b = std::cos((k + 2) * 0.9 * s);
      Phi.block<3, 1>(3 * p, k) = Eigen::Vector3d(0.3 * a * b, a, 0.5 * b) * 0.1 + 0.01 * Eigen::Vector3d(u(rng), u(rng), u(rng));
      Psi.block<3, 1>(3 * p, k) = Eigen::Vector3d(0.2 * b, -a, 0.7 * a * b) * 0.2;
    }
  }
  Eigen::VectorXd omega(nq);
  for (int k = 0; k < nq; ++k) omega(k) = 30.0 * (k + 1);
  return formats::synthetic::from_shapes(pts, Phi, with_rotations ? Psi : Eigen::MatrixXd(), omega,
                                         {{"A", 0}, {"B", n - 1}, {"C", 3}}, "free", damping);
}

formats::Sid mean_axis_body(int nq, unsigned seed) {
  using formats::synthetic::PointMass;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  const int n = 9;
  std::vector<PointMass> pts(n);
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  double mass = 0;
  for (int p = 0; p < n; ++p) {
    pts[p].m = 0.5 + 0.1 * p;
    pts[p].c = Eigen::Vector3d(0.4 * u(rng), 0.3 * u(rng), 0.2 * u(rng));
    const double i = 2e-3 * (1 + 0.1 * p);
    pts[p].inertia = Eigen::Vector3d(i, 0.7 * i, 0.5 * i).asDiagonal();
    com += pts[p].m * pts[p].c;
    mass += pts[p].m;
  }
  com /= mass;
  for (auto& p : pts) p.c -= com;
  // Generalised mass over (translation, rotation) of every point, and the rigid-body modes.
  const int N = 6 * n;
  Eigen::MatrixXd Mg = Eigen::MatrixXd::Zero(N, N), R(N, 6);
  for (int p = 0; p < n; ++p) {
    Mg.block<3, 3>(3 * p, 3 * p) = pts[p].m * Eigen::Matrix3d::Identity();
    Mg.block<3, 3>(3 * n + 3 * p, 3 * n + 3 * p) = pts[p].inertia;
    Eigen::Matrix3d cx;
    const Eigen::Vector3d& c = pts[p].c;
    cx << 0, -c(2), c(1), c(2), 0, -c(0), -c(1), c(0), 0;
    R.block<3, 3>(3 * p, 0) = Eigen::Matrix3d::Identity();
    R.block<3, 3>(3 * p, 3) = -cx;  // translation of a rotation w: w x c
    R.block<3, 3>(3 * n + 3 * p, 0).setZero();
    R.block<3, 3>(3 * n + 3 * p, 3) = Eigen::Matrix3d::Identity();
  }
  Eigen::MatrixXd S(N, nq);
  for (int k = 0; k < nq; ++k)
    for (int i = 0; i < N; ++i) S(i, k) = std::sin(0.7 * (k + 1) * i + 0.3 * k) + 0.2 * u(rng);
  // Remove the rigid-body part in the mass metric: S -= R (R^T M R)^-1 R^T M S.
  S -= R * (R.transpose() * Mg * R).ldlt().solve(R.transpose() * Mg * S);
  Eigen::VectorXd omega(nq);
  for (int k = 0; k < nq; ++k) omega(k) = 40.0 * (k + 1);
  return formats::synthetic::from_shapes(pts, S.topRows(3 * n), S.bottomRows(3 * n), omega, {{"A", 0}, {"B", n - 1}},
                                         "free", 0.0);
}

std::filesystem::path write_sid_file(const formats::Sid& sid, const std::filesystem::path& path) {
  formats::write_sid(sid, path);
  return path;
}

}  // namespace ffr::runtime::test
