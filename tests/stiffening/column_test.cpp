// Ke.M1 of a Craig-Bampton beam column (frame A at x = 0, interface B at x = L, both held by
// the fixed-interface modes), 40 shear-rigid 2-node beam elements, reduced by run_pipeline.
// B's axial constraint mode (mode 0) stretches the column uniformly: q_0 carries the tension
// N = EA q_0 phi_B,x / L, and q_0 Ke.M1[0] is then that tension's geometric stiffness on the
// clamped-clamped bending modes.
//
// References (Euler-Bernoulli beam, EI w'''' - N w'' = rho A omega^2 w, clamped ends):
//  - Galerkin with the beam's own first mode phi (Blevins, Formulas for Natural Frequency and
//    Mode Shape, 1979, table 8-1: beta L = 4.730040745, sigma = 0.982502215):
//      Ke.M1[0]_bb q_0 / Ke.M0_bb = N / P_b,  P_b = EI int phi''^2 / int phi'^2,
//    so omega^2(N) = omega^2(0) (1 + N / P_b).
//  - The exact first frequency under N: with s1^2, s2^2 = (sqrt(n^2 + 4 k^4) +- n) / 2,
//    n = N/EI, k^4 = rho A omega^2 / EI, the clamped-clamped characteristic equation
//      2 s1 s2 (1 - cosh s1L cos s2L) + (s1^2 - s2^2) sinh s1L sin s2L = 0
//    (derived from w = C1 cosh s1x + C2 sinh s1x + C3 cos s2x + C4 sin s2x; for N = 0 it is
//    cosh bL cos bL = 1; cf. Bokaian, J. Sound Vib. 142 (1990) 481-498).
#include "ffr/formats/validate.hpp"
#include "ffr/preproc/pipeline.hpp"
#include "../reduce/support.hpp"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <iostream>

using namespace ffr;

namespace {

constexpr double L = 1.0, E = 2.1e11, rho = 7850, A = 8e-5;
constexpr double Iy = 0.01 * 0.008 * 0.008 * 0.008 / 12, Iz = 0.008 * 0.01 * 0.01 * 0.01 / 12;

const formats::Sid& column() {
  static const formats::Sid sid = [] {
    test::TempDir dir("column");
    test::write_text(dir / "line.geo", R"(Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Line(1) = {1, 2};
Transfinite Curve{1} = 41; Physical Curve("beam") = {1}; Physical Point("a") = {1}; Physical Point("b") = {2};
)");
    test::write_text(dir / "column.json", R"({"geometry": "line.geo", "mesh": {"order": 1},
      "beams": [{"group": "beam", "E": 2.1e11, "nu": 0.3, "rho": 7850, "y_axis": [0, 1, 0],
                 "section": {"A": 8e-5, "Iy": 4.266666666666667e-10, "Iz": 6.666666666666667e-10, "J": 1e-9}}],
      "interfaces": [{"name": "A", "group": "a"}, {"name": "B", "group": "b"}],
      "output_nodes": [{"name": "mid", "at": [0.5, 0, 0]}],
      "reduction": {"method": "craig-bampton", "interfaces": ["A", "B"], "frame": "A", "modes": 4},
      "stiffening": true, "visual": false})");
    return preproc::run_pipeline(preproc::load_part(dir / "column.json"));
  }();
  return sid;
}

// The same column as a shell strip, 1 m x 50 mm x 2 mm, 40 x 2 QUAD4, nu = 0 so that B's axial
// constraint mode stretches it uniaxially (N_x = E t / L per unit q_0, N_y = 0): its first
// out-of-plane mode is the beam's, with A = b t and I = b t^3 / 12.
constexpr double kStripB = 0.05, kStripT = 0.002;

const formats::Sid& strip() {
  static const formats::Sid sid = [] {
    test::TempDir dir("strip");
    test::write_text(dir / "strip.geo", R"(Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 0.05, 0}; Point(4) = {0, 0.05, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 41; Transfinite Curve{2, 4} = 3; Transfinite Surface{1}; Recombine Surface{1};
Physical Surface("skin") = {1}; Physical Curve("a") = {4}; Physical Curve("b") = {2};
)");
    test::write_text(dir / "strip.json", R"({"geometry": "strip.geo", "mesh": {"order": 1},
      "shells": [{"group": "skin", "thickness": 0.002, "E": 2.1e11, "nu": 0.0, "rho": 7850}],
      "interfaces": [{"name": "A", "group": "a"}, {"name": "B", "group": "b"}],
      "output_nodes": [{"name": "mid", "at": [0.5, 0.025, 0]}],
      "reduction": {"method": "craig-bampton", "interfaces": ["A", "B"], "frame": "A", "modes": 4},
      "stiffening": true, "visual": false})");
    return preproc::run_pipeline(preproc::load_part(dir / "strip.json"));
  }();
  return sid;
}

