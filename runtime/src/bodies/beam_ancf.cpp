// The gradient-deficient ANCF beam element (FORMULATION.md section 15): its inertia as shape
// integrals, its elastic and damping forces and their tangents.
#include "ffr/runtime/beam.hpp"

#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/model.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>

namespace ffr::runtime {
namespace {

using Vec12 = Eigen::Matrix<double, 12, 1>;
using Mat12 = Eigen::Matrix<double, 12, 12>;
using Mat312 = Eigen::Matrix<double, 3, 12>;

// Gauss-Legendre points on [0, 1]. Five points integrate the mass (degree 6) exactly and the
// rational strain energy of a curved element far below the discretisation error.
constexpr int kGauss = 5;
constexpr double kXi[kGauss] = {0.046910077030668, 0.230765344947158, 0.5, 0.769234655052842, 0.953089922969332};
constexpr double kW[kGauss] = {0.118463442528095, 0.239314335249683, 0.284444444444444, 0.239314335249683,
                               0.118463442528095};

// Cubic Hermite shape functions of an element of length l at xi = x / l, for its four nodal
// vectors [r_i, r_x,i, r_j, r_x,j], and their first and second x-derivatives.
Eigen::Vector4d shape(double xi, double l) {
  const double x2 = xi * xi, x3 = x2 * xi;
  return {1 - 3 * x2 + 2 * x3, l * (xi - 2 * x2 + x3), 3 * x2 - 2 * x3, l * (x3 - x2)};
}
Eigen::Vector4d shape_x(double xi, double l) {
  return Eigen::Vector4d(-6 * xi + 6 * xi * xi, l * (1 - 4 * xi + 3 * xi * xi), 6 * xi - 6 * xi * xi, l * (3 * xi * xi - 2 * xi)) / l;
}
Eigen::Vector4d shape_xx(double xi, double l) {
  return Eigen::Vector4d(-6 + 12 * xi, l * (-4 + 6 * xi), 6 - 12 * xi, l * (-2 + 6 * xi)) / (l * l);
}

// The 3 x 12 matrix [s_0 I, s_1 I, s_2 I, s_3 I].
Mat312 expand(const Eigen::Vector4d& s) {
  Mat312 S = Mat312::Zero();
  for (int v = 0; v < 4; ++v) S.block<3, 3>(0, 3 * v).diagonal().setConstant(s(v));
  return S;
}

Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0, -a(2), a(1), a(2), 0, -a(0), -a(1), a(0), 0;
  return m;
}

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

// One element at its coordinates qe and rates qde: adds its elastic and damping force to fe,
// their tangents to Ke, Ce (when non-null); returns its strain energy.
double element(const AncfBeam& beam, const Vec12& qe, const Vec12& qde, Vec12& fe, Mat12* Ke, Mat12* Ce, bool damp) {
  const double l = beam.element_length();
  double U = 0;
  for (int gp = 0; gp < kGauss; ++gp) {
    const double w = kW[gp] * l;
    const Mat312 Sx = expand(shape_x(kXi[gp], l));
    const Mat312 Sxx = expand(shape_xx(kXi[gp], l));
    const Eigen::Vector3d rp = Sx * qe, rpp = Sxx * qe;
    const double g = rp.squaredNorm();
    const double eps = 0.5 * (g - 1);
    const Vec12 p = Sx.transpose() * rp;  // d eps / dq
    const Eigen::Vector3d f = rp.cross(rpp);
    const Mat312 F = skew(rp) * Sxx - skew(rpp) * Sx;  // df / dq
    const double ff = f.squaredNorm(), g3 = g * g * g, g4 = g3 * g;
    const Vec12 Ff = F.transpose() * f;
    U += w * 0.5 * (beam.EA * eps * eps + beam.EI * ff / g3);
    // dU/dq = EA eps p + EI (F^T f / g^3 - 3 |f|^2 / g^4 p)
    fe.noalias() += w * (beam.EA * eps * p + beam.EI * (Ff / g3 - 3 * ff / g4 * p));
    if (Ke) {
      // The 12 x 12 products are coefficient-based (lazyProduct): Eigen's default for these
      // fixed sizes is its blocked matrix product, whose packing and dispatch cost more than the
      // few hundred multiply-adds (with the copies, half of the 16-element pendulum's step).
      const Mat12 StS = Sx.transpose().lazyProduct(Sx);
      // The second derivative of f . f_frozen: -Sx^T [f]x Sxx + Sxx^T [f]x Sx (symmetric).
      const Eigen::Matrix3d fx = skew(f);
      const Mat312 fxSx = fx * Sx, fxSxx = fx * Sxx;
      const Mat12 Hf = Sxx.transpose().lazyProduct(fxSx) - Sx.transpose().lazyProduct(fxSxx);
      const Mat12 pp = p.lazyProduct(p.transpose());
      const Mat12 Ffp = Ff.lazyProduct(p.transpose());
      Mat12 H = beam.EA * (pp + eps * StS);
      H += beam.EI * ((F.transpose().lazyProduct(F) + Hf) / g3 - 6 / g4 * (Ffp + Ffp.transpose()) + 24 * ff / (g4 * g) * pp -
                      3 * ff / g4 * StS);
      *Ke += w * H;
    }
    if (damp && beam.tau > 0) {
      // Kelvin-Voigt: the stresses tau EA eps_dot, tau EI kappa_dot on the strain and curvature
      // vector k = f / g^(3/2) rates: Q = -tau (EA p p^T + EI Jk^T Jk) q_dot, Jk = dk/dq.
      const double gs = std::sqrt(g);
      const Mat312 Jk = F / (g * gs) - 3 / (g * g * gs) * f * p.transpose();
      const Mat12 D = beam.tau * (beam.EA * p.lazyProduct(p.transpose()) + beam.EI * Jk.transpose().lazyProduct(Jk));
      fe.noalias() += w * (D * qde);
      if (Ce) *Ce += w * D;
    }
  }
  return U;
}

}  // namespace

