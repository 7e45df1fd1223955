// A plate body (FORMULATION.md section 16): the reference grid, the inertia as shape integrals,
// the nodes and their small rotations, and the edge supports' rows.
#include "plate_shape.hpp"

#include "ffr/runtime/errors.hpp"
#include "ffr/runtime/model.hpp"
#include "ffr/runtime/plate.hpp"
#include "../number_text.hpp"

#include <Eigen/Geometry>

#include <array>
#include <cmath>

namespace ffr::runtime {
namespace {

// The support rows of one edge: at each of its nodes, what the edge holds (0 nothing, 1 the
// normal component, 2 all three) of r, r_x, r_y, r_xy. Simply supported (hinged, immovable):
// the edge stays where it is, so r and the gradient along the edge are held; clamped adds the
// normal components of the gradient across the edge and of the twist (the edge's normal slope
// stays zero along it). The in-plane components across the edge stay free.
void hold_edge(const AncfPlate& p, int edge, PlateSupport s, std::vector<std::array<int, 4>>& held) {
  if (s == PlateSupport::Free) return;
  const bool along_y = edge < 2;  // x0, x1: the edge runs along y
  const int count = along_y ? p.ny + 1 : p.nx + 1;
  for (int k = 0; k < count; ++k) {
    const int i = along_y ? (edge == 0 ? 0 : p.nx) : k;
    const int j = along_y ? k : (edge == 2 ? 0 : p.ny);
    auto& h = held[static_cast<std::size_t>(p.node(i, j))];
    const int along = along_y ? 2 : 1, across = along_y ? 1 : 2;
    h[0] = 2;
    h[static_cast<std::size_t>(along)] = 2;
    if (s == PlateSupport::Clamped) {
      h[static_cast<std::size_t>(across)] = std::max(h[static_cast<std::size_t>(across)], 1);
      h[3] = std::max(h[3], 1);
    }
  }
}

}  // namespace

Body make_plate_body(const std::string& name, const Eigen::Vector3d (&c)[4], int nx, int ny, double h, double E, double nu,
                     double rho, double tau, const PlateSupport (&edges)[4], const std::string& file, const std::string& field) {
  if (nx < 1 || ny < 1)
    throw ModelError(file, field + ".elements",
                     "must be at least 1 along each side (found [" + std::to_string(nx) + ", " + std::to_string(ny) + "])");
  double size = 0;
  for (const auto& p : c) size = std::max(size, p.cwiseAbs().maxCoeff());
  const double tol = 1e-9 * std::max(1.0, size);
  const Eigen::Vector3d ex = c[1] - c[0], ey = c[3] - c[0];
  const double a = ex.norm(), b = ey.norm();
  if (!(a > tol) || !(b > tol))
    throw ModelError(file, field + ".corners", "has coincident corners (sides " + num(a) + " m and " + num(b) + " m)");
  const Eigen::Vector3d e1 = ex / a, e2 = ey / b;
  if (!(e1.cross(e2).norm() > 1e-6))
    throw ModelError(file, field + ".corners", "corners 0, 1 and 3 are on one line: the plate has no area");
  const Eigen::Vector3d e3 = e1.cross(e2).normalized();
  const double off = (c[2] - c[0]).dot(e3);
  if (std::abs(off) > tol)
    throw ModelError(file, field + ".corners", "are not in one plane: corner 2 is " + num(off) +
                                                   " m off the plane of corners 0, 1 and 3 (a plate is flat)");
  if (std::abs(e1.dot(e2)) > 1e-9 || (c[2] - (c[1] + ey)).norm() > tol)
    throw ModelError(file, field + ".corners",
                     "are not a rectangle (corners in order round it, corner 1 - corner 0 perpendicular to corner 3 - corner 0, "
                     "corner 2 = corner 1 + corner 3 - corner 0)");
  if (!(h > 0) || !(h < 0.5 * std::min(a, b)))
    throw ModelError(file, field + ".thickness", "must be positive and small against the sides (a thin plate; found " + num(h) + " m)");

  auto plate = std::make_shared<AncfPlate>();
  AncfPlate& p = *plate;
  p.nx = nx;
  p.ny = ny;
  p.a = a;
  p.b = b;
  p.thickness = h;
  p.E = E;
  p.nu = nu;
  p.rhoh = rho * h;
  p.tau = tau;
  p.e1 = e1;
  p.e2 = e2 - e2.dot(e1) * e1;  // orthogonal to round-off
  p.e2.normalize();
  p.e3 = e3;
  const int nq = p.nq();
  p.q0 = Eigen::VectorXd::Zero(nq);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const int k = 12 * p.node(i, j);
      p.q0.segment<3>(k) = c[0] + (i * p.dx()) * p.e1 + (j * p.dy()) * p.e2;
      p.q0.segment<3>(k + 3) = p.e1;
      p.q0.segment<3>(k + 6) = p.e2;
    }
  // Support rows, one per held component, none twice (a corner on two held edges).
  std::vector<std::array<int, 4>> held(static_cast<std::size_t>(p.nodes()), std::array<int, 4>{0, 0, 0, 0});
  for (int e = 0; e < 4; ++e) hold_edge(p, e, edges[e], held);
  for (int k = 0; k < p.nodes(); ++k)
    for (int t = 0; t < 4; ++t) {
      const int what = held[static_cast<std::size_t>(k)][static_cast<std::size_t>(t)];
      if (what == 1) p.supports.push_back({12 * k + 3 * t, p.e3, t > 0});
      if (what == 2)
        for (int a2 = 0; a2 < 3; ++a2) p.supports.push_back({12 * k + 3 * t, Eigen::Vector3d::Unit(a2), t > 0});
    }

