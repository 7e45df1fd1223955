// The runtime's geometric stiffening against an independent geometrically exact beam (the
// planar Reissner/Simo beam of reissner_beam.hpp, its own elements and time integration) and
// against Euler's buckling load.
//
// Sources: Euler's column (a pinned-pinned Euler-Bernoulli beam under an end load P vibrates
// at f0 sqrt(1 - P/Pcr), Pcr = pi^2 EI / L^2; e.g. S. Timoshenko, D. H. Young, W. Weaver,
// "Vibration Problems in Engineering", 4th ed., Wiley 1974, sec. 5.13); the flexible
// slider-crank of B. Simeon, "Modelling a flexible slider crank mechanism by a mixed system of
// DAEs and PDEs", Math. Modelling of Systems 2 (1996) 1-18, and "Computational Flexible
// Multibody Dynamics", Springer 2013 (crank 0.15 m at 150 rad/s, rod 0.3 m, 8 x 8 mm steel,
// slider of half the rod's mass).
#include "crank_runs.hpp"
#include "reissner_beam.hpp"
#include "simeon_rod.hpp"
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

using namespace ffr::runtime;

namespace {

using D = test::SimeonData;

// The Simeon rod as a Reissner beam: 8 x 8 mm steel, shear-rigid in effect (GA = 100 EA: the
// runtime's rod and Euler's column are Euler-Bernoulli beams).
test::ReissnerBeam simeon_beam(int n) {
  test::ReissnerBeam b;
  const double A = D::BB * D::HH, I = D::BB * std::pow(D::HH, 3) / 12;
  b.EA = D::EE * A;
  b.GA = 100 * b.EA;
  b.EI = D::EE * I;
  b.rhoA = D::RHO * A;
  b.rhoI = D::RHO * I;
  b.L = D::L2;
  b.n = n;
  return b;
}

// Mean period of a signal from its upward zero crossings (linear interpolation).
double mean_period(const std::vector<double>& t, const std::vector<double>& s) {
  std::vector<double> up;
  for (std::size_t i = 1; i < s.size(); ++i)
    if (s[i - 1] < 0 && s[i] >= 0) up.push_back(t[i - 1] + (t[i] - t[i - 1]) * (-s[i - 1]) / (s[i] - s[i - 1]));
  if (up.size() < 2) return NAN;
  return (up.back() - up.front()) / static_cast<double>(up.size() - 1);
}

// ---- Euler's column -------------------------------------------------------------------------

// The oracle: pinned at s = 0, roller at s = L under the dead end load -P along x, started in
// its compressed equilibrium (N = -P exactly in a Reissner beam) with a small first-mode bow.
double oracle_column_frequency(double P, int n) {
  const test::ReissnerBeam b = simeon_beam(n);
  test::BeamIntegrator in(b);
  const int N = b.n;
  auto fixed = [](double) { return Eigen::Vector3d::Zero(); };
  in.prescribed = {{0, fixed}, {1, fixed}, {3 * N + 1, fixed}};
  in.load = [&](double) {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(b.ndof());
    f(3 * N) = -P;
    return f;
  };
  Eigen::VectorXd u = b.reference();
  const double a = 1e-5;
  for (int i = 0; i <= N; ++i) {
    const double s = b.L * i / N;
    u(3 * i) = s * (1 - P / b.EA);
    u(3 * i + 1) = a * std::sin(M_PI * s / b.L);
    u(3 * i + 2) = std::atan(a * M_PI / b.L * std::cos(M_PI * s / b.L) / (1 - P / b.EA));
  }
  in.start(0, u, Eigen::VectorXd::Zero(b.ndof()));
  const double f_est = M_PI / (2 * b.L * b.L) * std::sqrt(b.EI / b.rhoA) * std::sqrt(std::max(0.05, 1 - P / (M_PI * M_PI * b.EI / (b.L * b.L))));
  const double h = 1 / (f_est * 200);
  std::vector<double> t, y;
  for (int k = 0; k < 200 * 6; ++k) {
    in.step(h);
    t.push_back(in.t);
    y.push_back(in.u(3 * (N / 2) + 1));
  }
  return 1 / mean_period(t, y);
}

// The runtime: the Simeon rod (two pinned-pinned bending modes, two axial modes) with its Ke/M1,
// pinned at A to the ground, at B to a slider on a guide along x loaded by -P, started in the
// compressed state with a small first-mode bow.
double runtime_column_frequency(double P, bool stiffening) {
  test::TempDir dir("column");
  ffr::formats::Sid sid = test::simeon_rod_sid();
  sid.KeM1 = test::simeon_rod_ke_m1();
  test::write_sid_file(sid, dir / "rod.sid.h5");
  const double EA = D::EE * D::BB * D::HH;
  // u = -P x / EA is exactly (a3 / 2 + a4) (-P L / EA) in the axial shapes.
  const double q4 = -P * D::L2 / EA, q3 = q4 / 2;
  const double K11 = sid.Ke(0, 0), M11 = sid.Me(0, 0);
  const double f0 = std::sqrt(K11 / M11) / (2 * M_PI);
  const double h = 1 / (f0 * std::sqrt(std::max(0.05, 1 - P / (M_PI * M_PI * D::EE * D::BB * std::pow(D::HH, 3) / 12 / (D::L2 * D::L2))))) / 400;
  char json[4096];
  std::snprintf(json, sizeof json, R"({
  "bodies": [
    {"name": "rod", "type": "flexible", "sid": "rod.sid.h5", "stiffening": %s,
     "modal_coordinates": [1e-5, 0, %.17g, %.17g]},
    {"name": "slider", "type": "rigid", "mass": %.17g, "com": [%.17g, 0, 0],
     "inertia": [[1e-6, 0, 0], [0, 1e-6, 0], [0, 0, 1e-6]]}
  ],
  "joints": [
    {"name": "pin", "type": "revolute", "body1": "ground", "body2": "rod", "node2": "A", "axis": [0, 0, 1]},
    {"name": "wrist", "type": "revolute", "body1": "rod", "body2": "slider", "node1": "B", "axis": [0, 0, 1]},
    {"name": "guide", "type": "prismatic", "body1": "ground", "body2": "slider", "at": [%.17g, 0, 0], "axis": [1, 0, 0]}
  ],
  "forces": [{"type": "point_force", "body": "slider", "table": {"t": [0, 1], "value": [[%.17g, 0, 0], [%.17g, 0, 0]]}}],
  "solver": {"end": %.17g, "step": %.17g}
})",
                stiffening ? "true" : "false", q3, q4, D::M3, D::L2 + q4, D::L2 + q4, -P, -P, 8 * 400 * h, h);
  const Model model = test::model_from(json, dir.path);
  Data data(model);
  initialize(model, data);
  std::vector<double> t, y;
  const int o = model.bodies[0].offset;
  for (std::int64_t i = 0; i < step_count(model); ++i) {
    step(model, data);
    t.push_back(data.state.t);
    y.push_back(data.state.q(o + 12));
  }
  return 1 / mean_period(t, y);
}

}  // namespace

