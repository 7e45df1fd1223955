// Large-deformation thin plates (ANCF, FORMULATION.md 16) against references nobody here
// computed:
// - the natural frequencies of square plates, lambda = omega a^2 sqrt(rho h / D), from
//   A. W. Leissa, "Vibration of Plates", NASA SP-160 (1969): all edges clamped (Table 4.23:
//   35.99, 73.41, 73.41, 108.27, 131.64, 132.24), a cantilever plate (C-F-F-F, nu = 0.3,
//   Table 4.50: 3.492, 8.525, 21.43, 27.33, 31.11), and all edges simply supported against
//   Navier's exact solution lambda = pi^2 (m^2 + n^2);
// - a large static deflection of a clamped square plate under its own (dead) weight against
//   CalculiX (ccx, S4 shells with NLGEOM on a 32 x 32 mesh of the same plate), run by the test,
//   and its small deflection against Kirchhoff's solution w = 0.00126532 q a^4 / D (R. L. Taylor &
//   S. Govindjee, "Solution of clamped rectangular plate problems", Commun. Numer. Meth. Eng. 20
//   (2004); 0.00126 in Timoshenko & Woinowsky-Krieger's "Theory of Plates and Shells", Table 35);
// - the element's forces against finite differences of its energy, and its tangents against
//   finite differences of its forces;
// - a cantilever strip with nu = 0 against the elastica (Bisshopp & Drucker's table);
// - the released clamped plate vibrating at Leissa's first frequency with both integrators;
// - bad input refused naming the file and field.
#include "support.hpp"

#include "ffr/runtime/dynamics.hpp"
#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/plate.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace ffr::runtime;
using test::output;

namespace {

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// A square plate of side a in the x-y plane, corners from the origin.
struct Square {
  double a = 1, h = 0.01, E = 2.1e11, nu = 0.3, rho = 7850;
  double D() const { return E * h * h * h / (12 * (1 - nu * nu)); }
  double lambda(double omega) const { return omega * a * a * std::sqrt(rho * h / D()); }
};

Body square_body(const Square& s, int n, const PlateSupport (&edges)[4], double tau = 0) {
  const Eigen::Vector3d c[4] = {{0, 0, 0}, {s.a, 0, 0}, {s.a, s.a, 0}, {0, s.a, 0}};
  return make_plate_body("plate", c, n, n, s.h, s.E, s.nu, s.rho, tau, edges, "f", "bodies[0]");
}

// The lowest natural frequencies [rad/s] of a plate body at its flat state: the tangent and the
// mass matrix with the supports' coordinates removed (each support row of a plate in the x-y
// plane holds one coordinate).
std::vector<double> frequencies(const Body& b, int count) {
  const AncfPlate& p = *b.plate;
  const int n = p.nq();
  Eigen::VectorXd Q = Eigen::VectorXd::Zero(n);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  ancf_plate_forces(p, Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n), Q, &K, nullptr);
  std::vector<bool> held(static_cast<std::size_t>(n), false);
  for (const PlateSupportRow& r : p.supports) {
    int axis = -1;
    for (int c = 0; c < 3; ++c)
      if (std::abs(r.dir(c)) == 1.0) axis = c;
    EXPECT_GE(axis, 0);
    held[static_cast<std::size_t>(r.index + axis)] = true;
  }
  std::vector<int> keep;
  for (int j = 0; j < n; ++j)
    if (!held[static_cast<std::size_t>(j)]) keep.push_back(j);
  const int m = static_cast<int>(keep.size());
  Eigen::MatrixXd Kr(m, m), Mr(m, m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      Kr(i, j) = K(keep[i], keep[j]);
      Mr(i, j) = b.Myy(keep[i], keep[j]);
    }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ge(Kr, Mr, Eigen::EigenvaluesOnly);
  std::vector<double> w;
  for (int k = 0; k < count; ++k) w.push_back(std::sqrt(std::max(0.0, ge.eigenvalues()(k))));
  return w;
}

