// solid_element(): stiffness (isotropic, per stiffness rule; HEX8 via incompatible modes),
// consistent mass and the mass samples that carry it exactly.
#include "ffr/preproc/elements/solid.hpp"

#include "isoparametric.hpp"

#include <cmath>
#include <sstream>

namespace ffr::preproc {

void check_solid_material(const Material& mat) {
  std::ostringstream m;
  if (!(std::isfinite(mat.E) && mat.E > 0)) {
    m << "material: Young's modulus E = " << mat.E << " must be positive and finite";
  } else if (!(std::isfinite(mat.nu) && mat.nu > -1 && mat.nu < 0.5)) {
    m << "material: Poisson's ratio nu = " << mat.nu << " must lie in (-1, 0.5)";
    if (mat.nu == 0.5) m << " (nu = 0.5 is incompressible, which displacement elements cannot represent)";
  } else if (!(std::isfinite(mat.rho) && mat.rho >= 0)) {
    m << "material: density rho = " << mat.rho << " must be non-negative and finite";
  } else {
    return;
  }
  throw ElementError(m.str());
}

ElementMatrices solid_element(ElementType t, const Eigen::MatrixX3d& xe, const Material& mat,
                              const SolidOptions& opt) {
  check_solid_material(mat);
  const SolidShape& s = solid_shape(t);
  detail::check_geometry(s, xe);
  const int nn = s.nodes, ndof = 3 * nn;
  const detail::Lame L = detail::lame(mat);

  ElementMatrices em;
  em.dofs_per_node = 3;
  if (t == ElementType::Hex8 && opt.hex8_incompatible) {
    em.K = detail::hex8_incompatible(s, xe, L).K;
  } else {
    em.K.setZero(ndof, ndof);
    ShapeGradients G(nn, 3);
    for (int g = 0; g < s.stiffness_rule.size(); ++g) {
      const Eigen::Matrix3d J = detail::jacobian(xe, s.dN_stiffness[g]);
      detail::physical_gradients(s.dN_stiffness[g], J.inverse(), G);
      detail::add_isotropic_stiffness(em.K, G, L, s.stiffness_rule.w[g] * J.determinant());
    }
  }

  // Consistent mass: M = sum_g w_g N_g^T N_g with N_g = [N_a I3]; the scalar nn x nn part
  // first, then expanded per component.
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(nn, nn);
  if (opt.mass_samples) em.samples.resize(s.mass_rule.size());
  for (int g = 0; g < s.mass_rule.size(); ++g) {
    const ShapeValues& N = s.N_mass[g];
    const double w = mat.rho * s.mass_rule.w[g] * detail::jacobian(xe, s.dN_mass[g]).determinant();
    m.noalias() += w * N * N.transpose();
    if (!opt.mass_samples) continue;
    MassSample& ms = em.samples[g];
    ms.w = w;
    ms.c = xe.transpose() * N;
    ms.N.setZero(3, ndof);
    for (int a = 0; a < nn; ++a)
      for (int i = 0; i < 3; ++i) ms.N(i, 3 * a + i) = N[a];
  }
  em.M.setZero(ndof, ndof);
  for (int a = 0; a < nn; ++a)
    for (int b = 0; b < nn; ++b)
      for (int i = 0; i < 3; ++i) em.M(3 * a + i, 3 * b + i) = m(a, b);
  return em;
}

}  // namespace ffr::preproc
