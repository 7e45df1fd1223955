// The IFToMM simple pendulum: a 1 kg point bob on a 1 m massless arm, hinged at the origin,
// released at rest from the horizontal, g = 9.81 m/s^2 (IFToMM Technical Committee for
// Multibody Dynamics, library of computational benchmark problems, "simple pendulum"). The bob
// is a rigid body whose own rotational inertia is tiny (1e-3 down to 1e-9 kg m^2): its frame
// directions are then almost massless coordinates, which the Newton iteration must still
// converge in, at steps from 1e-2 to 1e-4 s.
//
// Reference: the exact period of the pendulum released from theta0 = pi/2,
//   T = 4 sqrt(L_eff / g) K(sin(theta0 / 2)),  L_eff = I_O / (m L) = L + I_bob / (m L),
// K the complete elliptic integral of the first kind (e.g. L. D. Landau & E. M. Lifshitz,
// Mechanics, section 11, problem 1); for the point mass (I_bob = 0) T = 2.367842 s.
#include "support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

using namespace ffr::runtime;

namespace {

constexpr double kG = 9.81, kL = 1.0, kMass = 1.0;

double exact_period(double inertia) {
  const double Leff = kL + inertia / (kMass * kL);
  return 4 * std::sqrt(Leff / kG) * std::comp_ellint_1(std::sin(M_PI / 4));
}

// Where the body's frame sits: at the hinge (the bob's centre of mass 1 m along its x axis), or
// at the bob (the hinge 1 m behind it); and which joint holds it: a revolute joint about y, or a
// spherical joint (the bob's spin about the arm is then free and almost massless).
enum class Frame { AtHinge, AtBob };
enum class Hinge { Revolute, Spherical };

std::string pendulum_json(double inertia, double h, Frame frame, Hinge hinge, const std::string& extra = "") {
  const bool at_bob = frame == Frame::AtBob;
  char buf[1400];
  std::snprintf(buf, sizeof buf, R"({
  "gravity": [0, 0, -9.81],
  "bodies": [{"name": "bob", "type": "rigid", "mass": 1.0, "com": [1, 0, 0],
              "inertia": [[%.17g, 0, 0], [0, %.17g, 0], [0, 0, %.17g]], "position": [%s, 0, 0]}],
  "joints": [{"name": "hinge", "type": "%s", "body1": "ground", "body2": "bob", "at": [0, 0, 0]%s}],
  "solver": {"end": 10, "step": %.17g%s}
})",
                inertia, inertia, inertia, at_bob ? "1" : "0",
                hinge == Hinge::Revolute ? "revolute" : "spherical", hinge == Hinge::Revolute ? R"(, "axis": [0, 1, 0])" : "", h, extra.c_str());
  return buf;
}

// The swing angle from the horizontal (positive downwards) and its rate, from the bob's centre
// of mass p = r0 + A c (its frame's coordinates: r0, then the columns u, v, w of A).
struct Swing {
  double angle, rate;
};
Swing swing(const Data& data, Frame frame) {
  const Eigen::Vector3d r = data.state.q.segment<3>(0), rd = data.state.qd.segment<3>(0);
  const Eigen::Vector3d u = data.state.q.segment<3>(3), ud = data.state.qd.segment<3>(3);
  const Eigen::Vector3d p = frame == Frame::AtBob ? r : Eigen::Vector3d(r + u);
  const Eigen::Vector3d pd = frame == Frame::AtBob ? rd : Eigen::Vector3d(rd + ud);
  const double x = p(0), z = -p(2);
  return {std::atan2(z, x), (x * -pd(2) - z * pd(0)) / (x * x + z * z)};
}

// Times at which the bob passes the bottom (angle pi/2). Each crossing is located on the cubic
// Hermite interpolant of the step's end values and rates (accurate to O(h^4), far below the
// integrator's O(h^2) error, so the period error measured is the integrator's).
std::vector<double> bottom_crossings(const Model& model, Data& data, Frame frame, int count) {
  std::vector<double> out;
  const double bottom = M_PI / 2;
  Swing s0 = swing(data, frame);
  double t0 = data.state.t;
  while (static_cast<int>(out.size()) < count) {
    step(model, data);
    const Swing s1 = swing(data, frame);
    const double h = data.state.t - t0;
    if ((s0.angle - bottom) * (s1.angle - bottom) <= 0 && s0.angle != s1.angle) {
      auto p = [&](double s) {
        const double s2 = s * s, s3 = s2 * s;
        return (2 * s3 - 3 * s2 + 1) * s0.angle + (s3 - 2 * s2 + s) * h * s0.rate + (-2 * s3 + 3 * s2) * s1.angle +
               (s3 - s2) * h * s1.rate - bottom;
      };
      double lo = 0, hi = 1;
      for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi);
        if ((p(lo) < 0) == (p(mid) < 0)) lo = mid; else hi = mid;
      }
      out.push_back(t0 + 0.5 * (lo + hi) * h);
    }
    s0 = s1;
    t0 = data.state.t;
    if (data.state.t > 20) break;
  }
  return out;
}

