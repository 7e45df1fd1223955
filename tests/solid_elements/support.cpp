#include "support.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SparseCholesky>

#include <cmath>
#include <random>
#include <stdexcept>

namespace ffr::test {

using namespace ffr::preproc;

const std::vector<ElementType>& all_solid_types() {
  static const std::vector<ElementType> t = {ElementType::Tet4,   ElementType::Tet10,   ElementType::Hex8,
                                             ElementType::Hex20,  ElementType::Hex27,   ElementType::Wedge6,
                                             ElementType::Wedge15, ElementType::Pyramid5};
  return t;
}

ElementType linear_type(ElementType t) {
  switch (t) {
    case ElementType::Tet10: return ElementType::Tet4;
    case ElementType::Hex20: case ElementType::Hex27: return ElementType::Hex8;
    case ElementType::Wedge15: return ElementType::Wedge6;
    default: return t;
  }
}

Eigen::MatrixX3d reference_corners(ElementType t) {
  const SolidShape& s = solid_shape(linear_type(t));
  Eigen::MatrixX3d c(s.nodes, 3);
  for (int a = 0; a < s.nodes; ++a) c.row(a) = s.reference_nodes[a].transpose();
  return c;
}

std::vector<std::vector<int>> corner_faces(ElementType t) {
  switch (linear_type(t)) {
    case ElementType::Tet4: return {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    case ElementType::Hex8:
      return {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}};
    case ElementType::Wedge6: return {{0, 2, 1}, {3, 4, 5}, {0, 1, 4, 3}, {0, 3, 5, 2}, {1, 2, 5, 4}};
    case ElementType::Pyramid5: return {{0, 3, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
    default: throw std::logic_error("corner_faces: not a solid");
  }
}

Eigen::MatrixX3d straight_element(ElementType t, const Eigen::MatrixX3d& corners) {
  const SolidShape& s = solid_shape(t);
  const SolidShape& lin = solid_shape(linear_type(t));
  ShapeValues N(lin.nodes);
  ShapeGradients dN(lin.nodes, 3);
  Eigen::MatrixX3d xe(s.nodes, 3);
  for (int a = 0; a < s.nodes; ++a) {
    if (a < lin.nodes) {
      xe.row(a) = corners.row(a);
      continue;
    }
    lin.eval(s.reference_nodes[a], N, dN);
    xe.row(a) = N.transpose() * corners;
  }
  return xe;
}

Eigen::MatrixX3d projective_corners(ElementType t) {
  Eigen::MatrixX3d c = reference_corners(t);
  Eigen::Matrix3d A;
  A << 1.1, 0.2, -0.1, 0.15, 0.9, 0.25, -0.05, 0.1, 1.3;
  const Eigen::Vector3d b(0.3, -0.2, 0.5), cc(0.12, -0.08, 0.1);
  const double d = 1.6;
  for (int a = 0; a < c.rows(); ++a) {
    const Eigen::Vector3d p = c.row(a).transpose();
    c.row(a) = ((A * p + b) / (cc.dot(p) + d)).transpose();
  }
  return c;
}

Moments polyhedron_moments(const Eigen::MatrixX3d& corners, const std::vector<std::vector<int>>& faces) {
  Moments m;
  const Eigen::Vector3d o = corners.colwise().mean().transpose();
  auto tet = [&](const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                 const Eigen::Vector3d& p3) {
    Eigen::Matrix3d E;
    E << p1 - p0, p2 - p0, p3 - p0;
    const double V = E.determinant() / 6;
    const Eigen::Vector3d s = p0 + p1 + p2 + p3;
    m.V += V;
    m.S1 += V * s / 4;
    // int x x^T over a tet = V/20 (sum p_i p_i^T + s s^T)
    m.S2 += V / 20 * (p0 * p0.transpose() + p1 * p1.transpose() + p2 * p2.transpose() + p3 * p3.transpose() +
                      s * s.transpose());
  };
  for (const auto& f : faces)
    for (std::size_t k = 1; k + 1 < f.size(); ++k)
      tet(o, corners.row(f[0]).transpose(), corners.row(f[k]).transpose(), corners.row(f[k + 1]).transpose());
  return m;
}

Eigen::MatrixX3d Patch::coords(int e) const {
  Eigen::MatrixX3d xe(elems[e].size(), 3);
  for (std::size_t a = 0; a < elems[e].size(); ++a) xe.row(a) = x[elems[e][a]].transpose();
  return xe;
}

namespace {
// Splits a hex cell (8 corner points, gmsh order) into linear elements of the target shape.
std::vector<Eigen::MatrixX3d> split_cell(ElementType lin, const Eigen::Matrix<double, 8, 3>& h) {
  std::vector<std::vector<int>> parts;
  Eigen::Matrix<double, 9, 3> pts;
  pts.topRows<8>() = h;
  pts.row(8) = h.colwise().mean();  // cell centre for pyramids
  switch (lin) {
    case ElementType::Hex8: parts = {{0, 1, 2, 3, 4, 5, 6, 7}}; break;
    case ElementType::Tet4:  // Kuhn: 6 tets around the diagonal 0-6 (conforming in a lattice)
      parts = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
      break;
    case ElementType::Wedge6: parts = {{0, 1, 2, 4, 5, 6}, {0, 2, 3, 4, 6, 7}}; break;
    case ElementType::Pyramid5:  // one pyramid per face, apex at the centre
      parts = {{0, 1, 2, 3, 8}, {4, 7, 6, 5, 8}, {0, 4, 5, 1, 8}, {3, 2, 6, 7, 8}, {0, 3, 7, 4, 8}, {1, 5, 6, 2, 8}};
      break;
    default: throw std::logic_error("split_cell");
  }
  std::vector<Eigen::MatrixX3d> out;
  for (auto p : parts) {
    Eigen::MatrixX3d c(p.size(), 3);
    for (std::size_t i = 0; i < p.size(); ++i) c.row(i) = pts.row(p[i]);
    // Fix orientation: a negative corner Jacobian means mirrored numbering.
    const double q = solid_quality(lin, c).min_det_j;
    if (q < 0) {
      if (lin == ElementType::Tet4) std::swap(p[1], p[2]);
      else if (lin == ElementType::Pyramid5) std::swap(p[1], p[3]);
      else if (lin == ElementType::Wedge6) { std::swap(p[1], p[2]); std::swap(p[4], p[5]); }
      for (std::size_t i = 0; i < p.size(); ++i) c.row(i) = pts.row(p[i]);
    }
    out.push_back(c);
  }
  return out;
}
}  // namespace

Patch make_box(ElementType t, int nx, int ny, int nz, const Eigen::Vector3d& L, double distortion,
               unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1, 1);
  const Eigen::Vector3d h(L.x() / nx, L.y() / ny, L.z() / nz);
  auto id = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  std::vector<Eigen::Vector3d> lat((nx + 1) * (ny + 1) * (nz + 1));
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        Eigen::Vector3d p(i * h.x(), j * h.y(), k * h.z());
        const bool inner = i > 0 && i < nx && j > 0 && j < ny && k > 0 && k < nz;
        if (inner && distortion > 0)
          for (int c = 0; c < 3; ++c) p[c] += distortion * h[c] * U(rng);
        lat[id(i, j, k)] = p;
      }
  Patch p;
  p.type = t;
  const double tol = 1e-9 * L.norm();
  auto node = [&](const Eigen::Vector3d& x) {
    for (std::size_t n = 0; n < p.x.size(); ++n)
      if ((p.x[n] - x).norm() < tol) return static_cast<int>(n);
    p.x.push_back(x);
    return static_cast<int>(p.x.size() - 1);
  };
  const int off[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        Eigen::Matrix<double, 8, 3> cell;
        for (int c = 0; c < 8; ++c) cell.row(c) = lat[id(i + off[c][0], j + off[c][1], k + off[c][2])].transpose();
        for (const auto& corners : split_cell(linear_type(t), cell)) {
          const Eigen::MatrixX3d xe = straight_element(t, corners);
          std::vector<int> conn;
          for (int a = 0; a < xe.rows(); ++a) conn.push_back(node(xe.row(a).transpose()));
          p.elems.push_back(conn);
        }
      }
  return p;
}

namespace {
Sparse assemble(const Patch& p, const std::function<Eigen::MatrixXd(int)>& ke) {
  std::vector<Eigen::Triplet<double>> trip;
  for (std::size_t e = 0; e < p.elems.size(); ++e) {
    const Eigen::MatrixXd k = ke(static_cast<int>(e));
    const auto& c = p.elems[e];
    for (std::size_t a = 0; a < c.size(); ++a)
      for (std::size_t b = 0; b < c.size(); ++b)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) trip.emplace_back(3 * c[a] + i, 3 * c[b] + j, k(3 * a + i, 3 * b + j));
  }
  Sparse K(p.ndof(), p.ndof());
  K.setFromTriplets(trip.begin(), trip.end());
  return K;
}
}  // namespace

