// Andrews' squeezing mechanism as a model file (andrews_model.hpp).
#include "andrews_model.hpp"

#include <Eigen/Core>

#include <cmath>
#include <cstdio>

namespace ffr::runtime::test {
namespace {

// The test set's parameters (andrews.f).
constexpr double m1 = .04325, m2 = .00365, m3 = .02373, m4 = .00706, m5 = .07050, m6 = .00706, m7 = .05498;
constexpr double xa = -.06934, ya = -.00227, xb = -0.03635, yb = .03273, xc = .014, yc = .072, c0 = 4530;
constexpr double i1 = 2.194e-6, i2 = 4.410e-7, i3 = 5.255e-6, i4 = 5.667e-7, i5 = 1.169e-5, i6 = 5.667e-7, i7 = 1.912e-5;
constexpr double d = 28e-3, da = 115e-4, e = 2e-2, ea = 1421e-5, rr = 7e-3, ra = 92e-5, l0 = 7785e-5;
constexpr double ss = 35e-3, sa = 1874e-5, sb = 1043e-5, sc = 18e-3, sd = 2e-2, ta = 2308e-5, tb = 916e-5;
constexpr double u = 4e-2, ua = 1228e-5, ub = 449e-5, zf = 2e-2, zt = 4e-2, fa = 1421e-5, mom = 33e-3;

using V2 = Eigen::Vector2d;
V2 dir(double a) { return {std::cos(a), std::sin(a)}; }
V2 perp(double a) { return {std::sin(a), -std::cos(a)}; }  // dir(a - pi/2)

struct Geometry {
  V2 O{0, 0}, A{xa, ya}, B{xb, yb}, C{xc, yc}, F, E2, E3, E4, E6, G, H, D;
  V2 cg[7];
  double phi[7];  // absolute angles of the bodies
};

Geometry geometry() {
  const double* q = kAndrewsInitial;
  const double be = q[0], th = q[1], ga = q[2], ph = q[3], de = q[4], om = q[5], ep = q[6];
  Geometry g;
  g.phi[0] = be;
  g.phi[1] = be + th;
  g.phi[2] = ga;
  g.phi[3] = ph + de;
  g.phi[4] = de;
  g.phi[5] = om + ep;
  g.phi[6] = ep;
  g.F = rr * dir(be);
  g.E2 = g.F - d * dir(be + th);
  g.E3 = g.B + ss * perp(ga);
  g.G = g.A + zt * dir(de);
  g.E4 = g.G + e * perp(ph + de);
  g.H = g.A + u * perp(ep);
  g.E6 = g.H + zf * dir(om + ep);
  g.D = g.B + sd * dir(ga) + sc * perp(ga);
  // Centres of mass: their distances from the pivots are what the mass matrix fixes (bodies 3,
  // 5 and 7 turn about fixed points, so only the distance matters for them; the side is taken
  // as in the test set's figure and does not change the motion).
  g.cg[0] = ra * dir(be);
  g.cg[1] = g.F - da * dir(be + th);
  g.cg[2] = g.B + sa * perp(ga) + sb * dir(ga);
  g.cg[3] = g.G + (e - ea) * perp(ph + de);
  g.cg[4] = g.A + ta * dir(de) + tb * dir(de + M_PI / 2);
  g.cg[5] = g.H + (zf - fa) * dir(om + ep);
  g.cg[6] = g.A + ua * perp(ep) + ub * dir(ep);
  return g;
}

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}
std::string pt(const V2& p) { return "[" + num(p(0)) + ", " + num(p(1)) + ", 0]"; }

std::string body(const char* name, double m, double I, const V2& pivot, const V2& cg, double phi) {
  const double c = std::cos(phi), s = std::sin(phi);
  // Planar bodies: the out-of-plane moments only have to be those of a real body (the joints
  // hold those rotations).
  return std::string(R"({"name": ")") + name + R"(", "type": "rigid", "mass": )" + num(m) + R"(, "com": )" + pt(cg) +
         R"(, "position": )" + pt(pivot) + R"(, "orientation": [[)" + num(c) + ", " + num(-s) + ", 0], [" + num(s) + ", " +
         num(c) + R"(, 0], [0, 0, 1]], "inertia": [[)" + num(0.6 * I) + ", 0, 0], [0, " + num(0.6 * I) + ", 0], [0, 0, " +
         num(I) + "]]}";
}

std::string revolute(const char* name, const char* b1, const char* b2, const V2& at) {
  return std::string(R"({"name": ")") + name + R"(", "type": "revolute", "body1": ")" + b1 + R"(", "body2": ")" + b2 +
         R"(", "at": )" + pt(at) + R"(, "axis": [0, 0, 1]})";
}

}  // namespace

