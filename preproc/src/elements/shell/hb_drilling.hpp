#pragma once
// Hughes–Brezzi drilling rotations (Hughes & Brezzi, CMAME 72 (1989) 105–121): the in-plane
// rotation rz is an independent field tied to the skew part of the displacement gradient by the
// variationally consistent term
//     (gamma t / 2) int (omega(u) - rz)^2 dA,   omega(u) = (v,x - u,y) / 2,
// which vanishes for every rigid motion and every linear field whose rz equals its rotation, so
// it leaves the patch test intact. Hughes & Brezzi show the formulation is stable for any
// gamma > 0 and recommend gamma = G; Ibrahimbegovic, Taylor & Wilson (IJNME 30 (1990)) find the
// results insensitive to gamma near G. We use gamma = G.

#include <Eigen/Core>

namespace ffr::preproc::shell {

inline constexpr double kDrillingGammaOverG = 1.0;

/// Adds the contribution of a displacement mode with Cartesian gradient (dx, dy) on the u and v
/// columns `cu`, `cv` to the row of omega(u) - rz.
template <class Row>
inline void add_skew(Row& r, int cu, int cv, double dx, double dy) {
  r(cu) += -0.5 * dy;
  r(cv) += 0.5 * dx;
}

}  // namespace ffr::preproc::shell
