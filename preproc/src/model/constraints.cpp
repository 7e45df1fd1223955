#include "ffr/preproc/model/constraints.hpp"

#include "ffr/formats/h5.hpp"

#include <Eigen/Dense>

#include <unordered_map>

namespace ffr::preproc {
namespace {

using formats::FormatError;

enum class Status : std::uint8_t { Independent, Dependent, Held };
using Combination = std::vector<std::pair<Index, double>>;  // sum of coeff * full DOF

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return s;
}

struct Builder {
  const FeModel& model;
  std::vector<Status> status;
  std::unordered_map<Index, Combination> dep;

  explicit Builder(const FeModel& m) : model(m), status(static_cast<std::size_t>(m.num_dofs), Status::Independent) {}

  void hold(Index d) { status[static_cast<std::size_t>(d)] = Status::Held; }
  void depend(Index d, Combination c) {
    status[static_cast<std::size_t>(d)] = Status::Dependent;
    dep[d] = std::move(c);
  }

  // Rigid spider: the group's DOFs follow the interface node r.
  void rigid(const InterfaceNode& itf, bool held) {
    for (Index n : itf.nodes) {
      const Eigen::Vector3d d = model.mesh->x.row(n).transpose() - itf.x;
      const Eigen::Matrix3d minus_skew = -skew(d);  // u_j = u_r - skew(d) theta_r
      for (int a = 0; a < 3; ++a) {
        const Index dof = model.dof(n, a);
        if (held) {
          hold(dof);
          continue;
        }
        Combination c{{itf.dof + a, 1.0}};
        for (int b = 0; b < 3; ++b)
          if (minus_skew(a, b) != 0) c.emplace_back(itf.dof + 3 + b, minus_skew(a, b));
        depend(dof, std::move(c));
      }
      if (model.node_ndof[static_cast<std::size_t>(n)] == 6)
        for (int a = 3; a < 6; ++a) {
          if (held) hold(model.dof(n, a));
          else depend(model.dof(n, a), {{itf.dof + a, 1.0}});
        }
    }
    if (held)
      for (int a = 0; a < 6; ++a) hold(itf.dof + a);
  }