void expect_lambdas(const char* what, const Square& s, const std::vector<double>& w, const std::vector<double>& ref,
                    double tol) {
  for (std::size_t k = 0; k < ref.size(); ++k) {
    const double l = s.lambda(w[k]);
    std::printf("%s mode %zu: lambda %.4f, reference %.4f (%+.3f %%)\n", what, k + 1, l, ref[k], 100 * (l / ref[k] - 1));
    EXPECT_NEAR(l / ref[k], 1.0, tol) << what << " mode " << k + 1;
  }
}

}  // namespace

// The element's forces are the gradient of its energy, its stiffness the derivative of its
// forces, its damping matrix the derivative in the rates (central differences), at a strongly
// bent, twisted and stretched state of a plate off the coordinate planes.
TEST(Plate, ElementForcesAndTangentsMatchFiniteDifferences) {
  const Eigen::Vector3d e1 = Eigen::Vector3d(1, 0.2, -0.1).normalized();
  const Eigen::Vector3d e2 = e1.cross(Eigen::Vector3d(0.3, 0.1, 1)).normalized();
  const Eigen::Vector3d o(0.1, -0.2, 0.3);
  const Eigen::Vector3d c[4] = {o, o + 0.8 * e1, o + 0.8 * e1 + 0.5 * e2, o + 0.5 * e2};
  const PlateSupport free[4] = {PlateSupport::Free, PlateSupport::Free, PlateSupport::Free, PlateSupport::Free};
  const Body b = make_plate_body("p", c, 2, 1, 0.02, 1e7, 0.3, 1000, 1e-3, free, "f", "bodies[0]");
  const AncfPlate& p = *b.plate;
  const int n = p.nq();
  Eigen::VectorXd y(n), yd(n);
  for (int i = 0; i < n; ++i) {
    y(i) = 0.05 * std::sin(1.7 * i + 0.3) + 0.02 * std::cos(0.4 * i * i);
    yd(i) = 0.3 * std::cos(0.9 * i + 0.1);
  }
  Eigen::VectorXd Q = Eigen::VectorXd::Zero(n);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n), C = Eigen::MatrixXd::Zero(n, n);
  ancf_plate_forces(p, y, Eigen::VectorXd::Zero(n), Q, &K, &C);
  double ef = 0, ek = 0, ec = 0;
  const double h = 1e-6;
  for (int j = 0; j < n; ++j) {
    Eigen::VectorXd yp = y, ym = y;
    yp(j) += h;
    ym(j) -= h;
    const double dU = (ancf_plate_energy(p, yp) - ancf_plate_energy(p, ym)) / (2 * h);
    ef = std::max(ef, std::abs(-Q(j) - dU));
    Eigen::VectorXd Qp = Eigen::VectorXd::Zero(n), Qm = Eigen::VectorXd::Zero(n);
    ancf_plate_forces(p, yp, Eigen::VectorXd::Zero(n), Qp, nullptr, nullptr);
    ancf_plate_forces(p, ym, Eigen::VectorXd::Zero(n), Qm, nullptr, nullptr);
    ek = std::max(ek, (-(Qp - Qm) / (2 * h) - K.col(j)).cwiseAbs().maxCoeff());
  }
  // The damping force is linear in the rates: C yd is all of it.
  Eigen::VectorXd Qd = Eigen::VectorXd::Zero(n);
  ancf_plate_forces(p, y, yd, Qd, nullptr, nullptr);
  ec = (-(Qd - Q) - C * yd).cwiseAbs().maxCoeff();
  std::printf("forces vs energy gradient %.3e of %.3e; tangent vs force differences %.3e of %.3e; damping %.3e of %.3e\n", ef,
              Q.cwiseAbs().maxCoeff(), ek, K.cwiseAbs().maxCoeff(), ec, (C * yd).cwiseAbs().maxCoeff());
  EXPECT_LT(ef, 1e-6 * Q.cwiseAbs().maxCoeff());
  EXPECT_LT(ek, 1e-6 * K.cwiseAbs().maxCoeff());
  EXPECT_LT((K - K.transpose()).cwiseAbs().maxCoeff(), 1e-9 * K.cwiseAbs().maxCoeff());
  EXPECT_LT(ec, 1e-9 * (C * yd).cwiseAbs().maxCoeff());
  // A rigid motion (a finite rotation and a shift of the reference) strains nothing.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Eigen::VectorXd yr(n);
  for (int k = 0; k < n / 3; ++k) {
    const bool position = (k % 4) == 0;
    const Eigen::Vector3d v = p.q0.segment<3>(3 * k);
    yr.segment<3>(3 * k) = R * v + (position ? Eigen::Vector3d(0.3, -1, 2) : Eigen::Vector3d::Zero()) - v;
  }
  EXPECT_LT(ancf_plate_energy(p, yr), 1e-20);
}