TEST(StiffeningOracle, EulerColumnOracleFrequencyFallsAsSqrtOneMinusPOverPcr) {
  const test::ReissnerBeam b = simeon_beam(80);
  const double Pcr = M_PI * M_PI * b.EI / (b.L * b.L);
  const double f0_exact = M_PI / (2 * b.L * b.L) * std::sqrt(b.EI / b.rhoA);
  const double f0 = oracle_column_frequency(0, 80);
  std::printf("oracle: f0 %.4f Hz (Euler-Bernoulli %.4f Hz, %.3f %%)\n", f0, f0_exact, 100 * (f0 / f0_exact - 1));
  EXPECT_NEAR(f0 / f0_exact, 1, 0.01);
  for (const double r : {0.5, 0.9}) {
    const double f = oracle_column_frequency(r * Pcr, 80);
    std::printf("oracle: P = %.1f Pcr: f / f0 = %.5f, Euler %.5f (%.3f %%)\n", r, f / f0, std::sqrt(1 - r),
                100 * (f / f0 / std::sqrt(1 - r) - 1));
    EXPECT_NEAR(f / f0 / std::sqrt(1 - r), 1, 0.01);
  }
}

TEST(StiffeningOracle, EulerColumnRuntimeWithKeM1FrequencyFallsAsSqrtOneMinusPOverPcr) {
  const double EI = D::EE * D::BB * std::pow(D::HH, 3) / 12;
  const double Pcr = M_PI * M_PI * EI / (D::L2 * D::L2);
  const double f0 = runtime_column_frequency(0, true);
  for (const double r : {0.5, 0.9}) {
    const double f = runtime_column_frequency(r * Pcr, true);
    const double f_off = runtime_column_frequency(r * Pcr, false);
    std::printf("runtime: P = %.1f Pcr: f / f0 = %.5f with Ke/M1, Euler %.5f (%.3f %%); without stiffening %.5f\n", r,
                f / f0, std::sqrt(1 - r), 100 * (f / f0 / std::sqrt(1 - r) - 1), f_off / f0);
    EXPECT_NEAR(f / f0 / std::sqrt(1 - r), 1, 0.01);
  }
}

