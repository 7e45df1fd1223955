#pragma once
// Andrews' squeezing mechanism (seven-body mechanism): E. Hairer & G. Wanner, Solving Ordinary
// Differential Equations II, section VII.7, and the IVP Test Set (F. Mazzia, C. Magherini,
// release 2.3, problem "andrews"), whose published reference solution at t = 0.03 is below.
//
// Planar, seven rigid bodies with the test set's angles beta, Theta, gamma, Phi, delta, Omega,
// epsilon, modelled in 3-D with ten revolute joints about z (O, F, E three times, B, A twice,
// G, H; the out-of-plane conditions are redundant). The geometry is read from the test set's
// constraint equations and mass matrix (the point E reached through bodies 1-2, 3, 5-4 and 7-6;
// each centre of mass at the distance its mass-matrix terms give), the driving torque mom on
// body 1 and the spring c0 (rest length l0) from C to the point D of body 3.

#include <string>

namespace ffr::runtime::test {

/// The test set's reference at t = 0.03: beta, Theta, gamma, Phi, delta, Omega, epsilon.
constexpr double kAndrewsReference[7] = {0.1581077119629904e+2,  -0.1575637105984298e+2, 0.4082224013073101e-1,
                                         -0.5347301163226948e+0, 0.5244099658805304e+0,  0.5347301163226948e+0,
                                         0.1048080741042263e+1};
/// The test set's initial angles (at rest), same order.
constexpr double kAndrewsInitial[7] = {-0.0617138900142764496358948458001, 0.0, 0.455279819163070380255912382449,
                                       0.222668390165885884674473185609, 0.487364979543842550225598953530,
                                       -0.222668390165885884674473185609, 1.23054744454982119249735015568};

/// The model file's text; `solver` is the value of its "solver" key. Outputs: the joint
/// coordinates "O" (beta), "F" (Theta), "B" (gamma), "G" (Phi), "A5" (delta), "H" (Omega),
/// "A7" (epsilon), each the change from its initial angle.
std::string andrews_json(const std::string& solver);

/// The distance between the three ways of reaching E at the initial angles (geometry check).
double andrews_closure_gap();

}  // namespace ffr::runtime::test