double andrews_closure_gap() {
  const Geometry g = geometry();
  return std::max({(g.E2 - g.E3).norm(), (g.E2 - g.E4).norm(), (g.E2 - g.E6).norm()});
}

std::string andrews_json(const std::string& solver) {
  const Geometry g = geometry();
  const V2& E = g.E2;
  std::string j = "{\n  \"bodies\": [\n    ";
  j += body("b1", m1, i1, g.O, g.cg[0], g.phi[0]) + ",\n    ";
  j += body("b2", m2, i2, g.F, g.cg[1], g.phi[1]) + ",\n    ";
  j += body("b3", m3, i3, g.B, g.cg[2], g.phi[2]) + ",\n    ";
  j += body("b4", m4, i4, g.G, g.cg[3], g.phi[3]) + ",\n    ";
  j += body("b5", m5, i5, g.A, g.cg[4], g.phi[4]) + ",\n    ";
  j += body("b6", m6, i6, g.H, g.cg[5], g.phi[5]) + ",\n    ";
  j += body("b7", m7, i7, g.A, g.cg[6], g.phi[6]) + "\n  ],\n  \"joints\": [\n    ";
  j += revolute("O", "ground", "b1", g.O) + ",\n    ";
  j += revolute("F", "b1", "b2", g.F) + ",\n    ";
  j += revolute("E3", "b2", "b3", E) + ",\n    ";
  j += revolute("E4", "b2", "b4", E) + ",\n    ";
  j += revolute("E6", "b2", "b6", E) + ",\n    ";
  j += revolute("B", "ground", "b3", g.B) + ",\n    ";
  j += revolute("A5", "ground", "b5", g.A) + ",\n    ";
  j += revolute("A7", "ground", "b7", g.A) + ",\n    ";
  j += revolute("G", "b5", "b4", g.G) + ",\n    ";
  j += revolute("H", "b7", "b6", g.H) + "\n  ],\n";
  j += R"(  "forces": [
    {"type": "spring_damper", "body1": "ground", "at1": )" + pt(g.C) + R"(, "body2": "b3", "at2": )" + pt(g.D) +
       R"(, "k": )" + num(c0) + R"(, "length0": )" + num(l0) + R"(},
    {"type": "point_torque", "body": "b1", "table": {"t": [0, 1], "value": [[0, 0, )" + num(mom) + "], [0, 0, " + num(mom) +
       R"(]]}}
  ],
  "solver": )" + solver + R"(,
  "outputs": [
    {"name": "beta", "type": "joint_coordinate", "joint": "O"},
    {"name": "Theta", "type": "joint_coordinate", "joint": "F"},
    {"name": "gamma", "type": "joint_coordinate", "joint": "B"},
    {"name": "Phi", "type": "joint_coordinate", "joint": "G"},
    {"name": "delta", "type": "joint_coordinate", "joint": "A5"},
    {"name": "Omega", "type": "joint_coordinate", "joint": "H"},
    {"name": "epsilon", "type": "joint_coordinate", "joint": "A7"}
  ]
})";
  return j;
}

}  // namespace ffr::runtime::test