// ---- Simeon's slider-crank ------------------------------------------------------------------

namespace {
// The first revolution, rounded to whole steps of 1e-5 s.
const double kRevolution = std::round(2 * M_PI / D::OMEGA / 1e-5) * 1e-5;
}  // namespace

// Simeon's rod (its two bending and two axial shape functions, with their Ke/M1) over the first
// crank revolution against the Reissner beam: the midpoint's deflection from the chord within a
// few percent of its peak, with the slider of half the rod's mass and with a (nearly) massless
// slider. The rod's axial force reaches some 5 % of its Euler load here.
TEST(StiffeningOracle, SimeonSliderCrankRodMidpointMatchesTheGeometricallyExactBeam) {
  test::TempDir dir("crank_oracle");
  ffr::formats::Sid sid = test::simeon_rod_sid();
  sid.KeM1 = test::simeon_rod_ke_m1();
  test::write_sid_file(sid, dir / "rod.sid.h5");
  const double h = 1e-5;
  for (const double ms : {D::M3, 1e-3 * D::M3}) {
    const test::CrankTrace ref = test::oracle_crank(simeon_beam(40), ms, h, kRevolution);
    const test::CrankTrace on = test::runtime_crank(dir.path, "rod.sid.h5", ms, true, h, kRevolution);
    const test::CrankTrace off = test::runtime_crank(dir.path, "rod.sid.h5", ms, false, h, kRevolution);
    const double e_on = test::worst_relative(on, ref), e_off = test::worst_relative(off, ref);
    std::printf("slider %.4g kg: oracle peak %.4e m; runtime with Ke/M1 peak %.4e (worst difference %.2f %% of the peak), "
                "without %.4e (%.2f %%)\n",
                ms, ref.peak(), on.peak(), 100 * e_on, off.peak(), 100 * e_off);
    EXPECT_LT(e_on, 0.05);
  }
}

// ---- A rotating beam with a tip mass --------------------------------------------------------

