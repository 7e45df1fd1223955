#pragma once
// The flexible connecting rod of the slider-crank benchmark of the IVP Test Set ("crank",
// B. Simeon, "Modelling a flexible slider crank mechanism by a mixed system of DAEs and PDEs",
// Math. Modelling of Systems 2 (1996) 1-18; IVP Test Set, F. Mazzia, C. Magherini, F. Iavernaro,
// release 2.3, crank.f) as a SID: the same shape functions and matrices, turned into the
// primitive integrals of formats/SPEC.md section 8.
//
// Rod along the body x axis from node A (x = 0, the crank pin) to node B (x = L2). Modes:
//   q1, q2  lateral (y): sin(pi xi), sin(2 pi xi)        (xi = x / L2)
//   q3, q4  axial (x): 4 xi (1 - xi), xi (2 xi - 1)      (quadratic element, middle and end node)
// Matrices exactly as published in crank.f (including its truncated PI = 3.1415927 and its axial
// mass block FACM [8 1; 1 2], which is what the published reference solution integrates).

#include "ffr/formats/sid.hpp"

#include <vector>

namespace ffr::runtime::test {

struct SimeonData {
  static constexpr double M1 = 0.36, M2 = 0.151104, M3 = 0.075552, L1 = 0.15, L2 = 0.30;
  static constexpr double J1 = 0.002727, J2 = 0.0045339259, EE = 0.20e12, BB = 0.0080, HH = 0.0080;
  static constexpr double RHO = 7870.0, OMEGA = 150.0, PI = 3.1415927;
};

formats::Sid simeon_rod_sid();

/// The rod's /sid/Ke/M1 from the same shape functions (formats/SPEC.md): the geometric stiffness
/// of each mode's stress, M1[k](i,j) = int N_k (u_i' u_j' + w_i' w_j') dx with N_k = EA u_k' the
/// axial force of mode k (bending stresses have no resultant in a beam), so the strain energy
/// gains the cubic terms of the von Karman beam, int EA u' (u'^2 + w'^2) / 2 dx.
std::vector<Eigen::MatrixXd> simeon_rod_ke_m1();

}  // namespace ffr::runtime::test
