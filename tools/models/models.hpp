#pragma once
// Benchmark models built from synthetic SIDs (formats/synthetic.hpp) in a temporary directory.

#include "ffr/formats/synthetic.hpp"
#include "ffr/runtime/runtime.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <vector>

namespace bench {

/// A steel connecting rod (0.3 m, 8 x 8 mm, free-free chain of `points` masses, `modes` modes).
ffr::formats::synthetic::ChainParams rod_params(int points, int modes);

/// The chain's masses sit on its axis; a real bar of section b x h also has the rotary inertia
/// of its section (m h^2/12, m b^2/12 about the transverse axes' second moments), which keeps the
/// rotation about the bar's own axis from being massless. Added to /integrals/rrdm.
void add_section_inertia(ffr::formats::Sid& sid, double b, double h);

/// Slider-crank along x: rigid crank (hub at the origin) driven at omega [rad/s], the flexible rod
/// (SID file, its frame at the crank pin), rigid slider; revolute joints about z and a prismatic
/// guide (3 redundant conditions).
struct SliderCrank {
  std::string sid_file;
  double crank_mass = 0.36, crank_com = 0.075;      ///< com on the crank's axis [m]
  Eigen::Vector3d crank_inertia{1e-5, 7.02e-4, 7.02e-4};  ///< principal, about the com
  double rod_x = 0.15;                                ///< rod frame origin (the crank pin) [m]
  double rod_vy = 0, rod_omega = 0;                   ///< initial velocity of the pin, angular rate
  std::vector<double> modal_coordinates, modal_velocities;  ///< empty: at rest, undeformed
  double slider_mass = 0.075552, slider_x = 0.45, slider_vx = 0;
  double omega = 150.0, step = 1e-3, end = 1.0;
  double penalty = 0;                                 ///< 0: the solver's default
};
std::string slider_crank_json(const SliderCrank& s);

/// The benchmark's: IVP Test Set geometry (crank 0.15 m, rod 0.3 m), rod started with the
/// crank's motion.
std::string slider_crank_json(const std::string& sid_file, double step, double end, double omega);

/// Per-step figures of one run of a model's whole time loop.
struct StepTiming {
  double us_per_step = 0, iterations_per_step = 0, factorizations_per_step = 0, solves_per_step = 0;
};

/// Runs `data` (constructed and initialized for `model`) to the end of the model's time span,
/// timing only the steps; trace, if given, gets the first coordinate of the last body after
/// every step (reserved before the loop, so the timed loop allocates nothing).
StepTiming run_timed(const ffr::runtime::Model& model, ffr::runtime::Data& data, std::vector<double>* trace = nullptr);

/// A fresh temporary directory.
std::filesystem::path temp_dir(const std::string& tag);

}  // namespace bench