double ancf_beam_forces(const AncfBeam& beam, const Eigen::Ref<const Eigen::VectorXd>& y,
                        const Eigen::Ref<const Eigen::VectorXd>& yd, Eigen::Ref<Eigen::VectorXd> Qy, Eigen::MatrixXd* K,
                        Eigen::MatrixXd* C) {
  double U = 0;
  Mat12 Ke, Ce;
  for (int e = 0; e < beam.elements; ++e) {
    // An element's coordinates are contiguous: node e's [r, r_x], then node e + 1's.
    const Vec12 qe = beam.q0.segment<12>(6 * e) + y.segment<12>(6 * e);
    const Vec12 qde = yd.segment<12>(6 * e);
    Vec12 fe = Vec12::Zero();
    Ke.setZero();
    Ce.setZero();
    U += element(beam, qe, qde, fe, K ? &Ke : nullptr, C ? &Ce : nullptr, true);
    Qy.segment<12>(6 * e) -= fe;
    if (K) K->block<12, 12>(6 * e, 6 * e) += Ke;
    if (C) C->block<12, 12>(6 * e, 6 * e) += Ce;
  }
  return U;
}

double ancf_beam_energy(const AncfBeam& beam, const Eigen::Ref<const Eigen::VectorXd>& y) {
  double U = 0;
  for (int e = 0; e < beam.elements; ++e) {
    const Vec12 qe = beam.q0.segment<12>(6 * e) + y.segment<12>(6 * e);
    Vec12 fe = Vec12::Zero();
    U += element(beam, qe, Vec12::Zero(), fe, nullptr, nullptr, false);
  }
  return U;
}

std::string beam_coordinate_name(int k) {
  return "node n" + std::to_string(k / 6) + (k % 6 < 3 ? " position " : " slope ") + "xyz"[k % 3];
}

