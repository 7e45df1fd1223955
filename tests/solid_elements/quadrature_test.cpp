// Every rule integrates the monomials up to its stated degree exactly. The exact integrals
// are the classical closed forms: int_tri r^a s^b = a! b! / (a+b+2)!, int_tet x^a y^b z^c =
// a! b! c! / (a+b+c+3)! (e.g. Zienkiewicz & Taylor, The Finite Element Method, vol. 1, eq. 6.46),
// and for the pyramid the Duffy collapse gives line(a) line(b) c! (a+b+2)! / (a+b+c+3)!.
#include "ffr/preproc/elements/quadrature.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace q = ffr::preproc::quadrature;

namespace {
double fact(int n) { return n <= 1 ? 1.0 : n * fact(n - 1); }
double line(int a) { return a % 2 ? 0.0 : 2.0 / (a + 1); }
double integrate(const q::Rule& r, int a, int b, int c) {
  double s = 0;
  for (int g = 0; g < r.size(); ++g)
    s += r.w[g] * std::pow(r.xi[g].x(), a) * std::pow(r.xi[g].y(), b) * std::pow(r.xi[g].z(), c);
  return s;
}
}  // namespace

TEST(Quadrature, GaussLegendreExactToDegree2nMinus1) {
  for (int n = 1; n <= 5; ++n) {
    const q::Rule r = q::hexahedron(n);
    for (int a = 0; a <= 2 * n - 1; ++a) EXPECT_NEAR(integrate(r, a, 0, 0), line(a) * 4, 1e-14) << n << " " << a;
    EXPECT_GT(std::abs(integrate(r, 2 * n, 0, 0) - line(2 * n) * 4), 1e-6) << "degree 2n must not be exact";
  }
}

TEST(Quadrature, HexahedronTensorMonomials) {
  const q::Rule r = q::hexahedron(3);
  for (int a = 0; a <= 5; ++a)
    for (int b = 0; b <= 5; ++b)
      for (int c = 0; c <= 5; ++c) EXPECT_NEAR(integrate(r, a, b, c), line(a) * line(b) * line(c), 1e-14);
}

TEST(Quadrature, TriangleAndPrism) {
  for (int deg : {1, 2, 5}) {
    const q::Rule r = q::triangle(deg);
    for (const double w : r.w) EXPECT_GT(w, 0);
    for (int a = 0; a <= deg; ++a)
      for (int b = 0; a + b <= deg; ++b)
        EXPECT_NEAR(integrate(r, a, b, 0), fact(a) * fact(b) / fact(a + b + 2), 1e-15) << deg << a << b;
  }
  const q::Rule p = q::prism(5, 4);
  for (int a = 0; a <= 5; ++a)
    for (int b = 0; a + b <= 5; ++b)
      for (int c = 0; c <= 7; ++c)
        EXPECT_NEAR(integrate(p, a, b, c), fact(a) * fact(b) / fact(a + b + 2) * line(c), 1e-15);
}

TEST(Quadrature, Tetrahedron) {
  for (int deg : {1, 2, 5}) {
    const q::Rule r = q::tetrahedron(deg);
    for (const double w : r.w) EXPECT_GT(w, 0);
    for (int a = 0; a <= deg; ++a)
      for (int b = 0; a + b <= deg; ++b)
        for (int c = 0; a + b + c <= deg; ++c)
          EXPECT_NEAR(integrate(r, a, b, c), fact(a) * fact(b) * fact(c) / fact(a + b + c + 3), 1e-15)
              << deg << ": " << a << b << c;
  }
}

TEST(Quadrature, PyramidCollapsed) {
  const q::Rule r = q::pyramid(3);
  for (const double w : r.w) EXPECT_GT(w, 0);
  for (int a = 0; a <= 3; ++a)
    for (int b = 0; a + b <= 3; ++b)
      for (int c = 0; a + b + c <= 3; ++c)
        EXPECT_NEAR(integrate(r, a, b, c), line(a) * line(b) * fact(c) * fact(a + b + 2) / fact(a + b + c + 3),
                    1e-15)
            << a << b << c;
  EXPECT_NEAR(integrate(r, 0, 0, 0), 4.0 / 3.0, 1e-15);  // volume of the reference pyramid
}
