#include "synthetic_bodies.hpp"

#include "ffr/formats/sid_io.hpp"

#include <random>

namespace ffr::runtime::test {

formats::Sid lumpy_body(int nq, unsigned seed, bool with_rotations) {
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
                                         {{"A", 0}, {"B", n - 1}, {"C", 3}}, "free", 0.02);
}

std::filesystem::path write_sid_file(const formats::Sid& sid, const std::filesystem::path& path) {
  formats::write_sid(sid, path);
  return path;
}

}  // namespace ffr::runtime::test