  // Averaged spider (least-squares rigid fit of the group's translations).
  void averaged(const InterfaceNode& itf, InterfaceState state, const std::string& file, const std::string& field) {
    const auto ng = static_cast<Index>(itf.nodes.size());
    Eigen::Matrix<double, 6, 6> G = Eigen::Matrix<double, 6, 6>::Zero();
    std::vector<Eigen::Matrix<double, 3, 6>> B(static_cast<std::size_t>(ng));
    for (Index j = 0; j < ng; ++j) {
      const Eigen::Vector3d d = model.mesh->x.row(itf.nodes[static_cast<std::size_t>(j)]).transpose() - itf.x;
      B[static_cast<std::size_t>(j)] << Eigen::Matrix3d::Identity(), -skew(d);
      G += B[static_cast<std::size_t>(j)].transpose() * B[static_cast<std::size_t>(j)];
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> es(G);
    if (es.eigenvalues()(0) <= 1e-10 * es.eigenvalues()(5))
      throw FormatError(file, field, "averaged coupling needs at least three non-collinear nodes in group '" +
                                         itf.group + "'");
    // A = G^-1 [B_1^T ... B_ng^T]: z_r = A u_group (6 x 3ng).
    Eigen::MatrixXd A(6, 3 * ng);
    const Eigen::Matrix<double, 6, 6> Ginv = G.inverse();
    for (Index j = 0; j < ng; ++j) A.middleCols(3 * j, 3) = Ginv * B[static_cast<std::size_t>(j)].transpose();
    auto group_dof = [&](Index col) { return model.dof(itf.nodes[static_cast<std::size_t>(col / 3)], static_cast<int>(col % 3)); };

    if (state == InterfaceState::Free) {
      for (int i = 0; i < 6; ++i) {
        Combination c;
        for (Index col = 0; col < 3 * ng; ++col)
          if (A(i, col) != 0) c.emplace_back(group_dof(col), A(i, col));
        depend(itf.dof + i, std::move(c));
      }
      return;
    }
    if (3 * ng > kMaxDenseAveragedDofs)
      throw FormatError(file, field, "averaged interface '" + itf.name + "' has " + std::to_string(3 * ng) +
                                         " DOFs; holding it or using it as a Craig-Bampton boundary couples them "
                                         "densely (limit " + std::to_string(kMaxDenseAveragedDofs) +
                                         "); use \"coupling\": \"rigid\" or a smaller group");
    // Six group DOFs become dependent: u_dep = A_dep^-1 (z_r - A_ind u_ind).
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
    std::vector<Index> dep_cols(6);
    for (int i = 0; i < 6; ++i) dep_cols[static_cast<std::size_t>(i)] = qr.colsPermutation().indices()(i);
    Eigen::Matrix<double, 6, 6> A_dep;
    for (int i = 0; i < 6; ++i) A_dep.col(i) = A.col(dep_cols[static_cast<std::size_t>(i)]);
    const Eigen::Matrix<double, 6, 6> A_dep_inv = A_dep.inverse();
    std::vector<bool> is_dep(static_cast<std::size_t>(3 * ng), false);
    for (Index c : dep_cols) is_dep[static_cast<std::size_t>(c)] = true;
    const Eigen::MatrixXd coeff = -A_dep_inv * A;  // applied to the independent group DOFs
    for (int i = 0; i < 6; ++i) {
      Combination c;
      for (Index col = 0; col < 3 * ng; ++col)
        if (!is_dep[static_cast<std::size_t>(col)] && coeff(i, col) != 0) c.emplace_back(group_dof(col), coeff(i, col));
      if (state == InterfaceState::Boundary)
        for (int k = 0; k < 6; ++k)
          if (A_dep_inv(i, k) != 0) c.emplace_back(itf.dof + k, A_dep_inv(i, k));
      depend(group_dof(dep_cols[static_cast<std::size_t>(i)]), std::move(c));
    }
    if (state == InterfaceState::Held)
      for (int a = 0; a < 6; ++a) hold(itf.dof + a);
  }
};

}  // namespace

DofTransform build_transform(const FeModel& model, const std::vector<InterfaceState>& state) {
  const std::string file = model.part ? model.part->file.string() : std::string("part");
  // Interface groups must be disjoint: a node cannot follow two interface nodes.
  std::unordered_map<Index, std::size_t> owner;
  for (std::size_t k = 0; k < model.interfaces.size(); ++k)
    for (Index n : model.interfaces[k].nodes) {
      auto [it, fresh] = owner.emplace(n, k);
      if (!fresh)
        throw FormatError(file, "interfaces[" + std::to_string(k) + "].group",
                          "node " + std::to_string(model.mesh->node_tag(n)) + " is in interfaces '" +
                              model.interfaces[it->second].name + "' and '" + model.interfaces[k].name +
                              "'; interface groups must not overlap");
    }

  Builder b(model);
  for (std::size_t k = 0; k < model.interfaces.size(); ++k) {
    const auto& itf = model.interfaces[k];
    const auto st = state.at(k);
    if (itf.coupling == "rigid") b.rigid(itf, st == InterfaceState::Held);
    else b.averaged(itf, st, file, "interfaces[" + std::to_string(k) + "]");
  }

  DofTransform t;
  const auto n = static_cast<std::size_t>(model.num_dofs);
  t.ind_of_full.assign(n, -1);
  for (std::size_t d = 0; d < n; ++d)
    if (b.status[d] == Status::Independent) {
      t.ind_of_full[d] = static_cast<Index>(t.full_of_ind.size());
      t.full_of_ind.push_back(static_cast<Index>(d));
    }
  t.identity = t.num_ind() == model.num_dofs;
  std::vector<Triplet> trip;
  trip.reserve(n + b.dep.size() * 4);
  for (std::size_t d = 0; d < n; ++d) {
    if (b.status[d] == Status::Independent) {
      trip.emplace_back(static_cast<Index>(d), t.ind_of_full[d], 1.0);
    } else if (b.status[d] == Status::Dependent) {
      for (const auto& [f, c] : b.dep[static_cast<Index>(d)]) {
        const Index ind = t.ind_of_full[static_cast<std::size_t>(f)];
        if (ind < 0) throw std::logic_error("constraint chain: a dependent DOF refers to a non-independent DOF");
        trip.emplace_back(static_cast<Index>(d), ind, c);
      }
    }
  }
  t.T.resize(model.num_dofs, t.num_ind());
  t.T.setFromTriplets(trip.begin(), trip.end());
  return t;
}

Eigen::MatrixXd rigid_body_modes(const FeModel& model, const DofTransform& t) {
  Eigen::MatrixXd R(t.num_ind(), 6);
  for (Index i = 0; i < t.num_ind(); ++i) R.row(i) = model.rigid_motion(t.full_of_ind[static_cast<std::size_t>(i)]);
  return R;
}

}  // namespace ffr::preproc
