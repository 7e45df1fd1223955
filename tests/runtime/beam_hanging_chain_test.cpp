// The flexible pendulum's small swings against a published closed-form benchmark, Bernoulli's
// heavy hanging chain, run by both beam formulations of the runtime (FORMULATION.md 15 and 17).
//
// Why this benchmark: no published table, nor values stated in a text, of the large-amplitude
// ANCF pendulum of M. Berzeri & A. A. Shabana ("Development of simple models for the elastic
// forces in the absolute nodal co-ordinate formulation", J. Sound Vib. 235 (2000) 539-565;
// again in J. Gerstmayr & A. A. Shabana, Nonlinear Dyn. 45 (2006) 109-130) could be found: the
// papers give the tip's motion as curves only (beam_pendulum_test.cpp holds that pendulum to an
// independent Reissner-beam oracle instead). The hanging chain is the limit of the same pendulum,
// pinned at its top and hanging under gravity, as its bending stiffness and its stretch vanish,
// and its frequencies are published in closed form:
//  - D. Bernoulli (1733; Lord Rayleigh, "The Theory of Sound", vol. 1, on the vibrations of a
//    heavy chain): the small swings of a uniform heavy chain of length L hanging from a fixed
//    point have the shapes J0(alpha_n sqrt(xi / L)) (xi the distance from the free end) and the
//    angular frequencies omega_n = (alpha_n / 2) sqrt(g / L), alpha_n the zeros of the Bessel
//    function J0, tabulated in M. Abramowitz & I. A. Stegun, "Handbook of Mathematical
//    Functions", Table 9.5 (here to 16 digits, 2.404825557695773, 5.520078110286311,
//    8.653727912911013, and checked below against std::cyl_bessel_j).
// The model: L = 1.2 m, A = 0.0018 m^2, rho = 5540 kg/m^3 (the Berzeri-Shabana pendulum's
// length, section and density; the chain's frequencies depend on neither rho nor A nor E),
// E = 1e8 Pa, I = 1.69e-12 m^4, hanging along -z from a spherical joint at the origin, first
// settled statically (solver.initial_equilibrium) and then set swinging in the x-z plane by the
// initial velocity V J0(alpha_n sqrt(xi / L)) along x (the slopes, or the directors, turning
// with it; tip amplitude 1e-3 L). The frequency is the mean spacing of the tip's zero crossings
// over two periods. What separates this beam from the chain, each bounded:
//  - its stretch under its own weight, at most rho g L / E = 6.5e-4 at the pin: it lowers
//    omega_n by about 2e-4 (measured: the converged ancf beam's frequencies are 2.0e-4, 2.3e-4
//    and 1.9e-4 low with E = 1e8, and 3e-5, 4e-5, 7e-5 low with E = 1e9, I = 1.69e-14);
//  - its bending stiffness, EI / (rho A g L^3) = 1e-6: the Rayleigh quotient of the chain's
//    modes bounds the rise it gives omega_n by 9e-7, 8e-5 and 8e-4 (n = 1, 2, 3);
//  - the trapezoidal rule's period lengthening (omega h)^2 / 12: 1.3e-5 at 500 steps a period,
//    3e-6 at 1000; the amplitude's own frequency shift, of order 1e-7;
//  - the discretisation: the cubic ancf elements are converged at 16 (16 and 32 elements agree
//    to 3e-5), the two-node geometrically exact elements with lumped mass are second order
//    (32 elements: 4.6e-4, 3.6e-4 and 1.1e-3 low).
// Tolerances: 1e-3 of omega_n for ancf (16 elements) and 2e-3 for geometrically exact (32), the
// bounds above with room; a 5 % change of g moves every omega_n by 2.5 % (measured: +2.45 %),
// far outside them (E does not enter the chain's frequencies, so its change would not show).
// The geometrically exact beam needs 1000 steps a period here: at 500 (h = 3.7 ms for mode 1) its
// first step stops on a tangent singular to working precision (Newton's message says so) with
// this small a section rotary inertia (rho I = 9.4e-9 kg m); with I 100 times larger it ran at 500.
#include "support.hpp"

#include "ffr/runtime/dynamics.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace ffr::runtime;

