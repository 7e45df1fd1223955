#pragma once
// Internal to diff: natural sizes of a body (from A), used to scale features and tolerances.
#include "ffr/formats/sid.hpp"

#include <algorithm>
#include <cmath>

namespace ffr::formats {

struct Size {
  double m = 1;    ///< mass
  double phi = 1;  ///< displacement of a mode, sqrt(max Me_kk / m)
  double L = 1;    ///< radius of gyration about O
};

inline Size size_of(const Sid& a) {
  Size z;
  z.m = a.refmod.mass > 0 ? a.refmod.mass : 1;
  double me = 0;
  for (Eigen::Index k = 0; k < a.Me.rows(); ++k) me = std::max(me, std::abs(a.Me(k, k)));
  z.phi = me > 0 ? std::sqrt(me / z.m) : 1;
  const double tr = a.J.M0.trace();
  z.L = tr > 0 ? std::sqrt(tr / (2 * z.m)) : 1;
  return z;
}

}  // namespace ffr::formats
