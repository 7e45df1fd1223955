// The geometrically exact beam in directors (FORMULATION.md section 17): its node bodies and
// its two-node element with one-point (midpoint) strains.
//
// Every strain is a function of ten primitives, each a bilinear form of the element's eight
// vectors x = [r_a, d1_a, d2_a, d3_a, r_b, d1_b, d2_b, d3_b]:
//   s_i = axial((R - R^T) / 2)_i, R_ij = d_i,a . d_j,b  (the relative rotation's sin(theta) n)
//   c   = (tr R - 1) / 2                                 (its cos(theta))
//   g_i = (d_i,a + d_i,b) . (r_b - r_a) / 2               (the mean director along the chord, times h)
//   n_i = |d_i,a + d_i,b|^2                               (four times the mean director's square)
// and Gamma_i = 2 g_i / (h sqrt(n_i)) - delta_i3, K_i = theta s_i / (h sin(theta)). A primitive's
// gradient is linear in x and its Hessian constant, so the element's tangent is exact:
//   dW/dq = sum_m W_m G_m,  d2W/dq2 = sum_m W_m B_m + G^T W_pp G.
#include "ffr/runtime/beam.hpp"

#include "ffr/runtime/data.hpp"
#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/model.hpp"
#include "../number_text.hpp"

#include <Eigen/Geometry>

#include <array>
#include <cmath>