namespace {

// Spin-up of the hub: the rate rises smoothly from 0 to W over T, then stays.
struct SpinUp {
  double W, T;
  Eigen::Vector3d operator()(double t) const {
    if (t < T)
      return {0.5 * W * (t - T / M_PI * std::sin(M_PI * t / T)), 0.5 * W * (1 - std::cos(M_PI * t / T)),
              0.5 * W * M_PI / T * std::sin(M_PI * t / T)};
    return {0.5 * W * T + W * (t - T), W, 0};
  }
};

struct TipRun {
  std::vector<double> y;  // the tip's deflection in the hub's rotating frame (in the plane)
  double peak() const {
    double p = 0;
    for (double v : y) p = std::max(p, std::abs(v));
    return p;
  }
};

ffr::formats::synthetic::ChainParams blade_params() {
  ffr::formats::synthetic::ChainParams p;
  p.points = 41;
  p.length = 1.0;
  p.mass = 1.0;
  p.EA = 1e6;
  p.EIy = p.EIz = 1000;
  p.clamped = true;
  p.modes = 6;
  p.stiffening = true;
  return p;
}

// The oracle: clamped at the hub (its node 0 held at the origin, its rotation prescribed), the
// tip mass a point mass at the last node.
TipRun oracle_blade(const SpinUp& spin, double tip_mass, double h, double end) {
  const auto p = blade_params();
  test::ReissnerBeam b;
  b.EA = p.EA;
  b.GA = 100 * p.EA;
  b.EI = p.EIz;
  b.rhoA = p.mass / p.length;
  b.rhoI = 0;  // the chain's points carry no rotary inertia
  b.L = p.length;
  b.n = p.points - 1;
  test::BeamIntegrator in(b);
  const int N = b.n;
  auto held = [](double) { return Eigen::Vector3d::Zero(); };
  in.prescribed = {{0, held}, {1, held}, {2, spin}};
  in.M(3 * N, 3 * N) += tip_mass;
  in.M(3 * N + 1, 3 * N + 1) += tip_mass;
  in.start(0, b.reference(), Eigen::VectorXd::Zero(b.ndof()));
  TipRun r;
  for (int k = 0; k < static_cast<int>(std::lround(end / h)); ++k) {
    in.step(h);
    const double th = spin(in.t)(0);
    const Eigen::Vector2d tip = in.u.segment<2>(3 * N);
    r.y.push_back(-std::sin(th) * tip.x() + std::cos(th) * tip.y());
  }
  return r;
}

// tip_on_bushing: the tip mass held by a stiff 6-DOF bushing (a force element) at the blade's
// node B instead of a spherical joint; its load reaches the blade's interface the same way.
TipRun runtime_blade(const SpinUp& spin, double tip_mass, bool stiffening, double h, double end, bool tip_on_bushing = false) {
  test::TempDir dir("blade");
  auto chain = ffr::formats::synthetic::spring_chain(blade_params());
  test::write_sid_file(chain.sid, dir / "blade.sid.h5");
  std::string t, v;
  for (int k = 0; k <= static_cast<int>(std::lround((end + 0.01) / 1e-3)); ++k) {
    char a[64], c[64];
    std::snprintf(a, sizeof a, "%s%.17g", k ? ", " : "", k * 1e-3);
    std::snprintf(c, sizeof c, "%s%.17g", k ? ", " : "", spin(k * 1e-3)(0));
    t += a;
    v += c;
  }
  std::string json = R"({
  "bodies": [
    {"name": "hub", "type": "rigid", "mass": 1.0, "com": [0, 0, 0], "inertia": [[0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.01]]},
    {"name": "blade", "type": "flexible", "sid": "blade.sid.h5", "stiffening": STIFF},
    {"name": "tip", "type": "rigid", "mass": MASS, "com": [1, 0, 0], "position": [1, 0, 0],
     "inertia": [[1e-4, 0, 0], [0, 1e-4, 0], [0, 0, 1e-4]]}
  ],
  "joints": [
    {"name": "hinge", "type": "revolute", "body1": "ground", "body2": "hub", "at": [0, 0, 0], "axis": [0, 0, 1]},
    {"name": "clamp", "type": "fixed", "body1": "hub", "body2": "blade", "node2": "A", "axis": [0, 0, 1]},
    {"name": "tip_joint", "type": "spherical", "body1": "blade", "body2": "tip", "node1": "B"}
  ],
  "motions": [{"joint": "hinge", "table": {"t": [TIMES], "value": [VALUES], "interpolation": "spline"}}],
  "solver": {"end": END, "step": STEP}
})";
  if (tip_on_bushing) {
    // 1e7 N/m (the tip's radial stretch ~50 um under its ~450 N pull), 5 % damping of the
    // tip's ~700 Hz mode on the bushing; no rotational stiffness (a spherical joint has none).
    const std::string joint = R"(,
    {"name": "tip_joint", "type": "spherical", "body1": "blade", "body2": "tip", "node1": "B"})";
    json.replace(json.find(joint), joint.size(), "");
    const std::string motions = R"(  "motions")";
    json.replace(json.find(motions), motions.size(),
                 R"(  "forces": [{"type": "bushing", "body1": "blade", "node1": "B", "body2": "tip",
               "stiffness": [1e7, 1e7, 1e7, 0, 0, 0], "damping": [224, 224, 224, 0, 0, 0]}],
  "motions")");
  }
  auto put = [&](const std::string& key, const std::string& val) { json.replace(json.find(key), key.size(), val); };
  char num[64];
  put("STIFF", stiffening ? "true" : "false");
  std::snprintf(num, sizeof num, "%.17g", tip_mass);
  put("MASS", num);
  put("TIMES", t);
  put("VALUES", v);
  std::snprintf(num, sizeof num, "%.17g", end);
  put("END", num);
  std::snprintf(num, sizeof num, "%.17g", h);
  put("STEP", num);
  const Model model = test::model_from(json, dir.path);
  Data data(model);
  initialize(model, data);
  const Body& tip = model.bodies[2];
  TipRun r;
  for (std::int64_t i = 0; i < step_count(model); ++i) {
    step(model, data);
    const double th = spin(data.state.t)(0);
    const Eigen::Vector3d p = data.state.q.segment<3>(tip.offset);
    r.y.push_back(-std::sin(th) * p.x() + std::cos(th) * p.y());
  }
  return r;
}

}  // namespace