Body make_beam_body(const std::string& name, const Eigen::Vector3d& start, const Eigen::Vector3d& end, int elements,
                    double E, double rho, double area, double inertia, double tau, const std::string& file,
                    const std::string& field) {
  if (elements < 1) throw ModelError(file, field + ".elements", "must be at least 1 (found " + std::to_string(elements) + ")");
  const double L = (end - start).norm();
  const double size = std::max(start.cwiseAbs().maxCoeff(), end.cwiseAbs().maxCoeff());
  if (!(L > 1e-12 * std::max(1.0, size)))
    throw ModelError(file, field + ".end", "the beam has zero length (end equals start, " + num(L) + " m apart)");
  auto beam = std::make_shared<AncfBeam>();
  beam->elements = elements;
  beam->length = L;
  beam->EA = E * area;
  beam->EI = E * inertia;
  beam->rhoA = rho * area;
  beam->tau = tau;
  const int nq = beam->nq();
  const Eigen::Vector3d t0 = (end - start) / L;
  const double l = L / elements;
  beam->q0.resize(nq);
  for (int k = 0; k <= elements; ++k) {
    beam->q0.segment<3>(6 * k) = start + (k * l) * t0;
    beam->q0.segment<3>(6 * k + 3) = t0;
  }

  Body b;
  b.name = name;
  b.flexible = true;
  b.nq = nq;
  b.mass = beam->rhoA * L;
  b.r0.setZero();
  b.A0.setIdentity();
  b.Pdm = Matrix3Xd::Zero(3, nq);
  for (auto& r : b.rPdm) r = Matrix3Xd::Zero(3, nq);
  for (auto& row : b.PPdm)
    for (auto& m : row) m = MatrixXd::Zero(nq, nq);
  // Shape integrals with Phi = S(x) and c(x) = S(x) q0 (FORMULATION.md 3): every material point
  // is r0 + A (c + S y) with the frame held at the global one.
  for (int e = 0; e < elements; ++e)
    for (int gp = 0; gp < kGauss; ++gp) {
      const double dm = beam->rhoA * kW[gp] * l;
      const Eigen::Vector4d s = shape(kXi[gp], l);
      const Mat312 S = expand(s);
      const Eigen::Vector3d c = S * beam->q0.segment<12>(6 * e);
      b.rdm += dm * c;
      b.J0 += dm * c * c.transpose();
      b.Pdm.middleCols<12>(6 * e) += dm * S;
      for (int a = 0; a < 3; ++a) b.rPdm[a].middleCols<12>(6 * e) += (dm * c(a)) * S;
      for (int v = 0; v < 4; ++v)
        for (int u = 0; u < 4; ++u)
          for (int a = 0; a < 3; ++a)
            for (int c2 = 0; c2 < 3; ++c2) b.PPdm[a][c2](6 * e + 3 * v + a, 6 * e + 3 * u + c2) += dm * s(v) * s(u);
    }
  b.Myy = MatrixXd::Zero(nq, nq);
  for (int a = 0; a < 3; ++a) b.Myy += b.PPdm[a][a];
  b.PsiI = MatrixXd::Zero(nq, 3);
  b.Ke = MatrixXd::Zero(nq, nq);  // the elastic forces are the element's (ancf_beam_forces)
  b.De = MatrixXd::Zero(nq, nq);
  // Nodes n0 .. nN, then start and end (the same as n0 and nN). A node's small rotation is
  // t0 x (its slope's change): no torsion (FORMULATION.md 15, what joints may read of it).
  const auto node = [&](const std::string& n, int k) {
    NodeSlice s;
    s.name = n;
    s.origin = beam->q0.segment<3>(6 * k);
    s.phi = Matrix3Xd::Zero(3, nq);
    s.phi.block<3, 3>(0, 6 * k).setIdentity();
    s.psi = Matrix3Xd::Zero(3, nq);
    s.psi.block<3, 3>(0, 6 * k + 3) = skew(t0);
    b.nodes.push_back(std::move(s));
  };
  for (int k = 0; k <= elements; ++k) node("n" + std::to_string(k), k);
  node("start", 0);
  node("end", elements);
  b.y0 = VectorXd::Zero(nq);
  b.yd0 = VectorXd::Zero(nq);
  b.beam = std::move(beam);
  return b;
}

}  // namespace ffr::runtime
