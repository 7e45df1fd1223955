#pragma once
// Frequencies of a reduced body spinning at constant speed about an axis through O, from the
// SID alone (the Campbell diagram).
//
// With O fixed (a = 0), constant angular velocity w = Omega e_axis (alpha = 0), the modal row
// of the equations of SPEC.md section 6,
//   Ct(q) a + Cr(q) alpha + Me q'' = -Ge(q') w - Oe(q) w_bar - Ke q - De q',
// becomes the linear, constant-coefficient system
//   Me q'' + (G + De) q' + (Ke + K_w) q = -Oe.M0 w_bar            (a constant: static offset)
// with the gyroscopic matrix G(i,k) = sum_c Ge[k](i,c) w_c  (antisymmetric: Ge[k](i,:) =
// -Ge[i](k,:)), and K_w(i,k) = sum_j (Oe.M1[k](i,j) + K0om[k](i,j)) w_bar_j, where the pure
// inertia part Oe.M1 is the centrifugal softening and K0om (when the file has it and
// stiffening is on) the geometric stiffening. Frequencies are those of q, i.e. seen in the
// rotating body frame. They are the eigenvalues lambda of the first-order form
// [q; q']' = [[0, I], [-Me^-1 K, -Me^-1 C]] [q; q'], reported as |Im lambda| / 2pi (the
// damped frequency; 0 for a divergent or overdamped pair), ascending.

#include "ffr/formats/sid.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace ffr::formats {

/// "x", "y" or "z" -> 0, 1, 2; throws std::invalid_argument otherwise.
int spin_axis_from_string(const std::string& s);

struct CampbellOptions {
  bool stiffening = true;  ///< add K0om when the file has /stiffening
  bool damping = true;     ///< include De
};

/// The matrices of the spinning body's modal equation M q'' + C q' + K q = const.
struct SpinningSystem {
  Eigen::MatrixXd M, C, K;
};
SpinningSystem spinning_system(const Sid& sid, int axis, double omega_rad_s, const CampbellOptions& options = {});

/// One frequency per mode [Hz], ascending; `growth` (optional) receives Re(lambda) [1/s] of
/// the same eigenvalues (positive: unstable).
Eigen::VectorXd spinning_frequencies_hz(const SpinningSystem& sys, Eigen::VectorXd* growth = nullptr);

struct Campbell {
  std::vector<double> speeds_rad_s;
  std::vector<std::vector<double>> frequency_hz;  ///< one row per speed, ascending
};
/// Throws std::invalid_argument for a bad axis or a non-finite speed.
Campbell campbell(const Sid& sid, int axis, const std::vector<double>& speeds_rad_s, const CampbellOptions& options = {});

}  // namespace ffr::formats
