// The gradient-deficient ANCF beam element (FORMULATION.md section 15): its inertia as shape
// integrals, its elastic and damping forces and their tangents.
#include "ffr/runtime/beam.hpp"

#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/model.hpp"

#include "../integrator/kernel_clones.hpp"
#include "../number_text.hpp"

#include <Eigen/Geometry>

#include <cmath>

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

// Adds w (sxx sxx^T (x) A + sxx sx^T (x) B + sx sxx^T (x) B^T + sx sx^T (x) C) to the 12 x 12 K
// (column-major; A, B, C 3 x 3 column-major): a tangent term of the element in its 4 x 4 blocks of
// 3 x 3 (see element()). Column 3u + c of the term is sxx (x) a + sx (x) b with
// a = w (sxx_u A + sx_u B) e_c, b = w (sxx_u B^T + sx_u C) e_c: twelve contiguous rows, which the
// AVX2 clone (kernel_clones.hpp) takes four at a time. Why: summed by Eigen's 3 x 3 blocks on
// the baseline's SSE2, this term was a tenth of a 16-element beam's step.
FFR_RT_CLONES
void add_kronecker(const double* sx, const double* sxx, const double* A, const double* B, const double* C, double w,
                   double* K) {
  double s_xx[12], s_x[12];  // sxx and sx, each entry three times
  for (int v = 0; v < 4; ++v)
    for (int r = 0; r < 3; ++r) {
      s_xx[3 * v + r] = sxx[v];
      s_x[3 * v + r] = sx[v];
    }
  for (int u = 0; u < 4; ++u) {
    const double wxx = w * sxx[u], wx = w * sx[u];
    for (int c = 0; c < 3; ++c) {
      double a[12], b[12];  // a and b, four times over
      for (int r = 0; r < 3; ++r) {
        a[r] = wxx * A[r + 3 * c] + wx * B[r + 3 * c];
        b[r] = wxx * B[c + 3 * r] + wx * C[r + 3 * c];
      }
      for (int v = 1; v < 4; ++v)
        for (int r = 0; r < 3; ++r) {
          a[3 * v + r] = a[r];
          b[3 * v + r] = b[r];
        }
      double* __restrict k = K + 12 * (3 * u + c);
      for (int e = 0; e < 12; ++e) k[e] += s_xx[e] * a[e] + s_x[e] * b[e];
    }
  }
}
void add_kronecker(const Eigen::Vector4d& sx, const Eigen::Vector4d& sxx, const Eigen::Matrix3d& A,
                   const Eigen::Matrix3d& B, const Eigen::Matrix3d& C, double w, Mat12& K) {
  add_kronecker(sx.data(), sxx.data(), A.data(), B.data(), C.data(), w, K.data());
}

// The shape functions' derivatives at the Gauss points of an element of length l: the same for
// every element of a beam, so evaluated once a pass over its elements (at every Gauss point, with
// their divisions by l, they were a tenth of the element's instructions).
struct GaussShapes {
  Eigen::Vector4d sx[kGauss], sxx[kGauss];
  explicit GaussShapes(double l) {
    for (int gp = 0; gp < kGauss; ++gp) {
      sx[gp] = shape_x(kXi[gp], l);
      sxx[gp] = shape_xx(kXi[gp], l);
    }
  }
};