Sparse assemble_stiffness(const Patch& p, const Material& m, const SolidOptions& o) {
  SolidOptions oo = o;
  oo.mass_samples = false;
  return assemble(p, [&](int e) { return solid_element(p.type, p.coords(e), m, oo).K; });
}

Sparse assemble_geometric(const Patch& p, const Material& m, const Eigen::VectorXd& d, const SolidOptions& o) {
  return assemble(p, [&](int e) {
    const auto& c = p.elems[e];
    Eigen::VectorXd de(3 * c.size());
    for (std::size_t a = 0; a < c.size(); ++a) de.segment<3>(3 * a) = d.segment<3>(3 * c[a]);
    return solid_geometric_stiffness(p.type, p.coords(e), m, de, o);
  });
}

Eigen::VectorXd solve_dirichlet(const Sparse& K, const Eigen::VectorXd& f, const std::map<int, double>& fixed) {
  const int n = static_cast<int>(K.rows());
  std::vector<int> map(n, -1);
  int nf = 0;
  for (int i = 0; i < n; ++i)
    if (!fixed.count(i)) map[i] = nf++;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
  for (const auto& [i, v] : fixed) u[i] = v;
  Eigen::VectorXd r = f - K * u;
  std::vector<Eigen::Triplet<double>> trip;
  for (int c = 0; c < K.outerSize(); ++c)
    for (Sparse::InnerIterator it(K, c); it; ++it)
      if (map[it.row()] >= 0 && map[it.col()] >= 0) trip.emplace_back(map[it.row()], map[it.col()], it.value());
  Sparse Kf(nf, nf);
  Kf.setFromTriplets(trip.begin(), trip.end());
  Eigen::VectorXd rf(nf);
  for (int i = 0; i < n; ++i)
    if (map[i] >= 0) rf[map[i]] = r[i];
  Eigen::SimplicialLDLT<Sparse> ldlt(Kf);
  if (ldlt.info() != Eigen::Success) throw std::runtime_error("solve_dirichlet: factorization failed");
  const Eigen::VectorXd uf = ldlt.solve(rf);
  for (int i = 0; i < n; ++i)
    if (map[i] >= 0) u[i] = uf[map[i]];
  return u;
}