namespace ffr::runtime {
namespace {

using Vec24 = Eigen::Matrix<double, 24, 1>;
using Mat24 = Eigen::Matrix<double, 24, 24>;
using Vec10 = Eigen::Matrix<double, 10, 1>;
using Mat10 = Eigen::Matrix<double, 10, 10>;
using Mat10x24 = Eigen::Matrix<double, 10, 24>;

// A term w x_P . x_Q of a primitive (vectors numbered r_a 0, d1_a 1, d2_a 2, d3_a 3, r_b 4, ...).
struct Term {
  int P, Q;
  double w;
};
struct Primitive {
  std::array<Term, 4> terms;
  int count;
  double constant;
};

// s1, s2, s3, c, g1, g2, g3, n1, n2, n3.
constexpr std::array<Primitive, 10> kPrimitives = {{
    {{{{3, 6, 0.5}, {2, 7, -0.5}}}, 2, 0.0},
    {{{{1, 7, 0.5}, {3, 5, -0.5}}}, 2, 0.0},
    {{{{2, 5, 0.5}, {1, 6, -0.5}}}, 2, 0.0},
    {{{{1, 5, 0.5}, {2, 6, 0.5}, {3, 7, 0.5}}}, 3, -0.5},
    {{{{1, 4, 0.5}, {1, 0, -0.5}, {5, 4, 0.5}, {5, 0, -0.5}}}, 4, 0.0},
    {{{{2, 4, 0.5}, {2, 0, -0.5}, {6, 4, 0.5}, {6, 0, -0.5}}}, 4, 0.0},
    {{{{3, 4, 0.5}, {3, 0, -0.5}, {7, 4, 0.5}, {7, 0, -0.5}}}, 4, 0.0},
    {{{{1, 1, 1.0}, {1, 5, 2.0}, {5, 5, 1.0}}}, 3, 0.0},
    {{{{2, 2, 1.0}, {2, 6, 2.0}, {6, 6, 1.0}}}, 3, 0.0},
    {{{{3, 3, 1.0}, {3, 7, 2.0}, {7, 7, 1.0}}}, 3, 0.0},
}};

// The primitives' values and gradients G (rows) at q.
void primitives(const Vec24& q, Vec10& p, Mat10x24& G) {
  G.setZero();
  for (int m = 0; m < 10; ++m) {
    const Primitive& pr = kPrimitives[static_cast<std::size_t>(m)];
    double v = pr.constant;
    for (int t = 0; t < pr.count; ++t) {
      const Term& tm = pr.terms[static_cast<std::size_t>(t)];
      const auto xP = q.segment<3>(3 * tm.P), xQ = q.segment<3>(3 * tm.Q);
      v += tm.w * xP.dot(xQ);
      G.row(m).segment<3>(3 * tm.P) += tm.w * xQ.transpose();
      G.row(m).segment<3>(3 * tm.Q) += tm.w * xP.transpose();
    }
    p(m) = v;
  }
}

// Adds a * B_m (the primitive's constant Hessian) to K.
void add_primitive_hessian(int m, double a, Mat24& K) {
  const Primitive& pr = kPrimitives[static_cast<std::size_t>(m)];
  for (int t = 0; t < pr.count; ++t) {
    const Term& tm = pr.terms[static_cast<std::size_t>(t)];
    K.block<3, 3>(3 * tm.P, 3 * tm.Q).diagonal().array() += a * tm.w;
    K.block<3, 3>(3 * tm.Q, 3 * tm.P).diagonal().array() += a * tm.w;
  }
}

// F(u, c) = theta / sin(theta) with theta = atan2(sqrt(u), c), u = |s|^2, and its derivatives.
struct Fd {
  double F, Fu, Fc, Fuu, Fuc, Fcc;
};
Fd rotation_factor(double u, double c) {
  const double r2 = u + c * c;
  Fd d{};
  if (c > 0 && u < 1e-2 * c * c) {
    // Series of atan(sqrt(t)) / sqrt(t), t = u / c^2 (the closed form cancels near theta = 0).
    const double t = u / (c * c), c3 = c * c * c;
    d.F = (1 - t / 3 + t * t / 5 - t * t * t / 7 + t * t * t * t / 9) / c;
    d.Fu = (-1.0 / 3 + 2 * t / 5 - 3 * t * t / 7 + 4 * t * t * t / 9) / c3;
    d.Fuu = (2.0 / 5 - 6 * t / 7 + 12 * t * t / 9 - 20 * t * t * t / 11) / (c3 * c * c);
  } else {
    const double s = std::sqrt(u), th = std::atan2(s, c);
    d.F = th / s;
    d.Fu = c / (2 * u * r2) - th / (2 * u * s);
    d.Fuu = 3 * th / (4 * u * u * s) - 3 * c / (4 * u * u * r2) - c / (2 * u * r2 * r2);
  }
  d.Fc = -1 / r2;
  d.Fuc = 1 / (r2 * r2);
  d.Fcc = 2 * c / (r2 * r2);
  return d;
}

// The six strains at primitives p, their gradients D (6 x 10) and, when H is given, each
// strain's Hessian in the primitives (H[k], 10 x 10).
void strains(double h, const Vec10& p, Eigen::Matrix<double, 6, 1>& e, Eigen::Matrix<double, 6, 10>& D,
             std::array<Mat10, 6>* H) {
  D.setZero();
  for (int i = 0; i < 3; ++i) {
    const double g = p(4 + i), n = p(7 + i), sn = std::sqrt(n);
    e(i) = 2 * g / (h * sn) - (i == 2 ? 1.0 : 0.0);
    D(i, 4 + i) = 2 / (h * sn);
    D(i, 7 + i) = -g / (h * n * sn);
    if (H) {
      Mat10& Hi = (*H)[static_cast<std::size_t>(i)];
      Hi.setZero();
      Hi(4 + i, 7 + i) = Hi(7 + i, 4 + i) = -1 / (h * n * sn);
      Hi(7 + i, 7 + i) = 3 * g / (2 * h * n * n * sn);
    }
  }
  const Eigen::Vector3d s = p.head<3>();
  const double c = p(3);
  const Fd f = rotation_factor(s.squaredNorm(), c);
  for (int i = 0; i < 3; ++i) {
    e(3 + i) = f.F * s(i) / h;
    for (int j = 0; j < 3; ++j) D(3 + i, j) = (f.F * (i == j) + 2 * f.Fu * s(i) * s(j)) / h;
    D(3 + i, 3) = f.Fc * s(i) / h;
    if (!H) continue;
    Mat10& Hk = (*H)[static_cast<std::size_t>(3 + i)];
    Hk.setZero();
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < 3; ++k)
        Hk(j, k) = (2 * f.Fu * ((i == j) * s(k) + (i == k) * s(j) + (j == k) * s(i)) + 4 * f.Fuu * s(i) * s(j) * s(k)) / h;
      Hk(j, 3) = Hk(3, j) = (f.Fc * (i == j) + 2 * f.Fuc * s(i) * s(j)) / h;
    }
    Hk(3, 3) = f.Fcc * s(i) / h;
  }
}

}  // namespace

