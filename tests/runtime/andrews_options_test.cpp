// Every solver option against the published solution of Andrews' squeezing mechanism
// (andrews_model.hpp; F. Mazzia & C. Magherini, Test Set for IVP Solvers, University of Bari,
// release 2.3, problem "andrews", whose reference at t = 0.03 s was computed with PSIDE at
// rtol = atol = 1e-14; E. Hairer & G. Wanner, Solving ODEs II, VII.7). A seven-body loop
// mechanism driven by a torque against a stiff spring: the angles turn by 16 rad in 0.03 s.
#include "andrews_model.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

using namespace ffr::runtime;

namespace {

// The test set's velocities at t = 0.03 s (y8 .. y14: the rates of beta, Theta, gamma, Phi,
// delta, Omega, epsilon), from the same reference solution.
constexpr double kReferenceRates[7] = {0.1139920302151208e+4, -0.1424379294994111e+4, 0.1103291221937134e+2,
                                       0.1929337464421385e+2, 0.5735699284790808e+0,  -0.1929337464421385e+2,
                                       0.3231791658026955e+0};

struct Result {
  double angle[7], rate[7];
};

// A body's angular rate about z: its frame turns in the plane, so omega = (u x u_dot)_z.
double spin(const Data& data, int body) {
  const int o = 12 * body;  // seven rigid bodies, none driven
  const Eigen::Vector3d u = data.state.q.segment<3>(o + 3), ud = data.state.qd.segment<3>(o + 3);
  return u.cross(ud)(2);
}

Result run(double h, const std::string& options) {
  char solver[256];
  std::snprintf(solver, sizeof solver, R"({"end": 0.03, "step": %.17g%s})", h, options.c_str());
  const Model model = test::model_from(test::andrews_json(solver));
  Data data(model);
  initialize(model, data);
  for (std::int64_t i = 0; i < step_count(model); ++i) step(model, data);
  Result r{};
  for (int j = 0; j < 7; ++j) {
    const int joint = model.outputs[static_cast<std::size_t>(j)].joint;
    r.angle[j] = test::kAndrewsInitial[j] + joint_coordinate(model, data, joint, JointCoordinate::Angle);
  }
  double w[7];
  for (int b = 0; b < 7; ++b) w[b] = spin(data, b);
  // beta, Theta, gamma, Phi, delta, Omega, epsilon from the bodies' absolute rates (the
  // angles of andrews_model.cpp: b2 at beta + Theta, b4 at Phi + delta, b6 at Omega + epsilon).
  const double rates[7] = {w[0], w[1] - w[0], w[2], w[3] - w[4], w[4], w[5] - w[6], w[6]};
  for (int j = 0; j < 7; ++j) r.rate[j] = rates[j];
  return r;
}

// Richardson extrapolation of a second-order result from steps h and h/2.
Result richardson(const Result& a, const Result& b) {
  Result r{};
  for (int j = 0; j < 7; ++j) {
    r.angle[j] = (4 * b.angle[j] - a.angle[j]) / 3;
    r.rate[j] = (4 * b.rate[j] - a.rate[j]) / 3;
  }
  return r;
}

double angle_error(const Result& r) {
  double e = 0;
  for (int j = 0; j < 7; ++j) e = std::max(e, std::abs(r.angle[j] - test::kAndrewsReference[j]));
  return e;
}
double rate_error(const Result& r) {
  double e = 0;
  for (int j = 0; j < 7; ++j) e = std::max(e, std::abs(r.rate[j] - kReferenceRates[j]) / std::abs(kReferenceRates[0]));
  return e;
}

}  // namespace

// The default settings and a large penalty: Richardson extrapolation of h = 5e-6 and 2.5e-6 s
// reaches the published angles to 1e-6 rad and the published rates to 1e-6 of the crank's
// (1140 rad/s). (Before the projections were iterated to convergence in x, penalty 1e6 ended
// 5e-2 rad off at h = 1e-5 s and did not improve with a smaller step.)
TEST(AndrewsOptions, RichardsonMatchesTheTestSetWithDefaultAndLargePenalty) {
  for (const char* opt : {"", R"(, "penalty": 1e6)"}) {
    const Result a = run(5e-6, opt), b = run(2.5e-6, opt);
    const Result x = richardson(a, b);
    std::printf("options {%s}: angle error %.3e / %.3e rad, extrapolated %.3e; rate error %.3e, extrapolated %.3e\n", opt,
                angle_error(a), angle_error(b), angle_error(x), rate_error(b), rate_error(x));
    EXPECT_LT(angle_error(x), 1e-6) << opt;
    EXPECT_LT(rate_error(x), 1e-6) << opt;
    // Second order: the error at the smaller step a quarter of the larger one's.
    EXPECT_NEAR(angle_error(a) / angle_error(b), 4.0, 0.3) << opt;
  }
}

// Every accepted solver option against the default at h = 1e-5 s: the results agree to far
// below the default's own error there (3e-4 rad against the test set): 1e-2 of it.
TEST(AndrewsOptions, EveryOptionKeepsTheDefaultsAccuracy) {
  const Result base = run(1e-5, "");
  const double own = angle_error(base);
  EXPECT_GT(own, 1e-4);  // (the truncation error the comparison is scaled by)
  // (The penalty's range: 1e-4 and the largest the model file takes, kMaxPenalty = 1e9; the
  // loosest constraint tolerance it takes, kMaxConstraintTolerance = 1e-8.)
  for (const char* opt : {R"(, "penalty": 1e-4)", R"(, "penalty": 1e2)", R"(, "penalty": 1e6)", R"(, "penalty": 1e9)",
                          R"(, "tolerance": 1e-8)", R"(, "tolerance": 1e-10)",
                          R"(, "newton_tolerance": 1e-12)", R"(, "max_iterations": 8)", R"(, "eliminate_driven_bodies": false)",
                          R"(, "reuse_jacobian": false)", R"(, "output_every": 7)"}) {
    const Result r = run(1e-5, opt);
    double d = 0;
    for (int j = 0; j < 7; ++j) d = std::max(d, std::abs(r.angle[j] - base.angle[j]));
    std::printf("options {%s}: %.3e rad from the default\n", opt, d);
    EXPECT_LT(d, 1e-2 * own) << opt;
  }
}
