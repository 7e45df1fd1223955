// The flexible pendulum's large swing in its stiff limit against the published closed form of
// the compound pendulum, run by both beam formulations (FORMULATION.md 15 and 17).
//
// The Berzeri-Shabana pendulum (M. Berzeri & A. A. Shabana, J. Sound Vib. 235 (2000); 1.2 m,
// A = 0.0018 m^2, I = 1.215e-8 m^4, rho = 5540 kg/m^3, pinned, released at rest from the
// horizontal) has no published table of its motion (beam_hanging_chain_test.cpp says so and
// checks its soft limit, Bernoulli's hanging chain). Its stiff limit is the uniform bar released
// from the horizontal, whose time to the vertical is a quarter period of the pendulum of
// amplitude 90 degrees, t = sqrt(I_O / (m g L / 2)) K(m = sin^2 45 deg = 1/2), I_O = m L^2 / 3:
// t = sqrt(2 L / (3 g)) K(1/2), the complete elliptic integral K(1/2) = 1.854074677301372 from
// M. Abramowitz & I. A. Stegun, "Handbook of Mathematical Functions", Table 17.1 (and the
// large-amplitude pendulum's period there, 17.4 and Example 8 of chapter 17).
// The model: the pendulum's L, A, I and rho with E = 1e15 Pa, so that the bending it keeps is
// rho A g L^3 / EI = 1.4e-5 of the length (its share of the time is of that order), and the
// section's rotary inertia (a geometrically exact node carries rho I of it) adds
// 3 I / (A L^2) = 1.4e-5 to I_O (7e-6 of the time). Measured: the time at which the tip passes
// under the pin (its x crosses 0), interpolated between steps; h = 0.5 ms, the trapezoidal
// rule's phase error (of order (omega h)^2 / 12, omega ~ 6 rad/s) 8e-7. Tolerance 1e-4 of t:
// several times those departures (the ancf beam's 8, 16, 32 elements were 8.7e-6, 3.0e-5,
// 8.4e-6 off); a 5 % change of g or L moves t by 2.5 %.
#include "support.hpp"

#include "ffr/runtime/dynamics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

using namespace ffr::runtime;

namespace {

constexpr double kL = 1.2, kA = 0.0018, kI = 1.215e-8, kRho = 5540, kE = 1e15, kG = 9.81, kNu = 0.3;
constexpr double kK_half = 1.854074677301372;  // K(m = 1/2), Abramowitz & Stegun Table 17.1

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

std::string stiff_json(const std::string& form, int elements, double h, double end) {
  const bool ge = form == "geometrically_exact";
  return R"({"gravity": [0, 0, )" + num(-kG) + R"(],
    "bodies": [{"name": "beam", "type": "beam", "formulation": ")" + form + R"(", "start": [0, 0, 0], "end": [)" + num(kL) +
         R"(, 0, 0], "elements": )" + std::to_string(elements) + R"(, "E": )" + num(kE) +
         (ge ? R"(, "nu": )" + num(kNu) : std::string()) + R"(, "rho": )" + num(kRho) + R"(, "section": {"A": )" + num(kA) +
         R"(, "Iy": )" + num(kI) + R"(, "Iz": )" + num(kI) + (ge ? R"(, "J": )" + num(2 * kI) : std::string()) + R"(}}],
    "joints": [{"name": "pin", "type": "spherical", "body1": "ground", "body2": "beam", "node2": "start"}],
    "solver": {"end": )" + num(end) + R"(, "step": )" + num(h) + R"(},
    "outputs": [{"name": "tip", "type": "node_position", "body": "beam", "node": "end"}]})";
}

// The time at which the tip first passes under the pin.
double time_to_vertical(const std::string& form, int elements, double h) {
  const double end = 0.7;
  const Model m = test::model_from(stiff_json(form, elements, h, end));
  Data d(m);
  initialize(m, d);
  double t_prev = d.state.t, x_prev = test::output(m, d, "tip")[0];
  while (d.state.t < end - 1e-9) {
    step(m, d);
    const auto tip = test::output(m, d, "tip");
    EXPECT_NEAR(tip[1], 0.0, 1e-9);  // the swing stays in its plane
    if (tip[0] <= 0) return t_prev + (d.state.t - t_prev) * x_prev / (x_prev - tip[0]);
    t_prev = d.state.t;
    x_prev = tip[0];
  }
  ADD_FAILURE() << form << ": the tip did not reach the vertical in " << end << " s";
  return 0;
}

}  // namespace

// The time to the vertical against the compound pendulum's, for the bar's moment of inertia as
// each discretisation has it: the ancf beam's consistent (cubic) mass gives the bar's m L^2 / 3
// exactly; the geometrically exact beam lumps the mass at its nodes, which the trapezoidal rule
// sums to m L^2 / 3 (1 + 1 / (2 N^2)) (N elements), and its nodes carry the section's rotary
// inertia rho I L on top: its time is longer by the square root of their ratio (9.8e-4 for
// N = 16, measured to 3e-6 of it; 3.9e-3 and 2.5e-4 for N = 8 and 32, likewise). Both within
// 1e-4 of their compound pendulum.
TEST(BeamStiffPendulum, BothFormulationsReachTheVerticalAtTheCompoundPendulumsQuarterPeriod) {
  const double bar = std::sqrt(2 * kL / (3 * kG)) * kK_half;
  struct Case {
    const char* form;
    int elements;
    double inertia_ratio;  // the discrete model's moment of inertia about the pin over m L^2 / 3
  };
  const int n_ge = 16;
  for (const Case c : {Case{"ancf", 8, 1.0},
                       Case{"geometrically_exact", n_ge, 1 + 1.0 / (2.0 * n_ge * n_ge) + 3 * kI / (kA * kL * kL)}}) {
    SCOPED_TRACE(c.form);
    const double t = time_to_vertical(c.form, c.elements, 5e-4), ref = bar * std::sqrt(c.inertia_ratio);
    std::printf("%s, %d elements: the tip under the pin at %.7f s; compound pendulum %.7f s (the bar's %.7f s); rel. diff "
                "%+.2e (from the bar's %+.2e)\n",
                c.form, c.elements, t, ref, bar, t / ref - 1, t / bar - 1);
    EXPECT_NEAR(t / ref, 1.0, 1e-4);
  }
}
