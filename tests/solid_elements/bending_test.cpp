// Slender cantilever (L = 10, square section 1 x 1, clamped at x = 0, uniform shear traction
// on the end face with resultant P): the load-weighted tip deflection f.u / P against
// Timoshenko beam theory, delta = P L^3 / (3 E I) + P L / (kappa G A), with Cowper's shear
// coefficient for a rectangle kappa = 10 (1 + nu) / (12 + 11 nu) (G. R. Cowper, "The shear
// coefficient in Timoshenko's beam theory", J. Appl. Mech. 33 (1966) 335-340).
// HEX8 uses one element through the thickness: the incompatible-modes element must be
// accurate while the plain trilinear one locks.
#include "support.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace ffr::preproc;
using namespace ffr::test;

namespace {
const Material kMat{1.0e5, 0.3, 1.0};
constexpr double kLen = 10, kH = 1, kP = 1;

double reference_deflection() {
  const double A = kH * kH, I = kH * kH * kH * kH / 12, G = kMat.E / (2 * (1 + kMat.nu));
  const double kappa = 10 * (1 + kMat.nu) / (12 + 11 * kMat.nu);
  return kP * kLen * kLen * kLen / (3 * kMat.E * I) + kP * kLen / (kappa * G * A);
}

double tip_deflection(ElementType t, int nx, int nyz, const SolidOptions& opt = {}) {
  const Patch p = make_box(t, nx, nyz, nyz, {kLen, kH, kH});
  const Eigen::VectorXd f = face_loads(p, 0, kLen, 1.0, [](const Eigen::Vector3d&, const Eigen::Vector3d&) {
    return Eigen::Vector3d(0, 0, -kP / (kH * kH));
  });
  std::map<int, double> fixed;
  for (std::size_t n = 0; n < p.x.size(); ++n)
    if (std::abs(p.x[n].x()) < 1e-12)
      for (int i = 0; i < 3; ++i) fixed[3 * static_cast<int>(n) + i] = 0;
  const Eigen::VectorXd u = solve_dirichlet(assemble_stiffness(p, kMat, opt), f, fixed);
  return f.dot(u) / kP;  // work-conjugate deflection (f and u both point along -z)
}
}  // namespace

TEST(CantileverBending, Hex8IncompatibleModesDoNotLock) {
  const double ref = reference_deflection();
  const double im = tip_deflection(ElementType::Hex8, 10, 1);
  const double plain = tip_deflection(ElementType::Hex8, 10, 1, {false, false});
  RecordProperty("hex8_incompatible_ratio", std::to_string(im / ref));
  RecordProperty("hex8_plain_ratio", std::to_string(plain / ref));
  EXPECT_NEAR(im / ref, 1.0, 0.03) << "HEX8 incompatible: " << im << " vs " << ref;
  EXPECT_LT(plain / ref, 0.75) << "plain trilinear HEX8 should lock: " << plain << " vs " << ref;
  std::cout << "[ HEX8 ] incompatible/ref = " << im / ref << ", plain/ref = " << plain / ref << "\n";
}

TEST(CantileverBending, Hex20) {
  // One element through the thickness: 0.980 of the beam value; refined (2 x 2 through the
  // section) 0.990, and 4 x 4 gives 0.992: the remaining ~0.8% is the 3D clamp (warping and
  // Poisson contraction held at x = 0), which beam theory does not have.
  const double ref = reference_deflection();
  const double d1 = tip_deflection(ElementType::Hex20, 10, 1), d2 = tip_deflection(ElementType::Hex20, 20, 2);
  std::cout << "[ HEX20 ] ratio = " << d1 / ref << " (1 through thickness), " << d2 / ref << " (2)\n";
  EXPECT_NEAR(d1 / ref, 1.0, 0.03);
  EXPECT_NEAR(d2 / ref, 1.0, 0.015);
  EXPECT_GT(d2, d1);  // converges from below (stiffer coarse mesh)
}

TEST(CantileverBending, Tet10) {
  const double ref = reference_deflection(), d = tip_deflection(ElementType::Tet10, 10, 1);
  std::cout << "[ TET10 ] ratio = " << d / ref << "\n";
  EXPECT_NEAR(d / ref, 1.0, 0.03);
}

TEST(CantileverBending, OtherQuadraticTypes) {
  const double ref = reference_deflection();
  for (ElementType t : {ElementType::Hex27, ElementType::Wedge15}) {
    const double d = tip_deflection(t, 10, 1);
    std::cout << "[ " << name(t) << " ] ratio = " << d / ref << "\n";
    EXPECT_NEAR(d / ref, 1.0, 0.03) << name(t);
  }
}