// One element at its coordinates qe and rates qde: adds its elastic and damping force to fe,
// their tangents to Ke, Ce (when non-null); returns its strain energy.
//
// The shape matrices are Kronecker products, S_x = sx^T (x) I3 over the four nodal vectors q_v
// (v = 0..3), so that with r' = S_x q, r'' = S_xx q, f = r' x r'':
//   p = d eps / dq:  p_v = sx_v r',    F = df/dq:  F_v = sxx_v [r']x - sx_v [r'']x,
//   (F^T f)_v = sx_v a - sxx_v b,  a = r'' x f,  b = r' x f,
// and every 12 x 12 term of the tangent is sxx sxx^T (x) A + sxx sx^T (x) B + sx sxx^T (x) B^T +
// sx sx^T (x) C for 3 x 3 matrices A, B, C of the Gauss point (add_kronecker). With
// P = [r']x^T [r']x, Q = [r'']x^T [r'']x, X = [r']x^T [r'']x = (r'.r'') I - r'' r'^T:
//   S_x^T S_x -> C = I;   p p^T -> C = r' r'^T;   F^T F -> A = P, B = -X, C = Q;
//   H_f = S_xx^T [f]x S_x - S_x^T [f]x S_xx (the second derivative of f . f_frozen) -> B = [f]x;
//   F^T f p^T + p f^T F -> B = -b r'^T, C = a r'^T + r' a^T.
// Why: the products of the expanded 3 x 12 matrices were three quarters multiplications by zero.
double element(const AncfBeam& beam, const GaussShapes& gs, const Vec12& qe, const Vec12& qde, Vec12& fe, Mat12* Ke,
               Mat12* Ce, bool damp) {
  const double l = beam.element_length();
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  double U = 0;
  for (int gp = 0; gp < kGauss; ++gp) {
    const double w = kW[gp] * l;
    const Eigen::Vector4d& sx = gs.sx[gp];
    const Eigen::Vector4d& sxx = gs.sxx[gp];
    Eigen::Vector3d rp = Eigen::Vector3d::Zero(), rpp = Eigen::Vector3d::Zero();
    for (int v = 0; v < 4; ++v) {
      rp += sx(v) * qe.segment<3>(3 * v);
      rpp += sxx(v) * qe.segment<3>(3 * v);
    }
    const double g = rp.squaredNorm();
    const double eps = 0.5 * (g - 1);
    const Eigen::Vector3d f = rp.cross(rpp);
    const double ff = f.squaredNorm(), g3 = g * g * g, g4 = g3 * g;
    const Eigen::Vector3d a = rpp.cross(f), b = rp.cross(f);
    const Eigen::Matrix3d rr = rp * rp.transpose();
    U += w * 0.5 * (beam.EA * eps * eps + beam.EI * ff / g3);
    // dU/dq = EA eps p + EI (F^T f / g^3 - 3 |f|^2 / g^4 p)
    const double c_F = beam.EI / g3, c_I = beam.EA * eps - 3 * beam.EI * ff / g4;
    const Eigen::Vector3d fx_part = w * (c_I * rp + c_F * a), fxx_part = (-w * c_F) * b;
    for (int v = 0; v < 4; ++v) fe.segment<3>(3 * v) += sx(v) * fx_part + sxx(v) * fxx_part;
    if (Ke) {
      // H = EA (p p^T + eps StS) + EI ((F^T F + H_f) / g^3 - 6 / g^4 (F^T f p^T + p f^T F)
      //     + 24 |f|^2 / g^5 p p^T - 3 |f|^2 / g^4 StS)
      const double c_rr = beam.EA + 24 * beam.EI * ff / (g4 * g), c_Fp = -6 * beam.EI / g4;
      const Eigen::Matrix3d P = g * I - rr;
      const Eigen::Matrix3d X = rp.dot(rpp) * I - rpp * rp.transpose();
      const Eigen::Matrix3d Q = rpp.squaredNorm() * I - rpp * rpp.transpose();
      const Eigen::Matrix3d ar = a * rp.transpose();
      const Eigen::Matrix3d A = c_F * P;
      const Eigen::Matrix3d B = c_F * (skew(f) - X) - c_Fp * (b * rp.transpose());
      const Eigen::Matrix3d C = c_F * Q + c_rr * rr + c_Fp * (ar + ar.transpose()) + c_I * I;
      add_kronecker(sx, sxx, A, B, C, w, *Ke);
    }
    if (damp && beam.tau > 0) {
      // Kelvin-Voigt: the stresses tau EA eps_dot, tau EI kappa_dot on the strain and curvature
      // vector k = f / g^(3/2) rates: Q = -tau (EA p p^T + EI Jk^T Jk) q_dot, Jk = dk/dq, its
      // blocks Jk_v = sxx_v J1 + sx_v J2 with J1 = [r']x / g^(3/2), J2 = -[r'']x / g^(3/2) - 3 f r'^T / g^(5/2).
      const double gs = std::sqrt(g);
      const Eigen::Matrix3d J1 = skew(rp) / (g * gs);
      const Eigen::Matrix3d J2 = -skew(rpp) / (g * gs) - (3 / (g * g * gs)) * f * rp.transpose();
      Eigen::Vector3d kd = Eigen::Vector3d::Zero();  // the curvature vector's rate Jk q_dot
      double ed = 0;                                 // the axial strain's rate p . q_dot
      for (int v = 0; v < 4; ++v) {
        kd += (sxx(v) * J1 + sx(v) * J2) * qde.segment<3>(3 * v);
        ed += sx(v) * rp.dot(qde.segment<3>(3 * v));
      }
      const double wt = w * beam.tau;
      const Eigen::Vector3d dx_part = wt * (beam.EA * ed * rp + beam.EI * J2.transpose() * kd),
                            dxx_part = (wt * beam.EI) * (J1.transpose() * kd);
      for (int v = 0; v < 4; ++v) fe.segment<3>(3 * v) += sx(v) * dx_part + sxx(v) * dxx_part;
      if (Ce)
        add_kronecker(sx, sxx, beam.EI * J1.transpose() * J1, beam.EI * J1.transpose() * J2,
                      beam.EA * rr + beam.EI * J2.transpose() * J2, wt, *Ce);
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
  const GaussShapes gs(beam.element_length());
  for (int e = 0; e < beam.elements; ++e) {
    // An element's coordinates are contiguous: node e's [r, r_x], then node e + 1's.
    const Vec12 qe = beam.q0.segment<12>(6 * e) + y.segment<12>(6 * e);
    const Vec12 qde = yd.segment<12>(6 * e);
    Vec12 fe = Vec12::Zero();
    if (K) Ke.setZero();
    if (C) Ce.setZero();
    U += element(beam, gs, qe, qde, fe, K ? &Ke : nullptr, C ? &Ce : nullptr, true);
    Qy.segment<12>(6 * e) -= fe;
    if (K) K->block<12, 12>(6 * e, 6 * e) += Ke;
    if (C) C->block<12, 12>(6 * e, 6 * e) += Ce;
  }
  return U;
}

void ancf_beam_tangents(const AncfBeam& beam, const Eigen::Ref<const Eigen::VectorXd>& y,
                        const Eigen::Ref<const Eigen::VectorXd>& yd, Eigen::Ref<Eigen::MatrixXd> K,
                        Eigen::Ref<Eigen::MatrixXd> C) {
  Mat12 Ke, Ce;
  const bool damped = beam.tau > 0;
  const GaussShapes gs(beam.element_length());
  for (int e = 0; e < beam.elements; ++e) {
    const Vec12 qe = beam.q0.segment<12>(6 * e) + y.segment<12>(6 * e);
    const Vec12 qde = yd.segment<12>(6 * e);
    Vec12 fe = Vec12::Zero();
    Ke.setZero();
    if (damped) Ce.setZero();
    element(beam, gs, qe, qde, fe, &Ke, damped ? &Ce : nullptr, damped);
    K.block<12, 12>(6 * e, 6 * e) += Ke;
    if (damped) C.block<12, 12>(6 * e, 6 * e) += Ce;
  }
}

double ancf_beam_energy(const AncfBeam& beam, const Eigen::Ref<const Eigen::VectorXd>& y) {
  double U = 0;
  const GaussShapes gs(beam.element_length());
  for (int e = 0; e < beam.elements; ++e) {
    const Vec12 qe = beam.q0.segment<12>(6 * e) + y.segment<12>(6 * e);
    Vec12 fe = Vec12::Zero();
    U += element(beam, gs, qe, Vec12::Zero(), fe, nullptr, nullptr, false);
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
  if (elements > kMaxAncfBeamElements)
    throw ModelError(file, field + ".elements",
                     "is " + std::to_string(elements) + "; an ancf beam has at most " + std::to_string(kMaxAncfBeamElements) +
                         " (its mass is held as a flexible body's dense shape integrals, which grow with the square of its " +
                         std::to_string(6LL * (elements + 1LL)) + " nodal coordinates); 16 elements give the elastica's tip to 0.006 %");
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
  for (int k = 0; k <= elements; ++k) {
    std::string n = "n";  // then the index (as one expression GCC 12 warns of a bogus memcpy bound)
    node(n += std::to_string(k), k);
  }
  node("start", 0);
  node("end", elements);
  b.y0 = VectorXd::Zero(nq);
  b.yd0 = VectorXd::Zero(nq);
  b.beam = std::move(beam);
  return b;
}

}  // namespace ffr::runtime
