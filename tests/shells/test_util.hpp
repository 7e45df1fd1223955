#pragma once
// Helpers shared by the shell and beam tests.

#include <gtest/gtest.h>

#include <Eigen/Core>

#include <string>

#define EXPECT_THROW_MSG(stmt, ExType, fragment)                                              \
  do {                                                                                        \
    try {                                                                                     \
      stmt;                                                                                   \
      ADD_FAILURE() << "expected " #ExType " containing \"" << (fragment) << "\"";            \
    } catch (const ExType& e) {                                                               \
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos)                      \
          << "message \"" << e.what() << "\" lacks \"" << (fragment) << "\"";                 \
    }                                                                                         \
  } while (0)

namespace ffr::test {

/// The six rigid-body motions of 6-DOF nodes at positions x (rows): columns are unit
/// translations along x, y, z and unit rotations about x, y, z through the origin.
inline Eigen::MatrixXd rigid_modes(const Eigen::MatrixX3d& x) {
  const int n = static_cast<int>(x.rows());
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(6 * n, 6);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      R(6 * i + k, k) = 1;
      const Eigen::Vector3d w = Eigen::Vector3d::Unit(k);
      const Eigen::Vector3d u = w.cross(x.row(i).transpose());
      R.block<3, 1>(6 * i, 3 + k) = u;
      R(6 * i + 3 + k, 3 + k) = 1;
    }
  return R;
}

}  // namespace ffr::test