// Clamped square plate (8 x 8 elements) against Leissa's table; the element is conforming, so
// its frequencies converge from above.
TEST(Plate, ClampedSquareFrequenciesMatchLeissa) {
  const Square s;
  const PlateSupport cl[4] = {PlateSupport::Clamped, PlateSupport::Clamped, PlateSupport::Clamped, PlateSupport::Clamped};
  const auto w = frequencies(square_body(s, 8, cl), 6);
  expect_lambdas("C-C-C-C", s, w, {35.99, 73.41, 73.41, 108.27, 131.64, 132.24}, 2.5e-3);
  for (double x : w) EXPECT_GT(s.lambda(x), 0);
}

// Simply supported square plate: Navier's lambda = pi^2 (m^2 + n^2) (exact).
TEST(Plate, SimplySupportedSquareFrequenciesMatchNavier) {
  const Square s;
  const PlateSupport ss[4] = {PlateSupport::SimplySupported, PlateSupport::SimplySupported, PlateSupport::SimplySupported,
                              PlateSupport::SimplySupported};
  const auto w = frequencies(square_body(s, 8, ss), 6);
  const double p2 = M_PI * M_PI;
  expect_lambdas("S-S-S-S", s, w, {2 * p2, 5 * p2, 5 * p2, 8 * p2, 10 * p2, 10 * p2}, 1.5e-3);
}

// Cantilever square plate, clamped along x = 0, nu = 0.3 (Leissa's table is for nu = 0.3). The
// table's values are Ritz solutions with few beam functions, themselves upper bounds a little
// above the converged ones; the conforming element converges from above too (4 x 4, then 8 x 8
// elements: every frequency lower), and 8 x 8 lies within 0.7 % below the table.
TEST(Plate, CantileverSquareFrequenciesMatchLeissa) {
  const Square s;
  const PlateSupport cf[4] = {PlateSupport::Clamped, PlateSupport::Free, PlateSupport::Free, PlateSupport::Free};
  const auto w4 = frequencies(square_body(s, 4, cf), 5);
  const auto w = frequencies(square_body(s, 8, cf), 5);
  expect_lambdas("C-F-F-F", s, w, {3.492, 8.525, 21.43, 27.33, 31.11}, 7e-3);
  for (std::size_t k = 0; k < w.size(); ++k) EXPECT_LT(w[k], w4[k]) << "mode " << k + 1;
}

namespace {

// The clamped square plate of side a under its weight (gravity g), n x n elements, solved
// statically; the centre's deflection.
std::string clamped_plate_json(const Square& s, int n, double g, const std::string& solver) {
  return R"({"gravity": [0, 0, )" + num(-g) + R"(],
    "bodies": [{"name": "plate", "type": "plate", "corners": [[0, 0, 0], [)" + num(s.a) + ", 0, 0], [" + num(s.a) + ", " +
         num(s.a) + ", 0], [0, " + num(s.a) + R"(, 0]],
                "elements": [)" + std::to_string(n) + ", " + std::to_string(n) + R"(], "thickness": )" + num(s.h) +
         R"(, "E": )" + num(s.E) + R"(, "nu": )" + num(s.nu) + R"(, "rho": )" + num(s.rho) + R"(,
                "supports": {"x0": "clamped", "x1": "clamped", "y0": "clamped", "y1": "clamped"}}],
    "solver": )" + solver + R"(,
    "outputs": [{"name": "centre", "type": "node_position", "body": "plate", "node": "n)" + std::to_string(n / 2) + "_" +
         std::to_string(n / 2) + R"("}, {"name": "e", "type": "energy"}]
  })";
}

