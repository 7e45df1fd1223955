// Geometric stiffening of a solid (TET10) cantilever, 1 m long, 20 mm thick (z) and 60 mm
// wide (y), clamped at x = 0, reduced once with "stiffening": true and a gravity preload.
// All references are the power-series solutions of beam_series.hpp, themselves checked
// against the published tables in series_test.cpp (Wright et al. 1982; Blevins 1979;
// Greenhill's self-weight buckling).
#include "beam_series.hpp"
#include "ffr/formats/campbell.hpp"
#include "ffr/formats/sid_io.hpp"
#include "ffr/preproc/pipeline.hpp"
#include "../reduce/support.hpp"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

using namespace ffr;

namespace {

constexpr double L = 1.0, h = 0.02, b = 0.06, E = 2.1e11, rho = 7850;
constexpr double A = b * h, I_flap = b * h * h * h / 12, I_lag = h * b * b * b / 12;
constexpr double g_scaled = 2675.0;  // scaled gravity: self-weight parameter gamma = 3

double unit(double I) { return std::sqrt(E * I / (rho * A * L * L * L * L)); }  // rad/s per omega_bar

const formats::Sid& beam() {
  static const formats::Sid sid = [] {
    test::TempDir dir("stiff");
    test::write_text(dir / "beam.geo", R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1.0, 0.06, 0.02};
Physical Volume("body") = {1};
Physical Surface("clamp") = Surface In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};
Physical Surface("end") = Surface In BoundingBox{1 - 1e-6, -1, -1, 1 + 1e-6, 1, 1};
)");
    test::write_text(dir / "beam.json", R"({"geometry": "beam.geo", "mesh": {"size": 0.01, "order": 2},
      "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}],
      "interfaces": [{"name": "root", "group": "clamp"}, {"name": "tip", "group": "end"}],
      "reduction": {"method": "clamped", "interface": "root", "modes": 12},
      "stiffening": true, "preload": {"gravity": [2675.0, 0, 0]}, "visual": false})");
    return preproc::run_pipeline(preproc::load_part(dir / "beam.json"));
  }();
  return sid;
}

// The same cantilever of 2-node Timoshenko beam elements (Iy = b h^3/12 bends in z, the flap):
// writes its part file into `dir` and returns the path.
std::filesystem::path write_beam_element_part(const test::TempDir& dir, bool stiffening) {
  test::write_text(dir / "line.geo", R"(Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Line(1) = {1, 2};
Transfinite Curve{1} = 41; Physical Curve("beam") = {1}; Physical Point("root") = {1}; Physical Point("end") = {2};
)");
  test::write_text(dir / "line.json", std::string(R"({"geometry": "line.geo", "mesh": {"order": 1},
      "beams": [{"group": "beam", "E": 2.1e11, "nu": 0.3, "rho": 7850, "y_axis": [0, 1, 0],
                 "section": {"A": 1.2e-3, "Iy": 4e-8, "Iz": 3.6e-7, "J": 1.5e-7}}],
      "interfaces": [{"name": "root", "group": "root"}, {"name": "tip", "group": "end"}],
      "reduction": {"method": "clamped", "interface": "root", "modes": 12},
      "stiffening": )") + (stiffening ? "true" : "false") + R"(, "visual": false})");
  return dir / "line.json";
}

const formats::Sid& beam_elements() {
  static const formats::Sid sid = [] {
    test::TempDir dir("stiffbeam");
    return preproc::run_pipeline(preproc::load_part(write_beam_element_part(dir, true)));
  }();
  return sid;
}

// Flap and lag frequencies of a SID spinning about z, against the power series.
void check_rotating(const formats::Sid& s, const char* what) {
  const double uf = unit(I_flap), ul = unit(I_lag);
  for (double sf : {0.0, 2.0, 4.0, 6.0}) {
    const double Omega = sf * uf;
    const auto c = formats::campbell(s, 2, {Omega});
    const auto& f = c.frequency_hz[0];
    // Flapwise (out of the plane of rotation): Southwell stiffening.
    const double flap_ref = test::cantilever_frequencies(test::rotating(sf), 1)[0] * uf;
    EXPECT_NEAR(2 * M_PI * f[0] / flap_ref, 1.0, 0.01) << what << ": first flap at speed " << sf;
    // Lagwise (in the plane): the same stiffening minus the centrifugal softening,
    // omega_lag^2 = omega_flaplike^2 - Omega^2 (Wright et al. 1982, sec. 4).
    const double sl = Omega / ul;
    const double like = test::cantilever_frequencies(test::rotating(sl), 1)[0] * ul;
    const double lag_ref = std::sqrt(like * like - Omega * Omega);
    EXPECT_NEAR(2 * M_PI * f[1] / lag_ref, 1.0, 0.01) << what << ": first lag at speed " << sf;
    // Without the softening term (Oe.M1 removed) the lag frequency is the stiffened one.
    formats::Sid no_soft = s;
    for (auto& m : no_soft.Oe.M1) m.setZero();
    const auto c2 = formats::campbell(no_soft, 2, {Omega});
    EXPECT_NEAR(2 * M_PI * c2.frequency_hz[0][1] / like, 1.0, 0.01) << what << ": lag without softening at speed " << sf;
  }
}

// Frequencies [rad/s] of (Ke + dK) q = w^2 Me q, ascending.
Eigen::VectorXd omegas(const formats::Sid& s, const Eigen::MatrixXd& dK) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(s.Ke + dK, s.Me);
  return es.eigenvalues().cwiseMax(0).cwiseSqrt();
}