Eigen::VectorXd face_loads(const Patch& p, int k, double value, double sign,
                           const std::function<Eigen::Vector3d(const Eigen::Vector3d&, const Eigen::Vector3d&)>& traction) {
  const SolidShape& s = solid_shape(p.type);
  const auto faces = corner_faces(p.type);
  const Eigen::MatrixX3d ref = reference_corners(p.type);
  const quadrature::Rule tri = quadrature::triangle(5);
  double gx[4], gw[4];
  quadrature::gauss_legendre(4, gx, gw);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(p.ndof());
  ShapeValues N(s.nodes);
  ShapeGradients dN(s.nodes, 3);
  const Eigen::Vector3d n = sign * Eigen::Vector3d::Unit(k);
  const double tol = 1e-9;
  for (std::size_t e = 0; e < p.elems.size(); ++e) {
    const Eigen::MatrixX3d xe = p.coords(static_cast<int>(e));
    for (const auto& fc : faces) {
      bool on = true;
      for (int c : fc) on = on && std::abs(xe(c, k) - value) < tol;
      if (!on) continue;
      // Integrate over the face parametrised by (u, v): triangle (1-u-v, u, v) with the
      // degree-5 rule, or bilinear quad on [-1,1]^2 with 4x4 Gauss.
      const bool is_tri = fc.size() == 3;
      const int ng = is_tri ? tri.size() : 16;
      for (int g = 0; g < ng; ++g) {
        double u, v, w;
        Eigen::Vector3d xi, xu, xv;
        if (is_tri) {
          u = tri.xi[g].x(); v = tri.xi[g].y(); w = tri.w[g];
          xi = (1 - u - v) * ref.row(fc[0]).transpose() + u * ref.row(fc[1]).transpose() + v * ref.row(fc[2]).transpose();
          xu = (ref.row(fc[1]) - ref.row(fc[0])).transpose();
          xv = (ref.row(fc[2]) - ref.row(fc[0])).transpose();
        } else {
          u = gx[g % 4]; v = gx[g / 4]; w = gw[g % 4] * gw[g / 4];
          const double ph[4] = {(1 - u) * (1 - v) / 4, (1 + u) * (1 - v) / 4, (1 + u) * (1 + v) / 4, (1 - u) * (1 + v) / 4};
          const double pu[4] = {-(1 - v) / 4, (1 - v) / 4, (1 + v) / 4, -(1 + v) / 4};
          const double pv[4] = {-(1 - u) / 4, -(1 + u) / 4, (1 + u) / 4, (1 - u) / 4};
          xi.setZero(); xu.setZero(); xv.setZero();
          for (int c = 0; c < 4; ++c) {
            xi += ph[c] * ref.row(fc[c]).transpose();
            xu += pu[c] * ref.row(fc[c]).transpose();
            xv += pv[c] * ref.row(fc[c]).transpose();
          }
        }
        s.eval(xi, N, dN);
        const Eigen::Matrix3d J = xe.transpose() * dN;
        const double dA = (J * xu).cross(J * xv).norm();
        const Eigen::Vector3d x = xe.transpose() * N;
        const Eigen::Vector3d t = traction(x, n);
        for (int a = 0; a < s.nodes; ++a) f.segment<3>(3 * p.elems[e][a]) += w * dA * N[a] * t;
      }
    }
  }
  return f;
}

}  // namespace ffr::test
