#pragma once
// The flexible slider-crank of the IVP Test Set (B. Simeon 1996; F. Mazzia, C. Magherini,
// F. Iavernaro, Test Set for IVP Solvers, release 2.3, problem "crank") as a model of the
// benchmark's builder (tools/models), with the Test Set's initial values; its rod is
// simeon_rod_sid() written as rod.sid.h5 next to the model. For the tests that link
// ffr_bench_runtime_models.

#include "simeon_rod.hpp"

#include "models.hpp"  // tools/models: the benchmark's slider-crank

#include <string>

namespace ffr::runtime::test {

inline std::string simeon_crank_json(double h, double end = 0.1, double penalty = 1e4) {
  using D = SimeonData;
  bench::SliderCrank s;
  s.sid_file = "rod.sid.h5";
  // Crank: a 0.15 m bar of mass M1 whose inertia about the hub is J1.
  const double Izz = D::J1 - D::M1 * (D::L1 / 2) * (D::L1 / 2);
  s.crank_mass = D::M1;
  s.crank_com = D::L1 / 2;
  s.crank_inertia = Eigen::Vector3d(1e-6, Izz, Izz);
  s.rod_x = D::L1;
  s.rod_vy = D::L1 * D::OMEGA;
  s.rod_omega = -74.9957670;
  s.modal_coordinates = {0, 0, 0.103339863e-4, 0.169327969e-4};
  s.modal_velocities = {0.444896105, 0.463434311e-2, -0.178591076e-5, -0.268938672e-5};
  s.slider_mass = D::M3;
  s.slider_x = 0.450016933;
  s.slider_vx = -0.268938672e-5;
  s.omega = D::OMEGA;
  s.step = h;
  s.end = end;
  s.penalty = penalty;
  return bench::slider_crank_json(s);
}

}  // namespace ffr::runtime::test