Eigen::Matrix<double, 6, 1> ge_beam_strains(const GeBeam& beam, const Vec24& q) {
  Vec10 p;
  Mat10x24 G;
  primitives(q, p, G);
  Eigen::Matrix<double, 6, 1> e;
  Eigen::Matrix<double, 6, 10> D;
  strains(beam.element_length(), p, e, D, nullptr);
  return e;
}

double ge_beam_element(const GeBeam& beam, int element, const Vec24& q, const Vec24& qd, Vec24& f, Mat24* K, Mat24* C) {
  const double h = beam.element_length();
  Vec10 p;
  Mat10x24 G;
  primitives(q, p, G);
  Eigen::Matrix<double, 6, 1> e;
  Eigen::Matrix<double, 6, 10> D;
  std::array<Mat10, 6> H;
  strains(h, p, e, D, K ? &H : nullptr);
  Eigen::Matrix<double, 6, 1> stiff;
  stiff << beam.CG, beam.CK;
  const Eigen::Matrix<double, 6, 1> de = e - beam.strain0.col(element);
  // W = h/2 sum_k C_k de_k^2: its gradient in the primitives, then in q.
  const Eigen::Matrix<double, 6, 1> sigma = h * stiff.cwiseProduct(de);  // h times the stress resultants
  const Vec10 Wp = D.transpose() * sigma;
  f.noalias() += G.transpose() * Wp;
  if (K) {
    Mat10 Wpp = D.transpose() * (h * stiff).asDiagonal() * D;
    for (int k = 0; k < 6; ++k) Wpp += sigma(k) * H[static_cast<std::size_t>(k)];
    for (int m = 0; m < 10; ++m) add_primitive_hessian(m, Wp(m), *K);
    // Coefficient-based products (lazyProduct): Eigen's default for these fixed sizes is its
    // blocked matrix product, whose packing and dispatch cost more than the multiply-adds.
    const Mat10x24 WG = Wpp.lazyProduct(G);
    K->noalias() += G.transpose().lazyProduct(WG);
  }
  if (beam.tau > 0) {
    // Kelvin-Voigt: stress resultants tau C_k de_k/dt on the strain rates J qd, J = D G. The
    // damping's dependence on q is left out of K (a Newton rate, not the solution).
    const Eigen::Matrix<double, 6, 24> J = D.lazyProduct(G);
    const Eigen::Matrix<double, 6, 1> rate = J * qd;
    f.noalias() += J.transpose() * ((h * beam.tau) * stiff.cwiseProduct(rate));
    if (C) {
      const Eigen::Matrix<double, 6, 24> SJ = (h * beam.tau * stiff).asDiagonal() * J;
      C->noalias() += J.transpose().lazyProduct(SJ);
    }
  }
  return 0.5 * h * de.dot(stiff.cwiseProduct(de));
}

void ge_beam_forces(const Model& model, const GeBeam& beam, Data& data, bool add_q, bool tangents) {
  Vec24 q, qd, f;
  Mat24 K, C;
  for (int e = 0; e < beam.elements; ++e) {
    const int oa = model.bodies[static_cast<std::size_t>(beam.node_bodies[static_cast<std::size_t>(e)])].offset;
    const int ob = model.bodies[static_cast<std::size_t>(beam.node_bodies[static_cast<std::size_t>(e + 1)])].offset;
    q << data.state.q.segment<12>(oa), data.state.q.segment<12>(ob);
    qd << data.state.qd.segment<12>(oa), data.state.qd.segment<12>(ob);
    f.setZero();
    if (tangents) {
      K.setZero();
      C.setZero();
    }
    ge_beam_element(beam, e, q, qd, f, tangents ? &K : nullptr, tangents ? &C : nullptr);
    if (add_q) {
      data.Q.segment<12>(oa) -= f.head<12>();
      data.Q.segment<12>(ob) -= f.tail<12>();
    }
    if (tangents) {
      const int o[2] = {oa, ob};
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
          data.K.block<12, 12>(o[i], o[j]) += K.block<12, 12>(12 * i, 12 * j);
          if (beam.tau > 0) data.C.block<12, 12>(o[i], o[j]) += C.block<12, 12>(12 * i, 12 * j);
        }
    }
  }
}