// The clamped-clamped first mode and P_b / EI = int phi''^2 / int phi'^2 (composite Gauss).
double galerkin_buckling_over_EI() {
  const double b = 4.730040745 / L, s = 0.982502215;
  auto d1 = [&](double x) { return b * (std::sinh(b * x) + std::sin(b * x) - s * (std::cosh(b * x) - std::cos(b * x))); };
  auto d2 = [&](double x) { return b * b * (std::cosh(b * x) + std::cos(b * x) - s * (std::sinh(b * x) + std::sin(b * x))); };
  const double g[3] = {-0.7745966692414834, 0, 0.7745966692414834}, w[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  double i1 = 0, i2 = 0;
  const int n = 400;
  for (int e = 0; e < n; ++e)
    for (int p = 0; p < 3; ++p) {
      const double x = (e + 0.5 + 0.5 * g[p]) * L / n, wx = 0.5 * w[p] * L / n;
      i1 += wx * d1(x) * d1(x);
      i2 += wx * d2(x) * d2(x);
    }
  return i2 / i1;
}

// The exact first bending frequency [rad/s] under axial force N (tension > 0), by bisection on
// the characteristic equation between its first two roots.
double exact_omega(double EI, double N) {
  auto f = [&](double omega) {
    const double n = N / EI, k4 = rho * A * omega * omega / EI, r = std::sqrt(n * n + 4 * k4);
    const double s1 = std::sqrt((r + n) / 2), s2 = std::sqrt((r - n) / 2);
    return 2 * s1 * s2 * (1 - std::cosh(s1 * L) * std::cos(s2 * L)) + (s1 * s1 - s2 * s2) * std::sinh(s1 * L) * std::sin(s2 * L);
  };
  const double w0 = 4.730040745 * 4.730040745 * std::sqrt(EI / (rho * A)) / (L * L);
  double lo = 0.3 * w0, hi = 1.8 * w0;  // brackets only the first root for |N| <= P_b / 2
  const double flo = f(lo);
  EXPECT_LT(flo * f(hi), 0) << "bracket";
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    ((f(mid) < 0) == (flo < 0) ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

struct Bending {
  Eigen::Index mode;
  double EI;
};

// The first normal mode bending in z (about local y: Iy) and in y (Iz), told by the mid node.
std::vector<Bending> first_bending_modes(const formats::Sid& s) {
  const auto& mid = s.nodes[static_cast<std::size_t>(s.find_node("mid"))];
  std::vector<Bending> out;
  bool z = false, y = false;
  for (Eigen::Index k = 0; k < s.nq(); ++k) {
    if (s.refmod.mode_type[k] != formats::ModeType::Normal) continue;
    const bool in_z = std::abs(mid.phi(2, k)) > std::abs(mid.phi(1, k));
    if (in_z && !z) out.push_back({k, E * Iy}), z = true;
    if (!in_z && !y) out.push_back({k, E * Iz}), y = true;
  }
  return out;
}

}  // namespace

TEST(ColumnSelfStiffness, WrittenSymmetricAndValid) {
  const formats::Sid& s = column();
  ASSERT_EQ(s.nq(), 10);
  ASSERT_EQ(s.KeM1.size(), 10u);
  ASSERT_TRUE(s.stiffening.has_value()) << "the load-case members stay";
  const auto r = formats::validate(s);
  EXPECT_TRUE(r.ok());
  const auto* c = r.find("Ke.M1 symmetric in (i,j)");
  ASSERT_NE(c, nullptr);
  EXPECT_TRUE(c->applicable && c->pass);
  // Mode 0 is B's axial constraint mode.
  ASSERT_EQ(s.refmod.mode_type[0], formats::ModeType::Constraint);
  const auto& B = s.nodes[static_cast<std::size_t>(s.find_node("B"))];
  EXPECT_NEAR(B.phi(0, 0), 1.0, 1e-12);
}

TEST(ColumnSelfStiffness, AxialConstraintModeStiffensBendingByTheGalerkinFactor) {
  const formats::Sid& s = column();
  const double phiB = s.nodes[static_cast<std::size_t>(s.find_node("B"))].phi(0, 0);
  const double N_per_q = E * A * phiB / L;
  const double g = galerkin_buckling_over_EI();
  const auto modes = first_bending_modes(s);
  ASSERT_EQ(modes.size(), 2u);
  for (const auto& m : modes) {
    const double ratio = s.KeM1[0](m.mode, m.mode) / s.Ke(m.mode, m.mode);
    const double ref = N_per_q / (m.EI * g);
    std::cout << "beam mode " << m.mode << ": Ke.M1[0]_bb / Ke_bb = " << ratio << ", N / P_b = " << ref << "\n";
    EXPECT_NEAR(ratio / ref, 1.0, 0.01) << "mode " << m.mode << ": Ke.M1[0]_bb / Ke_bb against N / P_b";
  }
}

TEST(ColumnSelfStiffness, FirstFrequencyUnderTensionAndCompressionMatchesTheExactBeam) {
  const formats::Sid& s = column();
  const double phiB = s.nodes[static_cast<std::size_t>(s.find_node("B"))].phi(0, 0);
  const double g = galerkin_buckling_over_EI();
  // B held at the stretch q_0: the fixed-interface modes are the remaining coordinates.
  std::vector<Eigen::Index> nm;
  for (Eigen::Index k = 0; k < s.nq(); ++k)
    if (s.refmod.mode_type[k] == formats::ModeType::Normal) nm.push_back(k);
  for (const auto& m : first_bending_modes(s))
    for (double p : {0.3, -0.3}) {
      const double N = p * m.EI * g, q0 = N * L / (E * A * phiB);
      Eigen::MatrixXd K(nm.size(), nm.size()), M(nm.size(), nm.size());
      for (std::size_t i = 0; i < nm.size(); ++i)
        for (std::size_t j = 0; j < nm.size(); ++j) {
          K(i, j) = s.Ke(nm[i], nm[j]) + q0 * s.KeM1[0](nm[i], nm[j]);
          M(i, j) = s.Me(nm[i], nm[j]);
        }
      const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M);
      // The plane of mode m: its eigenvector is the one dominated by m.
      Eigen::Index best = 0;
      const auto pos = std::find(nm.begin(), nm.end(), m.mode) - nm.begin();
      for (Eigen::Index c = 0; c < es.eigenvectors().cols(); ++c)
        if (std::abs(es.eigenvectors()(pos, c)) > std::abs(es.eigenvectors()(pos, best))) best = c;
      const double w = std::sqrt(es.eigenvalues()(best));
      const double w_exact = exact_omega(m.EI, N), w0 = exact_omega(m.EI, 0);
      std::cout << "EI " << m.EI << ", N/P_b " << p << ": omega " << w << ", exact " << w_exact << " (unloaded " << w0 << ")\n";
      EXPECT_NEAR(w / w_exact, 1.0, 0.01) << "EI " << m.EI << ", N / P_b = " << p;
      EXPECT_GT(std::abs(w_exact / w0 - 1), 0.1) << "the effect is large enough to be tested";
    }
}

TEST(ShellStripSelfStiffness, AxialConstraintModeStiffensBendingByTheGalerkinFactor) {
  const formats::Sid& s = strip();
  ASSERT_EQ(s.KeM1.size(), static_cast<std::size_t>(s.nq()));
  EXPECT_TRUE(formats::validate(s).ok());
  const auto& B = s.nodes[static_cast<std::size_t>(s.find_node("B"))];
  ASSERT_EQ(s.refmod.mode_type[0], formats::ModeType::Constraint);
  ASSERT_NEAR(B.phi(0, 0), 1.0, 1e-12);
  // The first normal mode bends out of plane (z) at mid-span.
  const auto& mid = s.nodes[static_cast<std::size_t>(s.find_node("mid"))];
  Eigen::Index b = 0;
  while (s.refmod.mode_type[b] != formats::ModeType::Normal) ++b;
  ASSERT_GT(std::abs(mid.phi(2, b)), 10 * mid.phi.col(b).head<2>().norm());
  const double EI = E * kStripB * kStripT * kStripT * kStripT / 12;
  const double N_per_q = E * kStripB * kStripT * B.phi(0, 0) / L;
  const double ratio = s.KeM1[0](b, b) / s.Ke(b, b);
  std::cout << "shell strip: Ke.M1[0]_bb / Ke_bb = " << ratio << ", N / P_b = " << N_per_q / (EI * galerkin_buckling_over_EI()) << "\n";
  EXPECT_NEAR(ratio / (N_per_q / (EI * galerkin_buckling_over_EI())), 1.0, 0.01);
}