// The period from the first and third passage through the bottom.
double period(double inertia, double h, Frame frame, Hinge hinge) {
  const Model model = test::model_from(pendulum_json(inertia, h, frame, hinge));
  Data data(model);
  initialize(model, data);
  const std::vector<double> c = bottom_crossings(model, data, frame, 3);
  return c.size() == 3 ? c[2] - c[0] : 0.0;
}

// The first step's failure of the pendulum hinged at its frame with these solver settings
// (empty: the step converged).
std::optional<SolverError> first_step_failure(const std::string& settings) {
  const Model model = test::model_from(pendulum_json(1e-9, 1e-3, Frame::AtHinge, Hinge::Revolute, settings));
  Data data(model);
  initialize(model, data);
  try {
    step(model, data);
  } catch (const SolverError& e) {
    return e;
  }
  return std::nullopt;
}

}  // namespace

TEST(PointPendulum, ExactPeriodOfThePointMass) {
  // The issue's figure, from the elliptic integral: 4 sqrt(1 / 9.81) K(sin(pi/4)) = 2.367842 s.
  EXPECT_NEAR(exact_period(0.0), 2.367842, 5e-7);
}

// Steps of 1e-3 and 1e-4 s: the period within 1e-4 s of the exact one (measured: 5.3e-6 and
// 5.3e-8 s, the trapezoidal rule's O(h^2)). At 1e-2 s the rule's own error is 5.2e-4 s, so there
// the period is Richardson-extrapolated from h and h/2 (second order: (4 T(h/2) - T(h)) / 3),
// and the error ratio checks the order.
TEST(PointPendulum, PeriodAtThreeStepsWithBobInertiasDownTo1e9) {
  for (const double inertia : {1e-3, 1e-6, 1e-9}) {
    const double exact = exact_period(inertia);
    for (const double h : {1e-3, 1e-4}) {
      const double T = period(inertia, h, Frame::AtHinge, Hinge::Revolute);
      EXPECT_NEAR(T, exact, 1e-4) << "bob inertia " << inertia << " kg m^2, h = " << h << " s";
    }
    const double T1 = period(inertia, 1e-2, Frame::AtHinge, Hinge::Revolute);
    const double T2 = period(inertia, 5e-3, Frame::AtHinge, Hinge::Revolute);
    EXPECT_NEAR((4 * T2 - T1) / 3, exact, 1e-4) << "bob inertia " << inertia << " kg m^2, h = 1e-2 s, extrapolated";
    EXPECT_NEAR((T1 - exact) / (T2 - exact), 4.0, 0.2) << "bob inertia " << inertia;
  }
}

// The same with the body's frame at the bob (the hinge 1 m from it) and with a spherical joint,
// about which the bob's spin along the arm is free and carries only its 1e-9 kg m^2.
TEST(PointPendulum, FrameAtTheBobAndSphericalHinge) {
  for (const Frame frame : {Frame::AtHinge, Frame::AtBob})
    for (const Hinge hinge : {Hinge::Revolute, Hinge::Spherical}) {
      const double T = period(1e-9, 1e-3, frame, hinge);
      EXPECT_NEAR(T, exact_period(1e-9), 1e-4) << "frame " << static_cast<int>(frame) << ", hinge " << static_cast<int>(hinge);
    }
}

// A step that cannot converge (one iteration allowed, a tolerance below round-off) names the
// time, the coordinate and the constraint row left worst, and what to try.
TEST(PointPendulum, NewtonFailureNamesTimeEquationAndRemedy) {
  const auto e = first_step_failure(R"(, "max_iterations": 1, "newton_tolerance": 1e-30)");
  ASSERT_TRUE(e) << "the step converged";
  const std::string msg = e->what();
  EXPECT_NEAR(e->time(), 1e-3, 1e-15);
  EXPECT_NE(msg.find("at t = 0.001 s"), std::string::npos) << msg;
  EXPECT_NE(msg.find("body 'bob', "), std::string::npos) << msg;
  EXPECT_TRUE(msg.find("joint 'hinge' (its row") != std::string::npos || msg.find("the frame of body 'bob'") != std::string::npos) << msg;
  EXPECT_NE(msg.find("Try a smaller step (solver.step = 0.0005)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("a newton_tolerance of at least 1e-15 (1e-30 is below what the coordinates' rounding resolves)"),
            std::string::npos) << msg;
  EXPECT_NE(msg.find("more iterations (solver.max_iterations)"), std::string::npos) << msg;
}

// At the largest max_iterations the message does not ask for more (they would be refused), and
// a stalled step fails at once instead of iterating for hours (with the 1e9 once allowed, this
// run had not finished its first step after 20 s).
TEST(PointPendulum, NewtonFailureAtTheIterationBoundAsksForNoMore) {
  const auto e = first_step_failure(R"(, "max_iterations": 1000, "newton_tolerance": 1e-30)");
  ASSERT_TRUE(e) << "the step converged";
  const std::string msg = e->what();
  EXPECT_NE(msg.find("after 1000 iterations"), std::string::npos) << msg;
  EXPECT_NE(msg.find("a newton_tolerance of at least"), std::string::npos) << msg;
  EXPECT_EQ(msg.find("more iterations"), std::string::npos) << msg;
}
