#include "pattern.hpp"

#include "../run_parts.hpp"

#include <algorithm>
#include <stdexcept>

namespace ffr::preproc::detail {

namespace {
// Entities touched by an element, in the order of its DOFs (unique).
std::vector<Index> element_entities(const FeModel& model, const ElementRef& ref) {
  std::vector<Index> ents;
  const Index N = model.mesh->num_nodes();
  if (ref.block >= 0) {
    const auto& blk = model.mesh->blocks[model.blocks[static_cast<std::size_t>(ref.block)].block];
    const Index* c = blk.element(ref.index);
    ents.assign(c, c + num_nodes(blk.type));
  } else {
    const auto& m = model.masses[static_cast<std::size_t>(ref.index)];
    ents.push_back(m.interface >= 0 ? N + m.interface : m.node);
  }
  return ents;
}
}  // namespace

Pattern build_pattern(const FeModel& model, const std::vector<ElementRef>& refs) {
  Pattern p;
  const Index N = model.mesh->num_nodes();
  const Index E = N + static_cast<Index>(model.interfaces.size());
  p.num_dofs = model.num_dofs;
  p.num_nodes = N;
  p.ent_dof0.resize(static_cast<std::size_t>(E));
  p.ent_ndof.resize(static_cast<std::size_t>(E));
  for (Index n = 0; n < N; ++n) {
    p.ent_dof0[static_cast<std::size_t>(n)] = model.node_dof[static_cast<std::size_t>(n)];
    p.ent_ndof[static_cast<std::size_t>(n)] = model.node_ndof[static_cast<std::size_t>(n)];
  }
  for (std::size_t k = 0; k < model.interfaces.size(); ++k) {
    p.ent_dof0[static_cast<std::size_t>(N) + k] = model.interfaces[k].dof;
    p.ent_ndof[static_cast<std::size_t>(N) + k] = 6;
  }

  // Adjacency: every entity with DOFs is adjacent to itself; elements connect their entities.
  // Built entity by entity from the elements incident to it (CSR, counted first), each list
  // gathered with a marker and sorted, straight into the flat arrays. Why: a growing vector
  // per entity took 0.15-0.25 s on the 100k-DOF plate (1.9 million insertions into 34 000
  // vectors, then a sort of each with its repeats), and the pattern is built twice when the
  // analysis runs beside the assembly (early_analysis.cpp).
  std::vector<std::vector<Index>> element_ents(refs.size());
  std::vector<Index> inc_ptr(static_cast<std::size_t>(E) + 1, 0);
  for (std::size_t k = 0; k < refs.size(); ++k) {
    element_ents[k] = element_entities(model, refs[k]);
    for (Index a : element_ents[k]) ++inc_ptr[static_cast<std::size_t>(a) + 1];
  }
  for (std::size_t e = 0; e < static_cast<std::size_t>(E); ++e) inc_ptr[e + 1] += inc_ptr[e];
  std::vector<Index> incident(static_cast<std::size_t>(inc_ptr.back()));
  {
    std::vector<Index> next(inc_ptr.begin(), inc_ptr.end() - 1);
    for (std::size_t k = 0; k < refs.size(); ++k)
      for (Index a : element_ents[k]) incident[static_cast<std::size_t>(next[static_cast<std::size_t>(a)]++)] = static_cast<Index>(k);
  }
  p.adj_ptr.assign(static_cast<std::size_t>(E) + 1, 0);
  p.adj.reserve(static_cast<std::size_t>(E) * 16);
  std::vector<Index> mark(static_cast<std::size_t>(E), -1);
  for (Index e = 0; e < E; ++e) {
    const std::size_t begin = p.adj.size();
    const auto add = [&](Index b) {
      if (mark[static_cast<std::size_t>(b)] == e) return;
      mark[static_cast<std::size_t>(b)] = e;
      p.adj.push_back(b);
    };
    if (p.ent_ndof[static_cast<std::size_t>(e)] > 0) add(e);
    for (Index k = inc_ptr[static_cast<std::size_t>(e)]; k < inc_ptr[static_cast<std::size_t>(e) + 1]; ++k)
      for (Index b : element_ents[static_cast<std::size_t>(incident[static_cast<std::size_t>(k)])])
        if (b != e) add(b);  // itself only with DOFs, as above
    std::sort(p.adj.begin() + static_cast<std::ptrdiff_t>(begin), p.adj.end());
    p.adj_ptr[static_cast<std::size_t>(e) + 1] = static_cast<Index>(p.adj.size());
  }
  p.adj.shrink_to_fit();
  p.adj_prefix.resize(p.adj.size());
  for (Index e = 0; e < E; ++e) {
    Index pre = 0;
    for (Index k = p.adj_ptr[static_cast<std::size_t>(e)]; k < p.adj_ptr[static_cast<std::size_t>(e) + 1]; ++k) {
      p.adj_prefix[static_cast<std::size_t>(k)] = pre;
      pre += p.ent_ndof[static_cast<std::size_t>(p.adj[static_cast<std::size_t>(k)])];
    }
  }

  // DOF-level columns: each DOF of entity e has the rows of all DOFs of e's neighbours.
  p.col_ptr.assign(static_cast<std::size_t>(p.num_dofs) + 1, 0);
  for (Index e = 0; e < E; ++e) {
    const int nd = p.ent_ndof[static_cast<std::size_t>(e)];
    if (nd == 0) continue;
    const auto last = static_cast<std::size_t>(p.adj_ptr[static_cast<std::size_t>(e) + 1] - 1);
    const Index rows = p.adj_prefix[last] + p.ent_ndof[static_cast<std::size_t>(p.adj[last])];
    for (int a = 0; a < nd; ++a) p.col_ptr[static_cast<std::size_t>(p.ent_dof0[static_cast<std::size_t>(e)] + a) + 1] = rows;
  }
  for (std::size_t c = 0; c < static_cast<std::size_t>(p.num_dofs); ++c) p.col_ptr[c + 1] += p.col_ptr[c];

  // Node-level columns, upper triangle (mesh nodes up to the column's own; interface entities
  // sort after all mesh nodes).
  p.node_col_ptr.assign(static_cast<std::size_t>(N) + 1, 0);
  for (Index n = 0; n < N; ++n) {
    Index cnt = 0;
    for (Index k = p.adj_ptr[static_cast<std::size_t>(n)]; k < p.adj_ptr[static_cast<std::size_t>(n) + 1]; ++k)
      if (p.adj[static_cast<std::size_t>(k)] <= n) ++cnt;
    p.node_col_ptr[static_cast<std::size_t>(n) + 1] = p.node_col_ptr[static_cast<std::size_t>(n)] + cnt;
  }
  return p;
}

Index Pattern::entity_of_dof(const FeModel& m, Index d) const {
  return d < m.mesh_dofs() ? m.dof_node[static_cast<std::size_t>(d)] : num_nodes + (d - m.mesh_dofs()) / 6;
}

Index Pattern::find(Index col_entity, Index row_entity) const {
  const auto b = adj.begin() + adj_ptr[static_cast<std::size_t>(col_entity)];
  const auto e = adj.begin() + adj_ptr[static_cast<std::size_t>(col_entity) + 1];
  const auto it = std::lower_bound(b, e, row_entity);
  if (it == e || *it != row_entity) throw std::logic_error("assembly pattern: entity pair not in the pattern");
  return static_cast<Index>(it - adj.begin());
}

void Pattern::make_matrix(SparseMatrix& A, unsigned threads, double value) const {
  A.resize(num_dofs, num_dofs);
  A.resizeNonZeros(col_ptr.back());
  std::copy(col_ptr.begin(), col_ptr.end(), A.outerIndexPtr());
  // Each entity writes the row indices and values of its own columns, so parts of the
  // entities can be filled by separate threads. Why: this is the first touch of K's and M's
  // 250 MB on the 100k plate, serial 0.15 s (mostly page faults), a third of the assembly at
  // 2 threads. (Every stored entry is in a column of some entity's DOFs.)
  const Index E = static_cast<Index>(ent_ndof.size());
  const unsigned parts = col_ptr.back() < (Index{1} << 16) ? 1u : std::max(1u, threads);
  run_parts(parts, [&](unsigned p) { return E * static_cast<Index>(p) / static_cast<Index>(parts); },
            [&](unsigned, Index e0, Index e1) {
    Index* inner = A.innerIndexPtr();
    double* val = A.valuePtr();
    for (Index e = e0; e < e1; ++e) {
      const int nd = ent_ndof[static_cast<std::size_t>(e)];
      if (nd == 0) continue;
      const Index c0 = ent_dof0[static_cast<std::size_t>(e)];
      std::fill(val + col_ptr[static_cast<std::size_t>(c0)], val + col_ptr[static_cast<std::size_t>(c0 + nd)], value);
      for (int a = 0; a < nd; ++a) {
        Index pos = col_ptr[static_cast<std::size_t>(c0 + a)];
        for (Index k = adj_ptr[static_cast<std::size_t>(e)]; k < adj_ptr[static_cast<std::size_t>(e) + 1]; ++k) {
          const Index b = adj[static_cast<std::size_t>(k)];
          for (int r = 0; r < ent_ndof[static_cast<std::size_t>(b)]; ++r) inner[pos++] = ent_dof0[static_cast<std::size_t>(b)] + r;
        }
      }
    }
  });
}

void Pattern::make_node_matrix(SparseMatrix& A) const {
  A.resize(num_nodes, num_nodes);
  A.resizeNonZeros(node_col_ptr.back());
  std::copy(node_col_ptr.begin(), node_col_ptr.end(), A.outerIndexPtr());
  for (Index n = 0; n < num_nodes; ++n) {
    Index pos = node_col_ptr[static_cast<std::size_t>(n)];
    for (Index k = adj_ptr[static_cast<std::size_t>(n)]; k < adj_ptr[static_cast<std::size_t>(n) + 1]; ++k)
      if (adj[static_cast<std::size_t>(k)] <= n) A.innerIndexPtr()[pos++] = adj[static_cast<std::size_t>(k)];
  }
  std::fill(A.valuePtr(), A.valuePtr() + node_col_ptr.back(), 0.0);
}

Placement Pattern::place(const std::vector<Index>& dofs, const FeModel& m) const {
  Placement p;
  const auto nd = dofs.size();
  p.ent_of.resize(nd);
  p.off.resize(nd);
  p.col0.resize(nd);
  for (std::size_t i = 0; i < nd; ++i) {
    const Index e = entity_of_dof(m, dofs[i]);
    const auto it = std::find(p.ents.begin(), p.ents.end(), e);
    p.ent_of[i] = static_cast<int>(it - p.ents.begin());
    if (it == p.ents.end()) p.ents.push_back(e);
    p.off[i] = dofs[i] - ent_dof0[static_cast<std::size_t>(e)];
    p.col0[i] = col_ptr[static_cast<std::size_t>(dofs[i])];
  }
  const std::size_t ne = p.ents.size();
  p.slot.resize(ne * ne);
  for (std::size_t b = 0; b < ne; ++b)
    for (std::size_t a = 0; a < ne; ++a) p.slot[b * ne + a] = find(p.ents[b], p.ents[a]);
  return p;
}

void Pattern::add(SparseMatrix& A, const Placement& p, const Eigen::MatrixXd& Ae) const {
  const auto nd = p.ent_of.size();
  const auto ne = p.ents.size();
  double* val = A.valuePtr();
  for (std::size_t j = 0; j < nd; ++j) {
    const Index* slots = p.slot.data() + static_cast<std::size_t>(p.ent_of[j]) * ne;
    const double* col = Ae.data() + static_cast<Index>(j) * Ae.rows();
    for (std::size_t i = 0; i < nd; ++i) {
      if (col[i] == 0.0) continue;
      val[p.col0[j] + adj_prefix[static_cast<std::size_t>(slots[p.ent_of[i]])] + p.off[i]] += col[i];
    }
  }
}

void Pattern::add_node_scalar(SparseMatrix& Ms, const Placement& p, const Eigen::MatrixXd& Me) const {
  double* val = Ms.valuePtr();
  const auto ne = p.ents.size();
  for (std::size_t b = 0; b < ne; ++b) {
    const auto cn = static_cast<std::size_t>(p.ents[b]);
    // adj is sorted: the nodes up to the column's own come first, so for those the slot less
    // the column's first slot is the position in the upper-triangle column.
    const Index c0 = node_col_ptr[cn] - adj_ptr[cn];
    for (std::size_t a = 0; a < ne; ++a)
      if (p.ents[a] <= p.ents[b]) val[c0 + p.slot[b * ne + a]] += Me(3 * static_cast<Index>(a), 3 * static_cast<Index>(b));
  }
}

}  // namespace ffr::preproc::detail
