#pragma once
// Second-order shell and beam elements from an order-2 mesh are computed as their linear
// sub-elements on the same nodes: TRI6 -> 4 TRI3, QUAD9 -> 4 QUAD4, LINE3 -> 2 LINE2. The
// kernels are first-order (MITC4/OPT/DKT shells, 2-node Timoshenko beams); splitting keeps
// every node of the quadratic mesh connected, so shells and beams share the solids' mesh.
// QUAD8 (no centre node) cannot be split and is refused.
#include "ffr/preproc/elements/element.hpp"
#include "ffr/preproc/mesh/mesh.hpp"

#include <vector>

namespace ffr::preproc::detail {

/// Sub-elements of `t` as (type, local node lists); a first-order type maps to itself.
struct SubElements {
  ElementType type;
  std::vector<std::vector<int>> nodes;
};
SubElements sub_elements(ElementType t);

/// Runs `kernel` on each sub-element and assembles the results (K, M, M_rotary, samples)
/// over the parent's nodes, `dofs_per_node` DOFs each.
template <class Kernel>
ElementMatrices composite(ElementType t, const Eigen::MatrixX3d& xe, int dofs_per_node, Kernel&& kernel) {
  const SubElements sub = sub_elements(t);
  if (sub.nodes.size() == 1 && sub.type == t) return kernel(t, xe);
  const Eigen::Index nd = xe.rows() * dofs_per_node;
  ElementMatrices out;
  out.dofs_per_node = dofs_per_node;
  out.K = Eigen::MatrixXd::Zero(nd, nd);
  out.M = Eigen::MatrixXd::Zero(nd, nd);
  bool rotary = false;
  for (const auto& local : sub.nodes) {
    Eigen::MatrixX3d xs(static_cast<Eigen::Index>(local.size()), 3);
    for (std::size_t i = 0; i < local.size(); ++i) xs.row(static_cast<Eigen::Index>(i)) = xe.row(local[i]);
    const ElementMatrices em = kernel(sub.type, xs);
    // Map sub-element DOF i*dpn+a to parent DOF local[i]*dpn+a.
    std::vector<Eigen::Index> map;
    for (int n : local)
      for (int a = 0; a < dofs_per_node; ++a) map.push_back(static_cast<Eigen::Index>(n) * dofs_per_node + a);
    if (em.M_rotary.size() > 0 && !rotary) {
      out.M_rotary = Eigen::MatrixXd::Zero(nd, nd);
      rotary = true;
    }
    for (std::size_t i = 0; i < map.size(); ++i)
      for (std::size_t j = 0; j < map.size(); ++j) {
        out.K(map[i], map[j]) += em.K(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
        out.M(map[i], map[j]) += em.M(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
        if (em.M_rotary.size() > 0)
          out.M_rotary(map[i], map[j]) += em.M_rotary(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
      }
    for (const auto& s : em.samples) {
      MassSample p;
      p.w = s.w;
      p.c = s.c;
      p.N = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, nd);
      for (std::size_t i = 0; i < map.size(); ++i) p.N.col(map[i]) = s.N.col(static_cast<Eigen::Index>(i));
      out.samples.push_back(std::move(p));
    }
  }
  return out;
}

/// The same composition for a matrix-only kernel (geometric stiffness).
template <class Kernel>
Eigen::MatrixXd composite_matrix(ElementType t, const Eigen::MatrixX3d& xe, const Eigen::VectorXd& d_e, int dofs_per_node,
                                 Kernel&& kernel) {
  const SubElements sub = sub_elements(t);
  if (sub.nodes.size() == 1 && sub.type == t) return kernel(t, xe, d_e);
  const Eigen::Index nd = xe.rows() * dofs_per_node;
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(nd, nd);
  for (const auto& local : sub.nodes) {
    Eigen::MatrixX3d xs(static_cast<Eigen::Index>(local.size()), 3);
    std::vector<Eigen::Index> map;
    for (std::size_t i = 0; i < local.size(); ++i) {
      xs.row(static_cast<Eigen::Index>(i)) = xe.row(local[i]);
      for (int a = 0; a < dofs_per_node; ++a) map.push_back(static_cast<Eigen::Index>(local[i]) * dofs_per_node + a);
    }
    Eigen::VectorXd ds(static_cast<Eigen::Index>(map.size()));
    for (std::size_t i = 0; i < map.size(); ++i) ds(static_cast<Eigen::Index>(i)) = d_e(map[i]);
    const Eigen::MatrixXd k = kernel(sub.type, xs, ds);
    for (std::size_t i = 0; i < map.size(); ++i)
      for (std::size_t j = 0; j < map.size(); ++j) out(map[i], map[j]) += k(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
  }
  return out;
}

}  // namespace ffr::preproc::detail