// A clamped blade (EI 1000 N m^2, 1 kg/m, 1 m: 18 Hz) with a 0.5 kg tip mass on a spherical
// joint, spun up to 30 rad/s in 0.5 s: the tip mass's centrifugal pull (some 450 N, 0.45 times
// EI/L^2) reaches the blade only through the joint at its tip interface (K0F); the tip deflects
// by a few percent of the length. The tip's
// in-plane deflection in the hub frame against the Reissner beam, with the hub's rotation
// prescribed (the classic spin-up of T. R. Kane, R. R. Ryan, A. K. Banerjee, "Dynamics of a
// cantilever beam attached to a moving base", J. Guidance 10 (1987), with a tip mass).
TEST(StiffeningOracle, SpunUpBladeWithTipMassMatchesTheGeometricallyExactBeam) {
  const SpinUp spin{30.0, 0.5};
  const double h = 2e-4, end = 1.0, mt = 0.5;
  const TipRun ref = oracle_blade(spin, mt, h, end);
  const TipRun on = runtime_blade(spin, mt, true, h, end);
  const TipRun off = runtime_blade(spin, mt, false, h, end);
  auto worst = [&](const TipRun& a) {
    double w = 0;
    for (std::size_t i = 0; i < std::min(a.y.size(), ref.y.size()); ++i) w = std::max(w, std::abs(a.y[i] - ref.y[i]));
    return w / ref.peak();
  };
  std::printf("blade: oracle peak tip deflection %.4e m; runtime stiffened %.4e (worst difference %.2f %% of the peak); "
              "unstiffened %.4e (%.2f %%)\n",
              ref.peak(), on.peak(), 100 * worst(on), off.peak(), 100 * worst(off));
  EXPECT_LT(worst(on), 0.05);
}

