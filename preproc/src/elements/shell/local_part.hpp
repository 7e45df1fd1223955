#pragma once
// One in-plane part of a flat shell facet in its local frame, acting on three DOFs per node:
// the membrane on (u, v, rz), the plate on (w, rx, ry). Besides K it keeps the strain–
// displacement maps at its recovery points, from which the resultants (and so the geometric
// stiffness) follow.

#include "ffr/preproc/elements/element.hpp"

#include <Eigen/Core>

#include <vector>

namespace ffr::preproc::shell {

struct LocalPart {
  Eigen::MatrixXd K;                  ///< 3n x 3n
  std::vector<Eigen::Vector2d> xi;    ///< recovery points (natural coordinates)
  std::vector<double> area;           ///< their area weights
  std::vector<Eigen::MatrixXd> B;     ///< membrane strains (exx, eyy, gxy) or curvatures, 3 x 3n
  std::vector<Eigen::MatrixXd> Bs;    ///< plate transverse shear strains (gxz, gyz), 2 x 3n
};

/// QUAD4 membrane with drilling rotations (quad4_membrane.cpp). xy: projected corners.
LocalPart quad4_membrane(const Eigen::Matrix<double, 4, 2>& xy, const Material& m, double t);
/// QUAD4 Reissner–Mindlin plate with MITC4 transverse shear (mitc4_plate.cpp).
LocalPart mitc4_plate(const Eigen::Matrix<double, 4, 2>& xy, const Material& m, double t);
/// TRI3 OPT membrane with drilling rotations (opt_membrane.cpp).
LocalPart opt_membrane(const Eigen::Matrix<double, 3, 2>& xy, const Material& m, double t);
/// TRI3 discrete Kirchhoff plate (dkt_plate.cpp).
LocalPart dkt_plate(const Eigen::Matrix<double, 3, 2>& xy, const Material& m, double t);

}  // namespace ffr::preproc::shell