// sum_c x_c K0[k](i, c) as a matrix (i, k).
template <class Stack>
Eigen::MatrixXd contract(const Stack& K0, int col) {
  const Eigen::Index nq = static_cast<Eigen::Index>(K0.size());
  Eigen::MatrixXd out(nq, nq);
  for (Eigen::Index k = 0; k < nq; ++k) out.col(k) = K0[static_cast<std::size_t>(k)].col(col);
  return out;
}

}  // namespace

TEST(SolidBeamStiffening, StiffeningMatricesAreSymmetricAndStiffenUnderTension) {
  const auto& st = *beam().stiffening;
  for (int c = 0; c < 6; ++c) {
    const Eigen::MatrixXd K = contract(st.K0om, c);
    EXPECT_LT((K - K.transpose()).cwiseAbs().maxCoeff(), 1e-9 * K.cwiseAbs().maxCoeff()) << "K0om column " << c;
  }
  // Spin about z pulls the beam (along x) outwards: K0om_zz is positive definite on bending.
  const Eigen::MatrixXd Kzz = contract(st.K0om, formats::kZZ);
  EXPECT_GT(Kzz(0, 0), 0.0);
  // A frame acceleration +x loads the clamped beam like gravity -x: compression, so K0t_x < 0.
  EXPECT_LT(contract(st.K0t, 0)(0, 0), 0.0);
}

TEST(SolidBeamStiffening, RotatingCantileverFlapAndLagFrequencies) { check_rotating(beam(), "TET10 solid"); }

TEST(BeamElementStiffening, RotatingCantileverFlapAndLagFrequencies) { check_rotating(beam_elements(), "beam elements"); }

TEST(SolidBeamStiffening, AxialEndForceTensionAndCompression) {
  const formats::Sid& s = beam();
  const auto& tip = s.stiffening->interfaces;
  ASSERT_EQ(tip.size(), 1u);
  const double uf = unit(I_flap), pcr = M_PI * M_PI / 4;
  for (double p : {0.5 * pcr, -0.5 * pcr}) {
    const double P = p * E * I_flap / (L * L);
    const Eigen::VectorXd w = omegas(s, P * contract(tip[0].K0F, 0));
    const double ref = test::cantilever_frequencies(test::end_force(p), 1)[0] * uf;
    EXPECT_NEAR(w(0) / ref, 1.0, 0.01) << "end force p = " << p << " (" << (p > 0 ? "tension" : "compression") << ")";
  }
}

TEST(SolidBeamStiffening, HangingAndStandingUnderGravity) {
  const formats::Sid& s = beam();
  const double uf = unit(I_flap);
  const double gamma = rho * A * g_scaled * L * L * L / (E * I_flap);
  ASSERT_NEAR(gamma, 3.0, 0.01);
  // Gravity +x (hanging from the clamp, tension) acts like a frame acceleration -x.
  const Eigen::MatrixXd K0tx = contract(s.stiffening->K0t, 0);
  const double hang_ref = test::cantilever_frequencies(test::self_weight(gamma), 1)[0] * uf;
  const double stand_ref = test::cantilever_frequencies(test::self_weight(-gamma), 1)[0] * uf;
  EXPECT_NEAR(omegas(s, -g_scaled * K0tx)(0) / hang_ref, 1.0, 0.01) << "hanging";
  EXPECT_NEAR(omegas(s, +g_scaled * K0tx)(0) / stand_ref, 1.0, 0.01) << "standing";
  // The preload in the part file (gravity +x) gives the same prestress through ksigma.
  EXPECT_NEAR(omegas(s, s.ksigma.M1)(0) / hang_ref, 1.0, 0.01) << "prestress (ksigma)";
  const double at_rest = test::cantilever_frequencies({}, 1)[0] * uf;
  EXPECT_GT(hang_ref, 1.05 * at_rest);   // the effect is large enough to be tested
  EXPECT_LT(stand_ref, 0.95 * at_rest);
}

TEST(BeamElementStiffening, OffMeansNoStiffeningGroupAndTheLinearCampbellDiagram) {
  // The beam-element cantilever reduced again with "stiffening": false: the file has no
  // /stiffening group, the modes are unchanged, and the Campbell diagram keeps only the
  // centrifugal softening (its frequencies fall below the stiffened ones under spin).
  test::TempDir dir("stiffoff");
  const auto part = write_beam_element_part(dir, false);
  const auto out = dir / "off.sid.h5";
  const auto r = test::run(test::bin("ffr-reduce").string() + " " + part.string() + " -o " + out.string() + " --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(test::run("h5ls " + out.string()).output.find("sid"), std::string::npos);
  EXPECT_EQ(test::run("h5ls " + out.string()).output.find("stiffening"), std::string::npos) << "no /stiffening group";
  const formats::Sid off = formats::read_sid(out);
  EXPECT_FALSE(off.stiffening.has_value());
  const formats::Sid& on = beam_elements();
  ASSERT_EQ(off.nq(), on.nq());
  for (Eigen::Index k = 0; k < on.nq(); ++k) EXPECT_NEAR(off.refmod.frequency_hz(k) / on.refmod.frequency_hz(k), 1.0, 1e-9);
  const double w = 3 * unit(I_flap);  // omega_bar = 3 about z (lag plane softens, flap stiffens)
  const auto c_on = formats::campbell(on, 2, {w}), c_off = formats::campbell(off, 2, {w});
  EXPECT_LT(c_off.frequency_hz[0][0], c_on.frequency_hz[0][0]);
}
