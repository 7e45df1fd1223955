#pragma once
// Geometric stiffening of a reduced body (formats/SPEC.md section 10; the stiffness change of a
// finite element in a moving frame, docs/references.md).
//
// Unit load cases, each solved statically under the body's reference conditions:
//  - translational acceleration e_c of the frame: inertial body force -rho e_c      -> K0t[:, :, c]
//  - angular acceleration e_c:                    -rho (e_c x c)                    -> K0r[:, :, c]
//  - each centrifugal product omega_bar_j:        -rho B_j c, where B_j is the
//    coefficient of omega_bar_j in skew(w) skew(w) = w w^T - |w|^2 I                -> K0om[:, :, j]
//  - unit force / moment e_c at each interface node not held                        -> K0F, K0M
// Reference conditions: clamped -> the interface held; Craig–Bampton -> the frame and every
// boundary interface held; free -> inertia relief (the load minus its rigid-body part
// M R (R^T M R)^-1 R^T f, solved on a statically determinate support and made M-orthogonal
// to the rigid-body modes).
// Projection: K0_L[k](i, .) = Phi_i^T K_G(sigma_L) Phi_k, K_G the element geometric stiffness.
// Sign: with these loads, the terms add to the modal stiffness as written in the modal
// equation of formats/SPEC.md section 6 (Ct(q) a, Cr(q) alpha on the left, -Oe(q) omega_bar on
// the right): a spinning cantilever stiffens (Southwell).
//
// Prestress (ksigma): a static preload (gravity and forces at interfaces) solved the same way;
// ksigma.M1 = Phi^T K_G(sigma_pre) Phi and ksigma.M0 = Phi^T K u_pre (the modal internal force
// of the preloaded state, in equilibrium with the preload itself).

#include "ffr/formats/sid.hpp"
#include "ffr/preproc/assembly/assembly.hpp"
#include "ffr/preproc/part/part.hpp"

#include <functional>
#include <string>

namespace ffr::preproc {

struct StiffeningResult {
  formats::Stiffening stiffening;
  formats::KSigma ksigma;   ///< zero-sized unless the part has a preload
  int load_cases = 0;
};

/// The unit load cases (if `unit_cases`) and the part's preload (if any).
StiffeningResult compute_stiffening(const FeModel& model, const Assembled& fe, const Eigen::MatrixXd& Phi,
                                    bool unit_cases, const std::function<void(const std::string&)>& log = {});

/// Coefficient matrix of omega_bar_j in skew(w) skew(w) (j in the order xx, yy, zz, xy, yz, xz).
Eigen::Matrix3d centrifugal_coefficient(int j);

}  // namespace ffr::preproc
