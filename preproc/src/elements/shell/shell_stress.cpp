// Nodal stresses of a linear shell solution (modal stress recovery, preproc/PART_FILE.md
// `stress`), as a linear map of the element's displacement. The resultants N, M, Q at the
// element's in-plane integration points (the same fields as shell_resultants(): membrane
// strains with the condensed incompatible modes or OPT's higher-order strains, plate
// curvatures, MITC4 shear) are extrapolated to the corners by the corner shape functions
// through those points (QUAD4: bilinear through the 2 x 2 Gauss points; TRI3: linear through
// the 3 interior points), the way CalculiX and Abaqus extrapolate element stresses and the
// solid recovery does. Through the thickness the plane-stress shell assumption gives, at height
// z along e3,
//   sigma_ab(z) = N_ab / t + 12 M_ab z / t^3     (linear: membrane + bending),
//   sigma_a3(z) = 3 Q_a / (2 t) (1 - 4 z^2 / t^2) (the parabolic transverse shear),
//   sigma_33 = 0,
// so the surfaces z = +-t/2 carry N/t +- 6 M/t^2 and no transverse shear, the mid-surface N/t
// and the peak shear 3 Q / (2 t). M = D kappa with kappa the curvature of the fibre rotations
// (beta_x, beta_y) = (ry, -rx) (u(z) = u0 + z beta), so a positive M stretches the +e3 side.
// The tensor is rotated from the element's axes to body axes: sigma_body = R^T sigma_local R.
#include "ffr/preproc/elements/shell.hpp"

#include "local_shell.hpp"
#include "material_check.hpp"
#include "shape2d.hpp"

#include <Eigen/Dense>

namespace ffr::preproc {
namespace {

// X (corners x points): corner values = X * values at the points (square for both rules).
Eigen::MatrixXd corner_extrapolation(ElementType type, const std::vector<Eigen::Vector2d>& xi) {
  const int n = num_nodes(type), ng = static_cast<int>(xi.size());
  Eigen::MatrixXd A(ng, n);
  for (int g = 0; g < ng; ++g)
    A.row(g) = type == ElementType::Quad4 ? Eigen::VectorXd(shell::quad4_N(xi[g].x(), xi[g].y())).transpose()
                                          : Eigen::VectorXd(shell::tri3_N(xi[g].x(), xi[g].y())).transpose();
  return A.colPivHouseholderQr().solve(Eigen::MatrixXd::Identity(ng, ng));
}

// V (6 x 6): body-axis Voigt (xx, yy, zz, xy, yz, xz) = V * local-axis Voigt, from
// sigma_body = R^T sigma_local R (R's rows are the local axes in body axes).
Eigen::Matrix<double, 6, 6> voigt_rotation(const Eigen::Matrix3d& R) {
  constexpr int ij[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};
  Eigen::Matrix<double, 6, 6> V;
  for (int c = 0; c < 6; ++c) {
    Eigen::Matrix3d S = Eigen::Matrix3d::Zero();
    S(ij[c][0], ij[c][1]) = S(ij[c][1], ij[c][0]) = 1;
    const Eigen::Matrix3d B = R.transpose() * S * R;
    for (int r = 0; r < 6; ++r) V(r, c) = B(ij[r][0], ij[r][1]);
  }
  return V;
}

// P (3n x 6n): a part's DOFs from the 6n local DOFs (the matrix of shell::gather).
Eigen::MatrixXd selection(int n, const int (&dofs)[3]) {
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(3 * n, 6 * n);
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) P(3 * i + a, 6 * i + dofs[a]) = 1;
  return P;
}

}  // namespace

ShellStressMap shell_stress_map(ElementType type, const Eigen::MatrixX3d& xe, const ShellSection& section) {
  shell::check_input(type, xe, section);
  const shell::LocalShell l = shell::local_shell(type, xe, section);
  const int n = static_cast<int>(xe.rows());
  const double t = section.thickness;
  const Eigen::Matrix3d Dm = shell::plane_stress(section.material.E, section.material.nu);  // N/t
  const Eigen::Matrix3d Db = Dm * (t / 2);                                                    // 6 M/t^2
  const double Ds = 1.5 * 5.0 / 6.0 * section.material.E / (2 * (1 + section.material.nu));  // 3 Q/(2t)
  const Eigen::MatrixXd Pm = selection(n, shell::kMembraneDof) * l.T, Pp = selection(n, shell::kPlateDof) * l.T;
  const Eigen::MatrixXd X = corner_extrapolation(type, l.membrane.xi);
  if (l.plate.xi.size() != l.membrane.xi.size()) structural::fail(shell::who(type), "membrane and plate points differ");
  const Eigen::Matrix<double, 6, 6> V = voigt_rotation(l.frame.R);

  ShellStressMap out;
  out.normal = l.frame.R.row(2).transpose();
  out.top = out.middle = out.bottom = Eigen::MatrixXd::Zero(6 * n, 6 * n);
  for (std::size_t g = 0; g < l.membrane.xi.size(); ++g) {
    const Eigen::MatrixXd m = Dm * l.membrane.B[g] * Pm;  // 3 x 6n: (xx, yy, xy) membrane stress
    const Eigen::MatrixXd b = Db * l.plate.B[g] * Pp;     // bending stress at z = +t/2
    Eigen::MatrixXd s = Eigen::MatrixXd::Zero(2, 6 * n);  // (xz, yz) peak transverse shear
    if (!l.plate.Bs.empty()) s = Ds * l.plate.Bs[g] * Pp;
    Eigen::MatrixXd top = Eigen::MatrixXd::Zero(6, 6 * n), mid = top, bot = top;
    for (int c = 0; c < 2; ++c) {  // local Voigt rows xx, yy
      top.row(c) = m.row(c) + b.row(c);
      mid.row(c) = m.row(c);
      bot.row(c) = m.row(c) - b.row(c);
    }
    top.row(3) = m.row(2) + b.row(2);
    mid.row(3) = m.row(2);
    bot.row(3) = m.row(2) - b.row(2);
    mid.row(4) = s.row(1);  // yz
    mid.row(5) = s.row(0);  // xz
    for (int a = 0; a < n; ++a) {
      const double w = X(a, static_cast<Eigen::Index>(g));
      out.top.middleRows(6 * a, 6) += w * V * top;
      out.middle.middleRows(6 * a, 6) += w * V * mid;
      out.bottom.middleRows(6 * a, 6) += w * V * bot;
    }
  }
  return out;
}

}  // namespace ffr::preproc