// CalculiX: the same plate as 32 x 32 S4 shells, clamped edges (all six degrees of freedom of
// the edge nodes), its weight as a dead GRAV load, NLGEOM; the centre's displacement. (S4, not
// S8R: on this thin plate, a / h = 100, ccx's S8R on 16 x 16 was 2.5 % stiff in the linear
// range against Kirchhoff's solution, its S4 on 32 x 32 0.2 %.)
double calculix_centre_deflection(const Square& s, double g, const std::filesystem::path& dir) {
  const int N = 32, M = N + 1;
  const auto id = [&](int i, int j) { return j * M + i + 1; };
  std::ostringstream inp;
  inp.precision(17);
  inp << "*NODE, NSET=NALL\n";
  for (int j = 0; j < M; ++j)
    for (int i = 0; i < M; ++i) inp << id(i, j) << ", " << s.a * i / N << ", " << s.a * j / N << ", 0\n";
  inp << "*ELEMENT, TYPE=S4, ELSET=EALL\n";
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i)
      inp << j * N + i + 1 << ", " << id(i, j) << ", " << id(i + 1, j) << ", " << id(i + 1, j + 1) << ", " << id(i, j + 1) << "\n";
  inp << "*NSET, NSET=NEDGE\n";
  for (int j = 0; j < M; ++j)
    for (int i = 0; i < M; ++i)
      if (i == 0 || j == 0 || i == N || j == N) inp << id(i, j) << ",\n";
  inp << "*NSET, NSET=NCENTRE\n" << id(N / 2, N / 2) << "\n";
  inp << "*MATERIAL, NAME=M\n*ELASTIC\n" << s.E << ", " << s.nu << "\n*DENSITY\n" << s.rho << "\n";
  inp << "*SHELL SECTION, ELSET=EALL, MATERIAL=M\n" << s.h << "\n";
  inp << "*BOUNDARY\nNEDGE, 1, 6\n";
  inp << "*STEP, NLGEOM, INC=1000\n*STATIC\n0.05, 1.0, 1e-6, 0.1\n";
  inp << "*DLOAD\nEALL, GRAV, " << g << ", 0., 0., -1.\n";
  inp << "*NODE PRINT, NSET=NCENTRE\nU\n*END STEP\n";
  test::write_text(dir / "plate.inp", inp.str());
  const int rc = std::system(("cd " + dir.string() + " && OMP_NUM_THREADS=1 ccx -i plate > ccx.log 2>&1").c_str());
  EXPECT_EQ(rc, 0) << "ccx failed; see " << (dir / "ccx.log");
  // The .dat file: blocks "displacements (vx,vy,vz) for set NCENTRE and time t", each followed by
  // the node's line; the last block is the converged end of the step.
  std::ifstream dat(dir / "plate.dat");
  std::string line;
  double w = std::nan(""), t = 0;
  bool next = false;
  while (std::getline(dat, line)) {
    if (line.find("displacements") != std::string::npos) {
      next = true;
      t = std::stod(line.substr(line.rfind(' ') + 1));
      continue;
    }
    std::istringstream is(line);
    int node;
    double ux, uy, uz;
    if (next && (is >> node >> ux >> uy >> uz)) {
      w = uz;
      next = false;
    }
  }
  EXPECT_NEAR(t, 1.0, 1e-9) << "ccx did not reach the full load";
  return w;
}

}  // namespace

