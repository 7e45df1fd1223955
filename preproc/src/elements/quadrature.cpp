#include "ffr/preproc/elements/quadrature.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace ffr::preproc::quadrature {

void gauss_legendre(int n, double* x, double* w) {
  // Closed forms (Abramowitz & Stegun, table 25.4).
  switch (n) {
    case 1: x[0] = 0; w[0] = 2; return;
    case 2: {
      const double a = 1.0 / std::sqrt(3.0);
      x[0] = -a; x[1] = a; w[0] = w[1] = 1; return;
    }
    case 3: {
      const double a = std::sqrt(0.6);
      x[0] = -a; x[1] = 0; x[2] = a; w[0] = w[2] = 5.0 / 9.0; w[1] = 8.0 / 9.0; return;
    }
    case 4: {
      const double s = 2.0 / 7.0 * std::sqrt(6.0 / 5.0);
      const double a = std::sqrt(3.0 / 7.0 - s), b = std::sqrt(3.0 / 7.0 + s);
      const double wa = (18.0 + std::sqrt(30.0)) / 36.0, wb = (18.0 - std::sqrt(30.0)) / 36.0;
      x[0] = -b; x[1] = -a; x[2] = a; x[3] = b; w[0] = w[3] = wb; w[1] = w[2] = wa; return;
    }
    case 5: {
      const double s = 2.0 * std::sqrt(10.0 / 7.0);
      const double a = std::sqrt(5.0 - s) / 3.0, b = std::sqrt(5.0 + s) / 3.0;
      const double wa = (322.0 + 13.0 * std::sqrt(70.0)) / 900.0;
      const double wb = (322.0 - 13.0 * std::sqrt(70.0)) / 900.0;
      x[0] = -b; x[1] = -a; x[2] = 0; x[3] = a; x[4] = b;
      w[0] = w[4] = wb; w[1] = w[3] = wa; w[2] = 128.0 / 225.0; return;
    }
    default: throw std::invalid_argument("gauss_legendre: n must be 1..5, got " + std::to_string(n));
  }
}

Rule hexahedron(int n) {
  double x[5], w[5];
  gauss_legendre(n, x, w);
  Rule r;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        r.xi.emplace_back(x[i], x[j], x[k]);
        r.w.push_back(w[i] * w[j] * w[k]);
      }
  return r;
}

namespace {
// Adds the orbit of barycentric point (l0, l1, l2) (all its distinct permutations) with
// weight w per point; the reference triangle is (r, s) = (l1, l2).
void tri_orbit(Rule& r, double a, double b, double w) {  // points (a, a, b) and permutations
  const double l[3][3] = {{a, a, b}, {a, b, a}, {b, a, a}};
  const int n = (a == b) ? 1 : 3;
  for (int i = 0; i < n; ++i) {
    r.xi.emplace_back(l[i][1], l[i][2], 0.0);
    r.w.push_back(w);
  }
}
// Tetrahedron orbits in barycentric coordinates; (x, y, z) = (l1, l2, l3).
void tet_orbit_aaab(Rule& r, double a, double w) {
  const double b = 1 - 3 * a;
  const double l[4][4] = {{b, a, a, a}, {a, b, a, a}, {a, a, b, a}, {a, a, a, b}};
  for (const auto& p : l) {
    r.xi.emplace_back(p[1], p[2], p[3]);
    r.w.push_back(w);
  }
}
void tet_orbit_aabb(Rule& r, double a, double w) {
  const double b = 0.5 - a;
  const double l[6][4] = {{a, a, b, b}, {a, b, a, b}, {a, b, b, a},
                          {b, a, a, b}, {b, a, b, a}, {b, b, a, a}};
  for (const auto& p : l) {
    r.xi.emplace_back(p[1], p[2], p[3]);
    r.w.push_back(w);
  }
}
}  // namespace

Rule triangle(int degree) {
  Rule r;
  if (degree <= 1) {
    tri_orbit(r, 1.0 / 3.0, 1.0 / 3.0, 0.5);
  } else if (degree == 2) {
    tri_orbit(r, 1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0);
  } else if (degree <= 5) {
    // Radon's 7-point degree-5 rule (Stroud 1971, T2:5-1), weights for area 1/2.
    const double s = std::sqrt(15.0);
    tri_orbit(r, 1.0 / 3.0, 1.0 / 3.0, 9.0 / 80.0);
    const double a1 = (6.0 - s) / 21.0, a2 = (6.0 + s) / 21.0;
    tri_orbit(r, a1, 1 - 2 * a1, (155.0 - s) / 2400.0);
    tri_orbit(r, a2, 1 - 2 * a2, (155.0 + s) / 2400.0);
  } else {
    throw std::invalid_argument("triangle rule: degree <= 5 supported, got " + std::to_string(degree));
  }
  return r;
}

Rule tetrahedron(int degree) {
  Rule r;
  if (degree <= 1) {
    r.xi.emplace_back(0.25, 0.25, 0.25);
    r.w.push_back(1.0 / 6.0);
  } else if (degree == 2) {
    // 4-point rule, a = (5 - sqrt 5)/20 (Keast 1986, rule 2).
    tet_orbit_aaab(r, (5.0 - std::sqrt(5.0)) / 20.0, 1.0 / 24.0);
  } else if (degree <= 5) {
    // 14-point degree-5 rule with positive weights (Walkington 2000, "Quadrature on simplices
    // of arbitrary dimension"; also Keast 1986). Digits checked by the monomial test.
    tet_orbit_aaab(r, 0.31088591926330060980, 0.018781320953002641800);
    tet_orbit_aaab(r, 0.092735250310891226402, 0.012248840519393658257);
    tet_orbit_aabb(r, 0.045503704125649649492, 0.0070910034628469110730);
  } else {
    throw std::invalid_argument("tetrahedron rule: degree <= 5 supported, got " + std::to_string(degree));
  }
  return r;
}

Rule prism(int tri_degree, int n) {
  const Rule t = triangle(tri_degree);
  double x[5], w[5];
  gauss_legendre(n, x, w);
  Rule r;
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < t.size(); ++i) {
      r.xi.emplace_back(t.xi[i].x(), t.xi[i].y(), x[k]);
      r.w.push_back(t.w[i] * w[k]);
    }
  return r;
}

Rule pyramid(int n) {
  double x[5], w[5];
  gauss_legendre(n, x, w);
  Rule r;
  for (int k = 0; k < n; ++k) {
    const double c = 0.5 * (1 + x[k]), wc = 0.5 * w[k] * (1 - c) * (1 - c);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        r.xi.emplace_back(x[i] * (1 - c), x[j] * (1 - c), c);
        r.w.push_back(w[i] * w[j] * wc);
      }
  }
  return r;
}

}  // namespace ffr::preproc::quadrature