  Body body;
  body.name = name;
  body.flexible = true;
  body.nq = nq;
  body.mass = p.rhoh * a * b;
  body.r0.setZero();
  body.A0.setIdentity();
  body.Pdm = Matrix3Xd::Zero(3, nq);
  for (auto& r : body.rPdm) r = Matrix3Xd::Zero(3, nq);
  for (auto& row : body.PPdm)
    for (auto& m : row) m = MatrixXd::Zero(nq, nq);
  // Shape integrals with Phi = S(x, y) and c(x, y) = S q0 (FORMULATION.md 3): every material
  // point is r0 + A (c + S y) with the frame held at the global one.
  const double lx = p.dx(), ly = p.dy();
  for (int ej = 0; ej < ny; ++ej)
    for (int ei = 0; ei < nx; ++ei) {
      int start[4];
      for (int l = 0; l < 4; ++l) start[l] = 12 * p.node(ei + (l & 1), ej + (l >> 1));
      for (int gi = 0; gi < plate_shape::kGauss; ++gi)
        for (int gj = 0; gj < plate_shape::kGauss; ++gj) {
          const double dm = p.rhoh * plate_shape::kW[gi] * plate_shape::kW[gj] * lx * ly;
          const plate_shape::Shape sh = plate_shape::shape(plate_shape::kXi[gi], plate_shape::kXi[gj], lx, ly);
          const auto col = [&](int k) { return start[k / 4] + 3 * (k % 4); };  // shape k's first coordinate
          Eigen::Vector3d cpt = Eigen::Vector3d::Zero();
          for (int k = 0; k < 16; ++k) cpt += sh.s(k) * p.q0.segment<3>(col(k));
          body.rdm += dm * cpt;
          body.J0 += dm * cpt * cpt.transpose();
          for (int k = 0; k < 16; ++k) {
            const double f = dm * sh.s(k);
            for (int x = 0; x < 3; ++x) {
              body.Pdm(x, col(k) + x) += f;
              for (int r = 0; r < 3; ++r) body.rPdm[static_cast<std::size_t>(r)](x, col(k) + x) += f * cpt(r);
            }
            for (int u = 0; u < 16; ++u) {
              const double g = f * sh.s(u);
              for (int x = 0; x < 3; ++x)
                for (int z = 0; z < 3; ++z)
                  body.PPdm[static_cast<std::size_t>(x)][static_cast<std::size_t>(z)](col(k) + x, col(u) + z) += g;
            }
          }
        }
    }
  body.Myy = MatrixXd::Zero(nq, nq);
  for (int x = 0; x < 3; ++x) body.Myy += body.PPdm[static_cast<std::size_t>(x)][static_cast<std::size_t>(x)];
  body.PsiI = MatrixXd::Zero(nq, 3);
  body.Ke = MatrixXd::Zero(nq, nq);  // the elastic forces are the element's (ancf_plate_forces)
  body.De = MatrixXd::Zero(nq, nq);
  // Nodes n<i>_<j>. A node's small rotation is that of the triad (r_x, r_y, normal) linearised:
  // theta = e1 (e3 . dr_y) - e2 (e3 . dr_x) + e3 (e2 . dr_x - e1 . dr_y) / 2 (FORMULATION.md 16).
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const int k = 12 * p.node(i, j);
      NodeSlice s;
      s.name = "n" + std::to_string(i) + "_" + std::to_string(j);
      s.origin = p.q0.segment<3>(k);
      s.phi = Matrix3Xd::Zero(3, nq);
      s.phi.block<3, 3>(0, k).setIdentity();
      s.psi = Matrix3Xd::Zero(3, nq);
      s.psi.block<3, 3>(0, k + 3) = -p.e2 * p.e3.transpose() + 0.5 * p.e3 * p.e2.transpose();
      s.psi.block<3, 3>(0, k + 6) = p.e1 * p.e3.transpose() - 0.5 * p.e3 * p.e1.transpose();
      body.nodes.push_back(std::move(s));
    }
  body.y0 = VectorXd::Zero(nq);
  body.yd0 = VectorXd::Zero(nq);
  body.plate = std::move(plate);
  return body;
}

}  // namespace ffr::runtime