// Small deflection: the clamped square plate's centre under a uniform load (its weight) from the
// tangent at the flat state and the gravity load Pdm^T g, against Kirchhoff's series solution
// 0.00126532 q a^4 / D; the conforming element's deflection converges from below.
TEST(Plate, ClampedPlateSmallDeflectionMatchesKirchhoff) {
  const Square s;
  const PlateSupport cl[4] = {PlateSupport::Clamped, PlateSupport::Clamped, PlateSupport::Clamped, PlateSupport::Clamped};
  const double g = 9.81, q = s.rho * s.h * g, exact = 0.00126532 * q * std::pow(s.a, 4) / s.D();
  double previous = 0;
  for (const int n : {4, 8}) {
    const Body b = square_body(s, n, cl);
    const AncfPlate& p = *b.plate;
    const int nq = p.nq();
    Eigen::VectorXd Q = Eigen::VectorXd::Zero(nq);
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(nq, nq);
    ancf_plate_forces(p, Eigen::VectorXd::Zero(nq), Eigen::VectorXd::Zero(nq), Q, &K, nullptr);
    const Eigen::VectorXd f = b.Pdm.transpose() * Eigen::Vector3d(0, 0, -g);
    std::vector<bool> held(static_cast<std::size_t>(nq), false);
    for (const PlateSupportRow& r : p.supports)
      for (int c = 0; c < 3; ++c)
        if (r.dir(c) != 0) held[static_cast<std::size_t>(r.index + c)] = true;
    std::vector<int> keep;
    for (int j = 0; j < nq; ++j)
      if (!held[static_cast<std::size_t>(j)]) keep.push_back(j);
    const int m = static_cast<int>(keep.size());
    Eigen::MatrixXd Kr(m, m);
    Eigen::VectorXd fr(m);
    for (int i = 0; i < m; ++i) {
      fr(i) = f(keep[static_cast<std::size_t>(i)]);
      for (int j = 0; j < m; ++j) Kr(i, j) = K(keep[static_cast<std::size_t>(i)], keep[static_cast<std::size_t>(j)]);
    }
    const Eigen::VectorXd yr = Kr.ldlt().solve(fr);
    Eigen::VectorXd y = Eigen::VectorXd::Zero(nq);
    for (int i = 0; i < m; ++i) y(keep[static_cast<std::size_t>(i)]) = yr(i);
    const double w = -y(12 * p.node(n / 2, n / 2) + 2);
    std::printf("clamped plate, uniform load, %d x %d elements: centre %.6e m, Kirchhoff %.6e m (%+.3f %%)\n", n, n, w, exact,
                100 * (w / exact - 1));
    EXPECT_NEAR(w / exact, 1.0, n == 8 ? 1e-3 : 1e-2);
    EXPECT_GT(w, previous);
    previous = w;
  }
}

// The clamped plate's weight deflects its centre about 1.6 thicknesses (its linear deflection
// 0.00126 q a^4 / D would be 4.1, Timoshenko's clamped-plate coefficient): membrane action carries
// most of the load. Against CalculiX with NLGEOM; the static analysis from the flat plate.
TEST(Plate, ClampedPlateLargeDeflectionMatchesCalculix) {
  Square s;
  s.E = 1e7;
  s.rho = 1000;
  const double g = 3.0;  // q = rho h g = 30 Pa
  const double q = s.rho * s.h * g, wlin = 0.00126 * q * std::pow(s.a, 4) / s.D();
  test::TempDir dir("plate_ccx");
  const double wc = calculix_centre_deflection(s, g, dir.path);
  for (const int n : {6, 8}) {
    const Model model = test::model_from(clamped_plate_json(s, n, g, R"({"analysis": "static"})"));
    Data data(model);
    for (const auto& note : initialize(model, data)) std::printf("note: %s\n", note.c_str());
    const double w = output(model, data, "centre")[2];
    std::printf("clamped plate, %d x %d elements: centre %.6f m (%.3f h; linear %.3f h), CalculiX S4 32 x 32 %.6f m (%+.3f %%)\n", n, n,
                w, -w / s.h, wlin / s.h, wc, 100 * (w / wc - 1));
    if (n == 8) {
      EXPECT_NEAR(w / wc, 1.0, 5e-3);
    }
  }
  EXPECT_GT(-wc, 1.5 * s.h);  // far beyond the linear range
  EXPECT_LT(-wc, 0.8 * wlin);
}

