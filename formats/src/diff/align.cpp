// align_modes(): the block-diagonal change of B's modal basis that best matches A's modes
// (see diff.hpp for the method).
#include "ffr/formats/diff.hpp"

#include "size.hpp"

#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ffr::formats {
namespace {

using Eigen::MatrixXd;

bool same_vertices(const Visual& a, const Visual& b, const Size& z) {
  if (a.empty() || b.empty() || a.vertices.rows() != b.vertices.rows()) return false;
  return (a.vertices - b.vertices).cwiseAbs().maxCoeff() <= 1e-9 * z.L;
}

// Rows of linear functionals of the modes, one column per mode, each block scaled to O(1).
MatrixXd features(const Sid& s, const Sid& other, const std::vector<std::string>& common_nodes, const Size& z) {
  std::vector<MatrixXd> blocks;
  blocks.push_back(s.integrals.Pdm / (z.m * z.phi));
  for (int a = 0; a < 3; ++a) blocks.push_back(s.integrals.rPdm[a] / (z.m * z.phi * z.L));
  // The nodes both files have, in A's order, so both give the same rows.
  for (const auto& name : common_nodes) {
    const auto& n = s.nodes[static_cast<std::size_t>(s.find_node(name))];
    blocks.push_back(n.phi / z.phi);
    blocks.push_back(n.psi * (z.L / z.phi));
  }
  // The surfaces' mode shapes only where both files have the same vertices in the same order:
  // a renumbered surface of the same size would pair unrelated vertices and could outweigh the
  // other features (a SID of the same plate from two versions of ffr-reduce was aligned with
  // wrong signs that way, and its invariants reported as different).
  if (same_vertices(s.visual, other.visual, z)) {
    MatrixXd v(3 * s.visual.vertices.rows(), s.nq());
    for (Eigen::Index k = 0; k < s.nq(); ++k)
      v.col(k) = Eigen::Map<const Eigen::VectorXd>(s.visual.modes[k].data(), v.rows());
    blocks.push_back(v / (z.phi * std::sqrt(static_cast<double>(s.visual.vertices.rows()))));
  }
  Eigen::Index rows = 0;
  for (const auto& b : blocks) rows += b.rows();
  MatrixXd S(rows, s.nq());
  rows = 0;
  for (const auto& b : blocks) {
    S.middleRows(rows, b.rows()) = b;
    rows += b.rows();
  }
  return S;
}

std::vector<std::vector<Index>> frequency_groups(const Sid& a, double rtol) {
  std::vector<std::vector<Index>> groups;
  const auto& f = a.refmod.frequency_hz;
  const double fmax = f.size() ? f.cwiseAbs().maxCoeff() : 0.0;
  for (Eigen::Index k = 0; k < f.size(); ++k) {
    const bool same = !groups.empty() && a.refmod.mode_type[k] == a.refmod.mode_type[groups.back().back()] &&
                      std::abs(f[k] - f[groups.back().back()]) <= rtol * std::max({std::abs(f[k]), 1e-6 * fmax, 1e-300});
    if (same)
      groups.back().push_back(k);
    else
      groups.push_back({k});
  }
  return groups;
}

}  // namespace

ModeAlignment align_modes(const Sid& a, const Sid& b, const DiffOptions& opt) {
  const Eigen::Index nq = a.nq();
  if (b.nq() != nq) throw std::invalid_argument("align_modes: the files have different numbers of modes");
  ModeAlignment al;
  al.T = MatrixXd::Identity(nq, nq);
  al.groups = frequency_groups(a, std::max(opt.group_rtol, 0.0));
  const Size z = size_of(a);
  std::vector<std::string> common;
  for (const auto& n : a.nodes)
    if (b.find_node(n.name) >= 0) common.push_back(n.name);
  const MatrixXd SA = features(a, b, common, z), SB = features(b, a, common, z);
  // A group whose features are at the rounding level of the largest mode's (a Craig-Bampton
  // fixed-interface mode with no net momentum and zero at every interface node: Pdm ~ 1e-13)
  // says nothing about its sign or orientation; Procrustes on that noise would flip or turn B's
  // modes at random. Such a group is left as written, and a real sign difference then shows.
  const double feature_scale = std::max(SA.colwise().norm().maxCoeff(), SB.colwise().norm().maxCoeff());
  const double no_information = 1e-9 * feature_scale * feature_scale;
  for (std::size_t g = 0; g < al.groups.size(); ++g) {
    const auto& G = al.groups[g];
    const auto n = static_cast<Eigen::Index>(G.size());
    MatrixXd A(SA.rows(), n), B(SB.rows(), n);
    for (Eigen::Index i = 0; i < n; ++i) {
      A.col(i) = SA.col(G[i]);
      B.col(i) = SB.col(G[i]);
    }
    // Orthogonal Procrustes: min ||B T - A|| over orthogonal T. Only orthogonal changes of
    // basis are excused (a sign, a rotation): a rescaled mode stays a difference.
    const Eigen::JacobiSVD<MatrixXd> svd(B.transpose() * A, Eigen::ComputeFullU | Eigen::ComputeFullV);
    if (!(svd.singularValues()(0) > no_information)) continue;  // T stays the identity on G
    const MatrixXd Tg = svd.matrixU() * svd.matrixV().transpose();
    for (Eigen::Index i = 0; i < n; ++i)
      for (Eigen::Index j = 0; j < n; ++j) al.T(G[i], G[j]) = Tg(i, j);
    if (n == 1 && Tg(0, 0) < 0) al.flipped.push_back(G[0]);
    if (n > 1 && (Tg - MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff() > 1e-12) al.rotated_groups.push_back(static_cast<Index>(g));
  }
  return al;
}

}  // namespace ffr::formats
