#include "grid_pencil.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace ffr::bench {

namespace {

constexpr double kLx = 2.0, kLy = 1.0, kLz = 1.0;

// 1D rod of n elements over L: tridiagonal K and M of the retained nodes. Fixed-free drops
// node 0; free-free keeps all n + 1 nodes. sub[i] couples node i and i + 1.
struct Rod1D {
  std::vector<double> kd, ks, md, ms;
  int size() const { return static_cast<int>(kd.size()); }
  // Entry (i, i + off) for off in {-1, 0, 1}; 0 outside.
  double k(int i, int off) const { return off == 0 ? kd[i] : ks[off < 0 ? i - 1 : i]; }
  double m(int i, int off) const { return off == 0 ? md[i] : ms[off < 0 ? i - 1 : i]; }
};

Rod1D rod1d(int n, double L, bool fixed_start) {
  const double h = L / n, k = 1.0 / h, m = h / 6.0;
  const int first = fixed_start ? 1 : 0, nn = n + 1 - first;
  Rod1D r;
  r.kd.assign(nn, 0.0);
  r.md.assign(nn, 0.0);
  r.ks.assign(nn - 1, -k);
  r.ms.assign(nn - 1, m);
  for (int e = 0; e < n; ++e)
    for (int node : {e, e + 1})
      if (node >= first) {
        r.kd[node - first] += k;
        r.md[node - first] += 2 * m;
      }
  return r;
}

std::vector<double> rod_eigenvalues(int n, double L, bool fixed_start) {
  const double h = L / n, c = 6.0 / (h * h);
  std::vector<double> l;
  for (int k = fixed_start ? 1 : 0; k <= n; ++k) {
    const double th = fixed_start ? (2 * k - 1) * M_PI / (2.0 * n) : k * M_PI / n;
    const double s = std::sin(0.5 * th);  // 1 - cos(th) = 2 sin^2(th/2), no cancellation
    l.push_back(c * 2 * s * s / (2 + std::cos(th)));
  }
  std::sort(l.begin(), l.end());
  return l;
}

// The fixed SPD coupling of the 3-DOF case (arbitrary, well conditioned, no symmetry).
Eigen::Matrix3d coupling() {
  Eigen::Matrix3d D;
  D << 3.0, 1.0, 0.5, 1.0, 2.0, 0.3, 0.5, 0.3, 1.5;
  return D;
}

}  // namespace

GridPencil make_grid_pencil(std::int64_t target_dofs, int dpn) {
  // nodes ~ (2m)(m+1)^2 with nx = 2m elements fixed-free (2m nodes kept), ny = nz = m.
  const double nodes = static_cast<double>(target_dofs) / dpn;
  int m = std::max(2, static_cast<int>(std::cbrt(nodes / 2.0)));
  while (2.0 * m * (m + 1.0) * (m + 1.0) < nodes) ++m;
  GridPencil g;
  g.nx = 2 * m;
  g.ny = g.nz = m;
  g.dofs_per_node = dpn;
  const Rod1D X = rod1d(g.nx, kLx, true), Y = rod1d(g.ny, kLy, false), Z = rod1d(g.nz, kLz, false);
  const std::int64_t sx = X.size(), sy = Y.size(), sz = Z.size();
  const std::int64_t nnodes = sx * sy * sz, n = nnodes * dpn;
  const Eigen::Matrix3d D = dpn == 3 ? coupling() : Eigen::Matrix3d::Identity();

  using SI = preproc::SparseMatrix::StorageIndex;
  std::vector<SI> outer(n + 1, 0);
  // Column pointers: every node couples to its 3x3x3 neighbourhood (clipped at the box).
  auto count = [](std::int64_t i, std::int64_t s) { return 1 + (i > 0) + (i + 1 < s); };
  for (std::int64_t kz = 0; kz < sz; ++kz)
    for (std::int64_t jy = 0; jy < sy; ++jy)
      for (std::int64_t ix = 0; ix < sx; ++ix) {
        const std::int64_t p = ix + sx * (jy + sy * kz);
        const SI c = count(ix, sx) * count(jy, sy) * count(kz, sz) * dpn;
        for (int d = 0; d < dpn; ++d) outer[p * dpn + d + 1] = c;
      }
  for (std::int64_t j = 0; j < n; ++j) outer[j + 1] += outer[j];
  g.K.resize(n, n);
  g.M.resize(n, n);
  g.K.resizeNonZeros(outer[n]);
  g.M.resizeNonZeros(outer[n]);
  std::copy(outer.begin(), outer.end(), g.K.outerIndexPtr());
  std::copy(outer.begin(), outer.end(), g.M.outerIndexPtr());
  // Fill: rows ascending = neighbours in (c, b, a) order, then the DOF within the node.
  for (std::int64_t kz = 0; kz < sz; ++kz)
    for (std::int64_t jy = 0; jy < sy; ++jy)
      for (std::int64_t ix = 0; ix < sx; ++ix) {
        const std::int64_t p = ix + sx * (jy + sy * kz);
        for (int e = 0; e < dpn; ++e) {
          SI k = outer[p * dpn + e];
          for (int c = -1; c <= 1; ++c) {
            if (kz + c < 0 || kz + c >= sz) continue;
            for (int b = -1; b <= 1; ++b) {
              if (jy + b < 0 || jy + b >= sy) continue;
              for (int a = -1; a <= 1; ++a) {
                if (ix + a < 0 || ix + a >= sx) continue;
                const std::int64_t q = (ix + a) + sx * ((jy + b) + sy * (kz + c));
                const double mx = X.m(ix, a), my = Y.m(jy, b), mz = Z.m(kz, c);
                const double lap = X.k(ix, a) * my * mz + mx * Y.k(jy, b) * mz + mx * my * Z.k(kz, c);
                for (int d = 0; d < dpn; ++d, ++k) {
                  g.K.innerIndexPtr()[k] = q * dpn + d;
                  g.M.innerIndexPtr()[k] = q * dpn + d;
                  g.K.valuePtr()[k] = lap * D(d, e);
                  g.M.valuePtr()[k] = d == e ? mx * my * mz : 0.0;
                }
              }
            }
          }
        }
      }
  return g;
}

std::vector<double> grid_eigenvalues(const GridPencil& g, int count) {
  const auto lx = rod_eigenvalues(g.nx, kLx, true), ly = rod_eigenvalues(g.ny, kLy, false),
             lz = rod_eigenvalues(g.nz, kLz, false);
  std::vector<double> mu{1.0};
  if (g.dofs_per_node == 3) {
    const Eigen::Vector3d e = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(coupling()).eigenvalues();
    mu = {e[0], e[1], e[2]};
  }
  // Only the lowest few 1D eigenvalues can contribute to the `count` lowest sums.
  const size_t cap = static_cast<size_t>(count) + 1;
  std::vector<double> all;
  for (size_t i = 0; i < std::min(cap, lx.size()); ++i)
    for (size_t j = 0; j < std::min(cap, ly.size()); ++j)
      for (size_t k = 0; k < std::min(cap, lz.size()); ++k)
        for (double s : mu) all.push_back((lx[i] + ly[j] + lz[k]) * s);
  std::sort(all.begin(), all.end());
  all.resize(std::min(all.size(), static_cast<size_t>(count)));
  return all;
}

}  // namespace ffr::bench