// A cantilever strip (1 m x 0.1 m, 8 x 1 elements, nu = 0) under a dead load P at its free edge
// (half at each corner node): with nu = 0 cylindrical bending decouples the width, and the plate
// is the elastica with EI = D b. Its tip against Bisshopp & Drucker's table ("Large deflection of
// cantilever beams", Quart. Appl. Math. 3, 1945) at P L^2 / (D b) = 1, 2, 5, within 0.2 %; the
// static analysis from the flat plate, without load stepping.
TEST(Plate, CantileverStripFollowsTheElastica) {
  const double E = 1e7, h = 0.01, b = 0.1, L = 1, D = E * h * h * h / 12;
  const double k[3] = {1, 2, 5}, u[3] = {0.05643, 0.16064, 0.38763}, w[3] = {0.30172, 0.49346, 0.71379};
  for (int i = 0; i < 3; ++i) {
    const double P = k[i] * D * b / (L * L);
    std::string forces;
    for (int j = 0; j < 2; ++j)
      forces += std::string(j ? ", " : "") + R"({"name": "P)" + std::to_string(j) + R"(", "type": "point_force", "body": "plate", "node": "n8_)" +
                std::to_string(j) + R"(", "table": {"t": [0, 1], "value": [[0, 0, )" + num(-P / 2) + "], [0, 0, " + num(-P / 2) + "]]}}";
    const Model model = test::model_from(R"({"bodies": [{"name": "plate", "type": "plate",
        "corners": [[0, 0, 0], [1, 0, 0], [1, 0.1, 0], [0, 0.1, 0]], "elements": [8, 1], "thickness": 0.01, "E": 1e7, "nu": 0,
        "rho": 1000, "supports": {"x0": "clamped"}}],
      "forces": [)" + forces + R"(], "solver": {"analysis": "static"},
      "outputs": [{"name": "tip", "type": "node_position", "body": "plate", "node": "n8_0"},
                  {"name": "tip1", "type": "node_position", "body": "plate", "node": "n8_1"}]})");
    Data data(model);
    for (const auto& note : initialize(model, data)) std::printf("note: %s\n", note.c_str());
    const auto tip = output(model, data, "tip"), tip1 = output(model, data, "tip1");
    const double tu = (L - tip[0]) / L, tw = -tip[2] / L;
    std::printf("strip P L^2 / (D b) = %g: u/L %.6f (table %.5f, %+.3f %%), w/L %.6f (table %.5f, %+.3f %%)\n", k[i], tu, u[i],
                100 * (tu / u[i] - 1), tw, w[i], 100 * (tw / w[i] - 1));
    EXPECT_NEAR(tu / u[i], 1.0, 2e-3);
    EXPECT_NEAR(tw / w[i], 1.0, 2e-3);
    EXPECT_NEAR(tip1[2], tip[2], 1e-9);  // cylindrical: both corners alike
  }
}