namespace {

constexpr double kL = 1.2, kA = 0.0018, kRho = 5540, kE = 1e8, kI = 1.69e-12, kG = 9.81, kNu = 0.3;
// Zeros of J0 (Abramowitz & Stegun, Table 9.5).
constexpr double kAlpha[3] = {2.404825557695773, 5.520078110286311, 8.653727912911013};

std::string num(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

std::string chain_json(const std::string& form, int elements, double h, double end, double g) {
  const bool ge = form == "geometrically_exact";
  return R"({"gravity": [0, 0, )" + num(-g) + R"(],
    "bodies": [{"name": "beam", "type": "beam", "formulation": ")" + form + R"(", "start": [0, 0, 0], "end": [0, 0, )" +
         num(-kL) + R"(], "elements": )" + std::to_string(elements) + R"(, "E": )" + num(kE) +
         (ge ? R"(, "nu": )" + num(kNu) : std::string()) + R"(, "rho": )" + num(kRho) + R"(, "section": {"A": )" + num(kA) +
         R"(, "Iy": )" + num(kI) + R"(, "Iz": )" + num(kI) + (ge ? R"(, "J": )" + num(2 * kI) : std::string()) + R"(}}],
    "joints": [{"name": "pin", "type": "spherical", "body1": "ground", "body2": "beam", "node2": "start"}],
    "solver": {"end": )" + num(end) + R"(, "step": )" + num(h) + R"(, "initial_equilibrium": true},
    "outputs": [{"name": "tip", "type": "node_position", "body": "beam", "node": "end"}]})";
}

// The chain's mode n (0-based) at distance S from the pin: its lateral displacement w and slope
// dw/dS (xi = L - S from the free end; w = 1 there).
void chain_mode(int n, double S, double& w, double& dw_dS) {
  const double xi = std::max(kL - S, 0.0), a = kAlpha[n], z = a * std::sqrt(xi / kL);
  w = std::cyl_bessel_j(0.0, z);
  // dw/dS = -dw/dxi = J1(z) a / (2 sqrt(xi L)); its limit at the free end is a^2 / (4 L).
  dw_dS = xi > 0 ? std::cyl_bessel_j(1.0, z) * a / (2 * std::sqrt(xi * kL)) : a * a / (4 * kL);
}

int body_index(const Model& m, const std::string& name) {
  for (std::size_t i = 0; i < m.bodies.size(); ++i)
    if (m.bodies[i].name == name) return static_cast<int>(i);
  ADD_FAILURE() << "no body " << name;
  return -1;
}

// Sets the beam swinging in mode n: velocity V w(S) along x at each node, and the slopes (ancf)
// or directors (geometrically exact) turning with the centre line, V dw/dS.
void start_mode(const Model& m, Data& d, const std::string& form, int elements, int n, double V) {
  for (int k = 0; k <= elements; ++k) {
    double w, wS;
    chain_mode(n, kL * k / elements, w, wS);
    const Eigen::Vector3d v(V * w, 0, 0), tangent_rate(V * wS, 0, 0);
    if (form == "ancf") {
      const Body& b = m.bodies[body_index(m, "beam")];
      d.state.qd.segment<3>(b.offset + 12 + 6 * k) = v;
      d.state.qd.segment<3>(b.offset + 12 + 6 * k + 3) = tangent_rate;
    } else {
      const Body& b = m.bodies[body_index(m, "beam:n" + std::to_string(k))];
      d.state.qd.segment<3>(b.offset) = v;
      // The directors turn at omega = d3 x d3_dot (d3 the centre line's unit tangent).
      const Eigen::Vector3d d3 = d.state.q.segment<3>(b.offset + 9), omega = d3.cross(tangent_rate);
      for (int j = 0; j < 3; ++j)
        d.state.qd.segment<3>(b.offset + 3 + 3 * j) = omega.cross(Eigen::Vector3d(d.state.q.segment<3>(b.offset + 3 + 3 * j)));
    }
  }
}

// The angular frequency of mode n measured from the tip's zero crossings along x over `periods`
// of the chain's period, and the largest tip deviation from the plane of swing.
double measured_omega(const std::string& form, int elements, int n, double periods, int steps_per_period, double g = kG) {
  const double omega_ref = kAlpha[n] / 2 * std::sqrt(kG / kL), period = 2 * M_PI / omega_ref, end = periods * period,
               h = period / steps_per_period;
  const Model m = test::model_from(chain_json(form, elements, h, end, g));
  Data d(m);
  initialize(m, d);
  start_mode(m, d, form, elements, n, 1e-3 * kL * omega_ref);
  std::vector<double> t_hist, x_hist;
  while (d.state.t < end - 1e-9) {
    step(m, d);
    const auto tip = test::output(m, d, "tip");
    EXPECT_NEAR(tip[1], 0.0, 1e-9);  // the swing stays in its plane
    t_hist.push_back(d.state.t);
    x_hist.push_back(tip[0]);
  }
  // The zero crossings, each the root of a least-squares line through the samples within a
  // third of the amplitude of it (the axial and shear vibrations the start excites ride on the
  // swing at far higher frequencies and far smaller amplitudes: a line through many samples
  // averages them out where a sign change between two samples would not).
  double amplitude = 0;
  for (double x : x_hist) amplitude = std::max(amplitude, std::abs(x));
  std::vector<double> crossings;
  const double band = amplitude / 3;
  std::size_t i = 0;
  while (i < x_hist.size()) {
    if (std::abs(x_hist[i]) >= band) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < x_hist.size() && std::abs(x_hist[j]) < band) ++j;
    // A window that starts at t = 0 or runs to the end is not a whole crossing.
    if (i > 0 && j < x_hist.size() && (x_hist[i - 1] < 0) != (x_hist[j] < 0)) {
      double st = 0, sx = 0, stt = 0, stx = 0;
      const double c = double(j - i);
      for (std::size_t k = i; k < j; ++k) st += t_hist[k], sx += x_hist[k], stt += t_hist[k] * t_hist[k], stx += t_hist[k] * x_hist[k];
      const double slope = (c * stx - st * sx) / (c * stt - st * st), intercept = (sx - slope * st) / c;
      crossings.push_back(-intercept / slope);
    }
    i = j;
  }
  if (crossings.size() < 3) {
    ADD_FAILURE() << form << " mode " << n + 1 << ": only " << crossings.size() << " zero crossings";
    return 0;
  }
  // Crossings are half a period apart: a least-squares line through them.
  const int c = static_cast<int>(crossings.size());
  double sk = 0, st = 0, skk = 0, skt = 0;
  for (int k = 0; k < c; ++k) sk += k, st += crossings[k], skk += double(k) * k, skt += k * crossings[k];
  const double half_period = (c * skt - sk * st) / (c * skk - sk * sk);
  return M_PI / half_period;
}

}  // namespace

