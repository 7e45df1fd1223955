#pragma once
// The shell obstacle course (MacNeal & Harder, Finite Elem. Anal. Des. 1 (1985) 3–20;
// Belytschko, Stolarski, Liu, Carpenter & Ong, CMAME 51 (1985) 221–258) on structured meshes
// generated here. Each function returns the displacement the benchmark quotes.

#include "ffr/preproc/mesh/mesh.hpp"

namespace ffr::test {

/// Scordelis–Lo roof: R = 25, L = 50, 80 deg arc, t = 0.25, E = 4.32e8, nu = 0, self weight 90
/// per unit area; ends on rigid diaphragms. Quarter model, n x n. Returns the vertical
/// deflection (downward positive) at the midspan of the free edge; reference 0.3024.
double scordelis_lo(int n, preproc::ElementType type);

/// Pinched cylinder with end diaphragms: R = 300, L = 600, t = 3, E = 3e6, nu = 0.3, two
/// opposite unit loads at midspan. Octant model, n x n. Returns the radial deflection under
/// the load; reference 1.8248e-5.
double pinched_cylinder(int n, preproc::ElementType type);

/// Pinched hemisphere with an 18 deg hole at the pole (MacNeal–Harder): R = 10, t = 0.04,
/// E = 6.825e7, nu = 0.3, four radial loads of 2 alternating in/out on the equator. Quarter
/// model, n x n. Returns the outward displacement under an outward load; reference 0.094.
double pinched_hemisphere(int n, preproc::ElementType type);

/// Twisted beam (MacNeal–Harder): L = 12, w = 1.1, t = 0.32, 90 deg twist, E = 29e6, nu = 0.22,
/// clamped root, unit tip load in the tip's width (in_plane = true) or thickness direction.
/// nw x nl elements. Returns the tip deflection along the load; references 5.424e-3 / 1.754e-3.
double twisted_beam(int nw, int nl, bool in_plane, preproc::ElementType type);

}  // namespace ffr::test