// A dynamic run with each integrator: the clamped plate (4 x 4 elements) settled under loads at
// its interior nodes shaped like its first mode (the product of 1/2, 1, 1/2 across each
// direction: little content of the higher symmetric modes), removed within the first step,
// vibrates at Leissa's first frequency; without damping the trapezoidal rule keeps its energy.
TEST(Plate, ReleasedClampedPlateVibratesAtLeissasFirstFrequency) {
  const Square s;
  const int n = 4;
  const double P = 20;  // N at the centre: a deflection of about 1e-3 h, linear
  const double w1 = 35.99 / (s.a * s.a) * std::sqrt(s.D() / (s.rho * s.h));
  for (const std::string integrator : {"trapezoidal", "generalized_alpha"}) {
    const std::string solver = R"({"end": 0.06, "step": 2e-4, "initial_equilibrium": true, "integrator": ")" + integrator + "\"" +
                               (integrator == "generalized_alpha" ? R"(, "spectral_radius": 0.9)" : "") + "}";
    std::string json = clamped_plate_json(s, n, 0, solver);
    std::string forces = R"("forces": [)";
    const double shape[3] = {0.5, 1, 0.5};
    for (int i = 1; i <= 3; ++i)
      for (int j = 1; j <= 3; ++j)
        forces += std::string(i + j > 2 ? ", " : "") + R"({"name": "P)" + std::to_string(i) + std::to_string(j) +
                  R"(", "type": "point_force", "body": "plate", "node": "n)" + std::to_string(i) + "_" + std::to_string(j) +
                  R"(", "table": {"t": [0, 1e-6, 1], "value": [[0, 0, )" + num(-P * shape[i - 1] * shape[j - 1]) +
                  R"(], [0, 0, 0], [0, 0, 0]]}})";
    json.replace(json.find("\"outputs\""), 9, forces + R"(], "outputs")");
    const Model model = test::model_from(json);
    Data data(model);
    initialize(model, data);
    const double z0 = output(model, data, "centre")[2];
    std::vector<double> crossings;
    double zprev = z0, tprev = data.state.t, e0 = 0, emax = 0;
    bool first = true;
    while (data.state.t < 0.06 - 1e-9) {
      step(model, data);
      const double z = output(model, data, "centre")[2];
      const auto e = output(model, data, "e");
      if (first) e0 = e[0] + e[1];
      first = false;
      emax = std::max(emax, std::abs(e[0] + e[1] - e0));
      if ((zprev < 0) != (z < 0)) crossings.push_back(tprev + (data.state.t - tprev) * zprev / (zprev - z));
      zprev = z;
      tprev = data.state.t;
    }
    ASSERT_GE(crossings.size(), 5u);
    const double period = 2 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
    const double w = 2 * M_PI / period;
    std::printf("%s: centre %.3e m, omega %.3f rad/s (Leissa %.3f, %+.3f %%), energy change %.2e of %.3e J\n", integrator.c_str(), z0, w,
                w1, 100 * (w / w1 - 1), emax, e0);
    EXPECT_LT(z0, 0);
    EXPECT_NEAR(w / w1, 1.0, 3e-3);
    if (integrator == "trapezoidal") {
      EXPECT_LT(emax, 1e-3 * std::abs(e0));
    }
  }
}

// A rigid body hung on the plate's centre node by a spherical joint (the constraint machinery)
// loads the plate with its weight alone: the static centre equals that of the weight applied as a
// point force there.
TEST(Plate, RigidBodyHungOnANodeLoadsItWithItsWeight) {
  const std::string plate = R"({"name": "plate", "type": "plate", "corners": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]],
      "elements": [4, 4], "thickness": 0.01, "E": 2.1e11, "nu": 0.3, "rho": 7850,
      "supports": {"x0": "clamped", "x1": "clamped", "y0": "clamped", "y1": "clamped"}})";
  const std::string tail = R"(, "solver": {"analysis": "static"},
    "outputs": [{"name": "c", "type": "node_position", "body": "plate", "node": "n2_2"}]})";
  const Model hung = test::model_from(R"({"gravity": [0, 0, -9.81], "bodies": [)" + plate + R"(,
      {"name": "bob", "type": "rigid", "mass": 50, "com": [0.5, 0.5, -0.1], "inertia": [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}],
    "joints": [{"name": "pin", "type": "spherical", "body1": "plate", "node1": "n2_2", "body2": "bob"}],
    "forces": [{"name": "spin", "type": "bushing", "body1": "ground", "body2": "bob", "at": [0.5, 0.5, -0.1],
                "stiffness": [0, 0, 0, 0, 0, 1]}])" + tail);
  const Model loaded = test::model_from(R"({"gravity": [0, 0, -9.81], "bodies": [)" + plate + R"(],
    "forces": [{"name": "W", "type": "point_force", "body": "plate", "node": "n2_2",
                "table": {"t": [0, 1], "value": [[0, 0, -490.5], [0, 0, -490.5]]}}])" + tail);
  Data dh(hung), dl(loaded);
  for (const auto& n : initialize(hung, dh)) std::printf("note: %s\n", n.c_str());
  initialize(loaded, dl);
  const auto ch = output(hung, dh, "c"), cl = output(loaded, dl, "c");
  std::printf("hung bob: centre z %.12f, weight as a point force: %.12f\n", ch[2], cl[2]);
  EXPECT_LT(cl[2], -1e-4);
  EXPECT_NEAR(ch[2], cl[2], 1e-9 * std::abs(cl[2]));
}