// The first three frequencies of both formulations against Bernoulli's chain: ancf (16 elements,
// 500 steps a period) within 1e-3, geometrically exact (32 elements, 1000 steps a period) within
// 2e-3 (the header says why).
TEST(BeamHangingChain, FirstThreeFrequenciesOfBothFormulationsMatchBernoullisChain) {
  for (double z : kAlpha) EXPECT_LT(std::abs(std::cyl_bessel_j(0.0, z)), 1e-14);  // the table's zeros
  struct Case {
    const char* form;
    int elements, steps_per_period;
    double tolerance;
  };
  for (const Case c : {Case{"ancf", 16, 500, 1e-3}, Case{"geometrically_exact", 32, 1000, 2e-3}}) {
    for (int n = 0; n < 3; ++n) {
      SCOPED_TRACE(std::string(c.form) + " mode " + std::to_string(n + 1));
      const double ref = kAlpha[n] / 2 * std::sqrt(kG / kL);
      const double got = measured_omega(c.form, c.elements, n, 2.0, c.steps_per_period);
      std::printf("%s, %d elements, mode %d: omega %.6f rad/s, Bernoulli's chain %.6f rad/s, rel. diff %+.2e\n", c.form,
                  c.elements, n + 1, got, ref, got / ref - 1);
      EXPECT_NEAR(got / ref, 1.0, c.tolerance);
    }
  }
}