double ge_beam_energy(const Model& model, const GeBeam& beam, const Data& data) {
  double W = 0;
  const double h = beam.element_length();
  Vec24 q;
  for (int e = 0; e < beam.elements; ++e) {
    const int oa = model.bodies[static_cast<std::size_t>(beam.node_bodies[static_cast<std::size_t>(e)])].offset;
    const int ob = model.bodies[static_cast<std::size_t>(beam.node_bodies[static_cast<std::size_t>(e + 1)])].offset;
    q << data.state.q.segment<12>(oa), data.state.q.segment<12>(ob);
    const Eigen::Matrix<double, 6, 1> de = ge_beam_strains(beam, q) - beam.strain0.col(e);
    Eigen::Matrix<double, 6, 1> stiff;
    stiff << beam.CG, beam.CK;
    W += 0.5 * h * de.dot(stiff.cwiseProduct(de));
  }
  return W;
}

ElementTurn ge_beam_largest_turn(const Model& model, const GeBeam& beam, const Eigen::VectorXd& q) {
  ElementTurn worst;
  Vec24 qe;
  Vec10 p;
  Mat10x24 G;
  for (int e = 0; e < beam.elements; ++e) {
    const int oa = model.bodies[static_cast<std::size_t>(beam.node_bodies[static_cast<std::size_t>(e)])].offset;
    const int ob = model.bodies[static_cast<std::size_t>(beam.node_bodies[static_cast<std::size_t>(e + 1)])].offset;
    if (ob + 12 > q.size() || oa + 12 > q.size()) continue;
    qe << q.segment<12>(oa), q.segment<12>(ob);
    if (!qe.allFinite()) continue;
    primitives(qe, p, G);
    const double angle = std::atan2(p.head<3>().norm(), p(3));
    if (angle > worst.angle) worst = {e, angle};
  }
  return worst;
}

std::string ge_beam_failure_hint(const Model& model, const Eigen::VectorXd& q0, const Eigen::VectorXd& q) {
  // Below about 120 degrees theta / sin(theta) is under 2.5 and the element is not what fails.
  constexpr double kSuspect = 2.0 * M_PI / 3.0;
  // The step's start (an accepted state) first; the iterate's turn where that one is not yet
  // suspect (Newton may have been carried there by the singularity itself).
  for (const Eigen::VectorXd* v : {&q0, &q}) {
    const GeBeam* beam = nullptr;
    ElementTurn worst;
    for (const GeBeam& b : model.ge_beams) {
      const ElementTurn t = ge_beam_largest_turn(model, b, *v);
      if (t.angle > worst.angle) {
        worst = t;
        beam = &b;
      }
    }
    if (!beam || worst.angle <= kSuspect) continue;
    const std::string e = std::to_string(worst.element);
    std::string hint = "Element ";
    hint += e + " of beam '" + beam->name + "' (nodes n" + e + ", n" + std::to_string(worst.element + 1) + ") turns by ";
    hint += std::to_string(std::lround(worst.angle * 180.0 / M_PI));
    hint += v == &q0 ? " degrees at the step's start" : " degrees in the last iterate";
    hint += ": a geometrically exact element's curvature is singular at 180, so the beam bends more sharply than its "
            "elements can follow; give it more elements (\"elements\": ";
    hint += std::to_string(2 * beam->elements) + ", twice as many). ";
    return hint;
  }
  return {};
}