// The 6 mm round steel rod of GitHub issue 37 (0.3 m, 0.0668 kg; its axial force reaches 10-30 %
// of its Euler load of 1.4 kN) with free-free modes: the synthetic chain of formats/synthetic
// (41 lumped points on Euler-Bernoulli segments, its lowest 8 elastic modes, with its load cases,
// K0F/K0M at both ends and Ke/M1), against the Reissner beam of the same section, over the first
// revolution.
TEST(StiffeningOracle, FreeFreeRoundRodSliderCrankMatchesTheGeometricallyExactBeam) {
  const double E = 2.0e11, rho = 7870, d = 0.006, L = 0.3;
  const double A = M_PI * d * d / 4, I = M_PI * std::pow(d, 4) / 64, m = rho * A * L;
  ffr::formats::synthetic::ChainParams p;
  p.points = 41;
  p.length = L;
  p.mass = m;
  p.EA = E * A;
  p.EIy = p.EIz = E * I;
  p.modes = 8;
  p.stiffening = true;
  p.nodes = {{"A", 0}, {"B", -1}, {"M", 20}};
  test::TempDir dir("crank_free_rod");
  auto chain = ffr::formats::synthetic::spring_chain(p);
  // The chain's points carry no rotary inertia, so turning about its own axis would cost no
  // kinetic energy: give the body its section's second moments (m d^2/16 about y and z), as the
  // frame's rigid inertia (the Reissner beam below has the same rho I).
  chain.sid.integrals.rrdm(1, 1) += m * d * d / 16;
  chain.sid.integrals.rrdm(2, 2) += m * d * d / 16;
  chain.sid.J.M0 = chain.sid.integrals.rrdm.trace() * Eigen::Matrix3d::Identity() - chain.sid.integrals.rrdm + chain.sid.rotary.I;
  test::write_sid_file(chain.sid, dir / "rod.sid.h5");
  test::ReissnerBeam b;
  b.EA = E * A;
  b.GA = 100 * b.EA;
  b.EI = E * I;
  b.rhoA = rho * A;
  b.rhoI = rho * I;
  b.L = L;
  b.n = 40;
  // Also at h = 1e-5: there the augmented-Lagrangian passes of the velocity projection, then
  // Newton's multiplier passes, contract at 0.99 a pass in a nearly redundant direction (both
  // revolutes hold the out-of-plane rotations of a chain whose nodes have no torsional rotation)
  // and the run stopped at t = 0.0186 s before the solver solved for those multipliers directly
  // (exact_multipliers.cpp, FORMULATION.md 9).
  std::printf("free-free chain: Ke/M1 %s, %zu stiffening interfaces\n", chain.sid.KeM1.empty() ? "absent" : "present",
              chain.sid.stiffening ? chain.sid.stiffening->interfaces.size() : 0u);
  for (const double h : {5e-5, 1e-5}) {
    const double end = std::round(2 * M_PI / D::OMEGA / h) * h;
    for (const double ms : {m / 2, 1e-3 * m}) {
      const test::CrankTrace ref = test::oracle_crank(b, ms, h, end);
      test::CrankTrace on;
      std::string failure;
      try {
        on = test::runtime_crank(dir.path, "rod.sid.h5", ms, true, h, end);
      } catch (const std::exception& e) {
        failure = e.what();
      }
      const test::CrankTrace off = test::runtime_crank(dir.path, "rod.sid.h5", ms, false, h, end);
      std::printf("free-free 6 mm rod, h = %g s, slider %.4g kg: oracle peak %.4e m; runtime stiffened peak %.4e (worst difference "
                  "%.2f %% of the peak) %s; unstiffened %.4e (%.2f %%)\n",
                  h, ms, ref.peak(), failure.empty() ? on.peak() : NAN, failure.empty() ? 100 * test::worst_relative(on, ref) : NAN,
                  failure.c_str(), off.peak(), 100 * test::worst_relative(off, ref));
      ASSERT_TRUE(failure.empty()) << failure;
      EXPECT_LT(test::worst_relative(on, ref), 0.05);
    }
  }
}

// The same blade with its tip mass held by a stiff bushing instead of a joint: the bushing's
// force at the blade's interface B enters the interface-load stiffening like a joint's reaction
// (FORMULATION.md 7), against the same oracle (the tip a point mass on the last node).
TEST(StiffeningOracle, SpunUpBladeWithTipMassOnABushingMatchesTheGeometricallyExactBeam) {
  const SpinUp spin{30.0, 0.5};
  const double h = 2e-4, end = 1.0, mt = 0.5;
  const TipRun ref = oracle_blade(spin, mt, h, end);
  const TipRun on = runtime_blade(spin, mt, true, h, end, true);
  const TipRun off = runtime_blade(spin, mt, false, h, end, true);
  auto worst = [&](const TipRun& a) {
    double w = 0;
    for (std::size_t i = 0; i < std::min(a.y.size(), ref.y.size()); ++i) w = std::max(w, std::abs(a.y[i] - ref.y[i]));
    return w / ref.peak();
  };
  std::printf("blade, tip on a bushing: oracle peak tip deflection %.4e m; runtime stiffened %.4e (worst difference "
              "%.2f %% of the peak); unstiffened %.4e (%.2f %%)\n",
              ref.peak(), on.peak(), 100 * worst(on), off.peak(), 100 * worst(off));
  EXPECT_LT(worst(on), 0.05);
  EXPECT_GT(worst(off), 0.2);  // the tip's pull is what stiffens the blade here
}