TEST(Plate, BadInputIsRefusedNamingTheField) {
  const std::string good = clamped_plate_json(Square{}, 4, 9.81, R"({"analysis": "static"})");
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    const auto at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return s.replace(at, from.size(), to);
  };
  test::expect_error(with("\"elements\": [4, 4]", "\"elements\": [0, 4]"), "bodies[0].elements", "at least 1");
  test::expect_error(with("\"elements\": [4, 4]", "\"elements\": [4]"), "bodies[0].elements", "[nx, ny]");
  test::expect_error(with("\"elements\": [4, 4]", "\"elements\": [20, 20]"), "bodies[0].elements", "at most");
  test::expect_error(with("[0, 1, 0]]", "[0, 1, 0.01]]"), "bodies[0].corners", "not in one plane");
  test::expect_error(with("[1, 1, 0]", "[1.2, 1, 0]"), "bodies[0].corners", "not a rectangle");
  test::expect_error(with("[1, 0, 0]", "[0, 0, 0]"), "bodies[0].corners", "coincident");
  test::expect_error(with("\"node\": \"n2_2\"", "\"node\": \"n5_2\""), "node", "has no node 'n5_2'");
  test::expect_error(with("\"x0\": \"clamped\"", "\"x0\": \"glued\""), "supports.x0", "unknown support");
  test::expect_error(with("\"x0\": \"clamped\"", "\"z0\": \"clamped\""), "supports", "z0");
  test::expect_error(with("\"nu\": 0.29999999999999999", "\"nu\": 0.5"), "bodies[0].nu", "(-1, 0.5)");
  test::expect_error(with("\"thickness\": 0.01", "\"thickness\": 0"), "bodies[0].thickness", "");
  test::expect_error(with("\"thickness\": 0.01", "\"thickness\": 0.7"), "bodies[0].thickness", "thin plate");
  test::expect_error(with("\"rho\": 7850", "\"rho\": 7850, \"section\": {}"), "bodies[0]", "section");
  const std::string joint = R"("joints": [{"name": "j", "type": "revolute", "body1": "ground", "body2": "plate", "node2": "n1_1",
                                             "axis": [1, 0, 0]}], "solver":)";
  test::expect_error(with("\"solver\":", joint), "type", "not supported");
  const std::string away = R"("joints": [{"name": "j", "type": "spherical", "body1": "ground", "body2": "plate", "at": [0, 0, 0]}], "solver":)";
  test::expect_error(with("\"solver\":", away), "joints[0]", "away from its nodes");
}

// ffr-sim: a static plate run writes its results; a plate with zero elements or non-planar
// corners is refused with exit status 2, the message naming the file and the field, and no
// results file.
TEST(Plate, FfrSimRunsAPlateOrRefusesItsBadInput) {
  test::TempDir dir("plate_cli");
  const std::string good = clamped_plate_json(Square{}, 4, 9.81, R"({"analysis": "static"})");
  const std::pair<std::string, std::string> bad[2] = {{"\"elements\": [4, 4]", "\"elements\": [4, 0]"},
                                                      {"[0, 1, 0]]", "[0, 1, 0.1]]"}};
  for (int k = -1; k < 2; ++k) {
    std::string json = good;
    if (k >= 0) json.replace(json.find(bad[k].first), bad[k].first.size(), bad[k].second);
    test::write_text(dir / "plate.json", json);
    std::filesystem::remove(dir / "out.h5");
    const auto r = test::run_ffr_sim((dir / "plate.json").string() + " -o " + (dir / "out.h5").string());
    std::printf("case %d: status %d\n%s\n", k, r.status, r.output.c_str());
    if (k < 0) {
      EXPECT_EQ(r.status, 0) << r.output;
      EXPECT_TRUE(std::filesystem::exists(dir / "out.h5"));
    } else {
      EXPECT_EQ(r.status, 2) << r.output;
      EXPECT_NE(r.output.find("plate.json"), std::string::npos) << r.output;
      EXPECT_NE(r.output.find(k == 0 ? "bodies[0].elements" : "bodies[0].corners"), std::string::npos) << r.output;
      EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
    }
  }
}