GeBeam make_ge_beam(std::vector<Body>& nodes, const std::string& name, const Eigen::Vector3d& start,
                    const Eigen::Vector3d& end, const Eigen::Vector3d& y_axis, int elements, double E, double G, double rho,
                    double area, double Iy, double Iz, double J, double shear_factor, double tau, const std::string& file,
                    const std::string& field) {
  if (elements < 1) throw ModelError(file, field + ".elements", "must be at least 1 (found " + std::to_string(elements) + ")");
  // Each node is a body of twelve coordinates: refused here, before the node bodies are made,
  // rather than by finalize's count of the model's coordinates.
  if (12LL * (elements + 1LL) > kMaxModelCoordinates)
    throw ModelError(file, field + ".elements",
                     "is " + std::to_string(elements) + ": its " + std::to_string(elements + 1LL) + " node bodies would have " +
                         std::to_string(12LL * (elements + 1LL)) + " coordinates; a model has at most " +
                         std::to_string(kMaxModelCoordinates) + " (the step's matrices are dense in them), so at most " +
                         std::to_string(kMaxModelCoordinates / 12 - 1) + " elements");
  const double L = (end - start).norm();
  const double size = std::max(start.cwiseAbs().maxCoeff(), end.cwiseAbs().maxCoeff());
  if (!(L > 1e-12 * std::max(1.0, size)))
    throw ModelError(file, field + ".end", "the beam has zero length (end equals start, " + num(L) + " m apart)");
  const Eigen::Vector3d d3 = (end - start) / L;
  const Eigen::Vector3d y = y_axis - y_axis.dot(d3) * d3;
  if (!(y.norm() > 1e-6 * y_axis.norm()))
    throw ModelError(file, field + ".y_axis", "is along the beam (it must have a component normal to start -> end)");
  const Eigen::Vector3d d1 = y.normalized(), d2 = d3.cross(d1);
  GeBeam beam;
  beam.name = name;
  beam.elements = elements;
  beam.length = L;
  // Section: a point y d1 + z d2, Iy = int z^2, Iz = int y^2. Bending about d1 is EIy's.
  beam.CG << shear_factor * G * area, shear_factor * G * area, E * area;
  beam.CK << E * Iy, E * Iz, G * J;
  beam.tau = tau;
  const double h = L / elements;
  Eigen::Matrix3d A;
  A << d1, d2, d3;
  for (int k = 0; k <= elements; ++k) {
    // Lumped: a node carries the mass and the section's rotary inertia of its half elements.
    const double l = (k == 0 || k == elements) ? h / 2 : h;
    Body b;
    b.name = name + ":n" + std::to_string(k);
    b.flexible = false;
    b.nq = 0;
    b.mass = rho * area * l;
    b.r0 = start + (k * h) * d3;
    b.A0 = A;
    b.rdm.setZero();
    // Pseudo-inertia int c c^T dm over the slice: the directors' kinetic energy
    // 1/2 rho (Iz |d1_dot|^2 + Iy |d2_dot|^2) per length; none along d3 (a section has no depth).
    b.J0 = Eigen::Vector3d(rho * Iz * l, rho * Iy * l, 0.0).asDiagonal();
    b.Myy.resize(0, 0);
    b.Ke.resize(0, 0);
    b.De.resize(0, 0);
    b.Pdm.resize(3, 0);
    for (auto& r : b.rPdm) r.resize(3, 0);
    b.PsiI.resize(0, 3);
    b.y0.resize(0);
    b.yd0.resize(0);
    // The node's one slice: at its frame origin; joints, forces and outputs name it n<k>.
    NodeSlice s;
    s.name = "n";  // then the index (as one expression GCC 12 warns of a bogus memcpy bound)
    s.name += std::to_string(k);
    s.phi.resize(3, 0);
    s.psi.resize(3, 0);
    b.nodes.push_back(std::move(s));
    nodes.push_back(std::move(b));
  }
  beam.strain0.resize(6, elements);
  for (int e = 0; e < elements; ++e) {
    Vec24 q;
    const Body& a = nodes[nodes.size() - static_cast<std::size_t>(elements + 1 - e)];
    const Body& b = nodes[nodes.size() - static_cast<std::size_t>(elements - e)];
    q << a.r0, a.A0.col(0), a.A0.col(1), a.A0.col(2), b.r0, b.A0.col(0), b.A0.col(1), b.A0.col(2);
    beam.strain0.col(e) = ge_beam_strains(beam, q);
  }
  return beam;
}

}  // namespace ffr::runtime
