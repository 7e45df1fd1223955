// The synthetic spring chain (a clamped lumped-mass Euler-Bernoulli beam, formats/synthetic.hpp)
// on a hub, against an independent unreduced nodal model of the same chain (chain_oracle.hpp):
//  - driven hub: the chain spun up about z (the spin-up profile of Kane, Ryan & Banerjee 1987)
//    under gravity along -z, i.e. a rotating, accelerating cantilever bending out of plane;
//  - free hub: a flexible pendulum, the chain swinging about y under gravity.
// The chain has 2% modal damping on every mode, on both sides: its highest modes (~1000 rad/s)
// are not resolved by the steps used here and would otherwise dominate the difference.
// With all the chain's modes the reduced body spans the full nodal space, so the runtime must
// reproduce the oracle up to the trapezoidal rule's O(h^2) error; with stiffening on, the
// oracle carries the same geometric stiffness, unreduced: the load cases' K_G for a SID without
// Ke/M1, and for the whole SID (Ke/M1 with the load cases less their modal part) axial springs
// with the second-order strain of the body's own modal stress (chain_oracle.hpp). With 4
// modes, the reduction error.
#include "chain_oracle.hpp"
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

using namespace ffr::runtime;
namespace syn = ffr::formats::synthetic;

namespace {

syn::ChainParams chain_params(int modes, bool stiffening) {
  syn::ChainParams p;
  p.points = 6;
  p.length = 1.0;
  p.mass = 1.0;
  p.EA = 1e4;
  p.EIy = p.EIz = 20.0;
  p.clamped = true;
  p.modes = modes;
  p.stiffening = stiffening;
  p.damping_ratio = 0.02;  // damps the highest modes, which the trapezoidal rule cannot follow at these steps
  return p;
}

// theta(t) of the spin-up: Omega/Ts (t^2/2 + (Ts/2pi)^2 (cos(2 pi t/Ts) - 1)), then Omega (t - Ts/2).
double spin_up(double t) {
  const double W = 4.0, Ts = 1.5;
  if (t >= Ts) return W * (t - Ts / 2);
  const double c = Ts / (2 * M_PI);
  return W / Ts * (t * t / 2 + c * c * (std::cos(2 * M_PI * t / Ts) - 1));
}

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

struct Outcome {
  double err = 0;      // max |u_B - u_B,oracle| / max |u_B,oracle|
  double peak = 0;     // max |u_B,oracle|
  double theta = 0, theta_oracle = 0;
};

// How the chain is stiffened: not at all; by the load cases alone (the SID without Ke/M1, the
// oracle with the load cases' K_G, both linear in the deformation); or by everything the SID has
// (Ke/M1 with the load cases less their modal part), against the oracle with geometrically exact
// axial springs. The last is a different physics from the second: the chain's ~0.1 m
// out-of-plane vibration foreshortens it by ~3/5 w^2 / L (up to 9 mm), and in the spinning
// frame that radial motion drives the in-plane bending through Coriolis forces (~1 cm), which a
// model linear in the deformation has not: the Ke/M1 run differed 9.8 % from the load-case oracle.
enum class Stiff { None, LoadCases, Full, FullExact };

Outcome run(bool free_hub, Stiff mode, int modes, double h, double T) {
  test::TempDir dir("chain");
  const bool stiffening = mode != Stiff::None;
  const syn::Chain full = syn::spring_chain(chain_params(15, stiffening));
  syn::Chain body = syn::spring_chain(chain_params(modes, stiffening));
  if (mode == Stiff::LoadCases) body.sid.KeM1.clear();
  test::write_sid_file(body.sid, dir / "chain.sid.h5");
  std::string table_t, table_v;
  for (int i = 0; i <= 300; ++i) {
    // (Appended piece by piece: `const char* + std::string&&` trips GCC 12's -Wrestrict false
    // positive, PR105329.)
    if (i) {
      table_t += ", ";
      table_v += ", ";
    }
    table_t += num(0.01 * i);
    table_v += num(spin_up(0.01 * i));
  }
  const std::string stiff = stiffening ? "true" : "false";
  std::string json = R"({"gravity": [0, 0, -9.81], "solver": {"end": )" + num(T) + R"(, "step": )" + num(h) + "},\n";
  if (!free_hub) {
    json += R"("bodies": [{"name": "chain", "type": "flexible", "sid": "chain.sid.h5", "stiffening": )" + stiff + R"(}],
      "joints": [{"name": "hub", "type": "revolute", "body1": "ground", "body2": "chain", "node2": "A", "axis": [0, 0, 1]}],
      "motions": [{"joint": "hub", "table": {"t": [)" + table_t + R"(], "value": [)" + table_v + R"(], "interpolation": "spline"}}]})";
  } else {
    json += R"("bodies": [
        {"name": "hub", "type": "rigid", "mass": 0.5, "com": [0, 0, 0], "inertia": [[0.05, 0, 0], [0, 0.05, 0], [0, 0, 0.05]]},
        {"name": "chain", "type": "flexible", "sid": "chain.sid.h5", "stiffening": )" + stiff + R"(}],
      "joints": [{"name": "hinge", "type": "revolute", "body1": "ground", "body2": "hub", "at": [0, 0, 0], "axis": [0, 1, 0]},
                 {"name": "clamp", "type": "fixed", "body1": "hub", "body2": "chain", "node2": "A"}]})";
  }
  const Model model = test::model_from(json, dir.path);
  Data data(model);
  initialize(model, data);

  std::vector<double> tt, tv;
  for (int i = 0; i <= 300; ++i) {
    tt.push_back(0.01 * i);
    tv.push_back(spin_up(0.01 * i));
  }
  const Table drive(Eigen::Map<Eigen::VectorXd>(tt.data(), tt.size()), Eigen::Map<Eigen::VectorXd>(tv.data(), tv.size()));
  const auto oracle_mode = mode == Stiff::None        ? test::ChainOracle::Stiffening::None
                           : mode == Stiff::LoadCases ? test::ChainOracle::Stiffening::LoadCases
                           : mode == Stiff::Full      ? test::ChainOracle::Stiffening::VonKarman
                                                      : test::ChainOracle::Stiffening::ExactAxial;
  test::ChainOracle oracle(full.model, free_hub ? Vector3d::UnitY() : Vector3d::UnitZ(), Vector3d(0, 0, -9.81), oracle_mode,
                           0.05, free_hub ? nullptr : &drive);
  const int chain_index = free_hub ? 1 : 0;
  const Body& chain = model.bodies[chain_index];
  const int B = chain.find_node("B");
  const int sub = 20;
  Outcome o;
  double worst = 0;
  for (std::int64_t s = 0; s < step_count(model); ++s) {
    step(model, data);
    for (int k = 0; k < sub; ++k) oracle.step(h / sub);
    const Vector3d u = chain.nodes[B].phi * data.state.q.segment(chain.offset + 12, chain.nq);
    const Vector3d uo = oracle.displacement(5);
    worst = std::max(worst, (u - uo).norm());
    if (std::getenv("CHAIN_DEBUG") && s % 100 == 0)
      std::printf("t %.3f th %.6f %.6f u %.5e %.5e %.5e uo %.5e %.5e %.5e\n", data.state.t, joint_coordinate(model, data, 0, JointCoordinate::Angle), oracle.theta(), u(0), u(1), u(2), uo(0), uo(1), uo(2));
    o.peak = std::max(o.peak, uo.norm());
  }
  o.err = worst / o.peak;
  o.theta = joint_coordinate(model, data, 0, JointCoordinate::Angle);
  o.theta_oracle = oracle.theta();
  return o;
}

void report(const char* what, const Outcome& o) {
  std::printf("%-44s tip peak %.4e m, max error %.3e of peak, theta %.8f (oracle %.8f)\n", what, o.peak, o.err, o.theta,
              o.theta_oracle);
}

}  // namespace

const char* name(Stiff s) { return s == Stiff::None ? "" : s == Stiff::LoadCases ? ", load cases" : ", Ke/M1 + load cases"; }  // (Full)

TEST(SpringChain, DrivenHubMatchesUnreducedModel) {
  for (Stiff stiff : {Stiff::None, Stiff::LoadCases, Stiff::Full}) {
    const Outcome a = run(false, stiff, 15, 2e-3, 2.5), b = run(false, stiff, 15, 1e-3, 2.5);
    report((std::string("driven") + name(stiff) + ", 15 modes, h = 2e-3").c_str(), a);
    report((std::string("driven") + name(stiff) + ", 15 modes, h = 1e-3").c_str(), b);
    EXPECT_LT(b.err, 2e-3);
    EXPECT_NEAR(a.err / b.err, 4.0, 0.8);  // the remaining difference is the O(h^2) time error
  }
  // Against geometrically exact axial springs: the second-order (von Karman) strain of Ke/M1 is a
  // model error of fourth order in the segments' rotations (up to ~0.15 rad here).
  const Outcome e = run(false, Stiff::FullExact, 15, 1e-3, 2.5);
  report("driven, Ke/M1 + load cases vs exact springs, h = 1e-3", e);
  EXPECT_LT(e.err, 3e-3);
}

TEST(SpringChain, FlexiblePendulumMatchesUnreducedModel) {
  for (Stiff stiff : {Stiff::None, Stiff::LoadCases, Stiff::Full}) {
    const Outcome a = run(true, stiff, 15, 2e-3, 1.5), b = run(true, stiff, 15, 1e-3, 1.5);
    report((std::string("pendulum") + name(stiff) + ", 15 modes, h = 2e-3").c_str(), a);
    report((std::string("pendulum") + name(stiff) + ", 15 modes, h = 1e-3").c_str(), b);
    EXPECT_LT(b.err, 2e-3);
    EXPECT_NEAR(a.err / b.err, 4.0, 0.8);
    EXPECT_NEAR(b.theta, b.theta_oracle, 1e-4);
  }
}

TEST(SpringChain, ReductionErrorFallsWithModes) {
  // Fewer modes than the chain has: the difference to the unreduced chain is the reduction
  // error, which falls as modes are added (the axial modes carry the centrifugal stretching).
  double prev = 1e9;
  for (int modes : {4, 8, 12}) {
    const Outcome r = run(true, Stiff::LoadCases, modes, 1e-3, 1.5);
    char what[64];
    std::snprintf(what, sizeof what, "pendulum, stiffening, %d modes, h = 1e-3", modes);
    report(what, r);
    EXPECT_LT(r.err, prev);
    prev = r.err;
  }
  EXPECT_LT(prev, 2e-2);
}
