#include "pattern_analysis.hpp"

#include "setup.hpp"
#include "sparse_ops.hpp"
#include "../solver/pattern_hash.hpp"

#include <algorithm>

namespace ffr::preproc::detail {

std::vector<Index> unit_column_rows(const DofTransform& t, const std::vector<Index>& columns) {
  if (!t.identity) return selected_rows(t.T, &columns);
  for (std::size_t k = 1; k < columns.size(); ++k)
    if (columns[k] <= columns[k - 1]) return {};
  return columns;
}

std::optional<SelectedStructure> selected_structure(const Pattern& p, const std::vector<Index>& rows, bool upper) {
  const auto E = static_cast<Index>(p.ent_ndof.size());
  const auto dof0 = [&p](Index e) { return p.ent_dof0[static_cast<std::size_t>(e)]; };
  const auto ndof = [&p](Index e) { return static_cast<Index>(p.ent_ndof[static_cast<std::size_t>(e)]); };
  for (Index e = 0, end = 0; e < E; ++e) {
    if (ndof(e) == 0) continue;
    if (dof0(e) < end) return std::nullopt;
    end = dof0(e) + ndof(e);
  }
  std::vector<Index> new_of_old(static_cast<std::size_t>(p.num_dofs), -1);
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const Index r = rows[j];
    if (r < 0 || r >= p.num_dofs || (j > 0 && r <= rows[j - 1])) return std::nullopt;
    new_of_old[static_cast<std::size_t>(r)] = static_cast<Index>(j);
  }
  const auto kept = [&new_of_old](Index d) { return new_of_old[static_cast<std::size_t>(d)]; };

  // Groups: the entities with kept DOFs, in DOF order; their kept DOFs are consecutive in the
  // new numbering, since rows ascend and an entity's DOFs are contiguous.
  SelectedStructure out;
  QuotientGraph& g = out.graph;
  std::vector<Index> group(static_cast<std::size_t>(E), -1);
  for (Index e = 0; e < E; ++e)
    for (Index a = 0; a < ndof(e); ++a)
      if (kept(dof0(e) + a) >= 0) {
        group[static_cast<std::size_t>(e)] = static_cast<Index>(g.first.size());
        g.first.push_back(kept(dof0(e) + a));
        break;
      }
  g.first.push_back(static_cast<Index>(rows.size()));
  g.xadj.reserve(g.first.size());
  g.xadj.push_back(0);
  for (Index e = 0; e < E; ++e) {
    if (group[static_cast<std::size_t>(e)] < 0) continue;
    for (Index k = p.adj_ptr[static_cast<std::size_t>(e)]; k < p.adj_ptr[static_cast<std::size_t>(e) + 1]; ++k) {
      const Index b = p.adj[static_cast<std::size_t>(k)];
      if (b != e && group[static_cast<std::size_t>(b)] >= 0) g.adjncy.push_back(group[static_cast<std::size_t>(b)]);
    }
    g.xadj.push_back(static_cast<Index>(g.adjncy.size()));
  }

  // Upper triangle of A(rows, rows): column j (a kept DOF of entity e) holds the kept DOFs
  // i <= j of e's neighbours, ascending as the neighbours and their DOFs are: a prefix of the
  // entity's row list, which its columns share. The columns come in ascending order.
  const auto n = static_cast<Index>(rows.size());
  std::vector<Index> list;
  auto each_column = [&](auto&& body) {
    for (Index e = 0; e < E; ++e) {
      if (group[static_cast<std::size_t>(e)] < 0) continue;
      list.clear();
      for (Index k = p.adj_ptr[static_cast<std::size_t>(e)]; k < p.adj_ptr[static_cast<std::size_t>(e) + 1]; ++k) {
        const Index b = p.adj[static_cast<std::size_t>(k)];
        for (Index r = 0; r < ndof(b); ++r)
          if (const Index i = kept(dof0(b) + r); i >= 0) list.push_back(i);
      }
      for (Index a = 0; a < ndof(e); ++a)
        if (const Index j = kept(dof0(e) + a); j >= 0)
          body(j, static_cast<Index>(std::upper_bound(list.begin(), list.end(), j) - list.begin()));
    }
  };
  PatternHash hash(n);
  each_column([&](Index j, Index count) {
    hash.column(j);
    for (Index k = 0; k < count; ++k) hash.row(list[static_cast<std::size_t>(k)]);
  });
  out.hash = hash.value();
  out.upper_nnz = hash.entries();
  if (!upper) return out;

  // The matrix: counted first, then written.
  SparseMatrix& C = out.upper;
  C.resize(n, n);
  auto* outer = C.outerIndexPtr();
  outer[0] = 0;
  each_column([&](Index j, Index count) { outer[j + 1] = count; });
  for (Index j = 0; j < n; ++j) outer[j + 1] += outer[j];
  C.resizeNonZeros(outer[n]);
  auto* inner = C.innerIndexPtr();
  each_column([&](Index j, Index count) { std::copy(list.begin(), list.begin() + count, inner + outer[j]); });
  // The values stay unset, their pages untouched: the analysis reads the structure only.
  return out;
}

std::vector<Index> factorized_rows(const FeModel& model, const DofTransform& t, const ReductionSpec& spec) {
  std::vector<Index> columns;
  if (spec.method == ReductionSpec::Method::CraigBampton) {
    columns = interior_of(t.num_ind(), boundary_dofs(model, t, spec));
  } else {
    columns.resize(static_cast<std::size_t>(t.num_ind()));
    for (std::size_t j = 0; j < columns.size(); ++j) columns[j] = static_cast<Index>(j);
  }
  return unit_column_rows(t, columns);
}

bool analyse_from_pattern(const FeModel& model, const DofTransform& t, const ReductionSpec& spec, const SparseMatrix* C,
                          const std::atomic<bool>* cancel, CholmodFactor& f) {
  if (eigen_factor_options(spec).ordering != Ordering::Metis) return false;  // another order asked for
  const auto cancelled = [cancel] { return cancel && cancel->load(); };
  const std::vector<Index> rows = factorized_rows(model, t, spec);
  if (rows.empty()) return false;
  std::optional<SelectedStructure> st;
  {
    const Pattern p = build_pattern(model, all_elements(model));
    st = selected_structure(p, rows, false);
  }
  if (!st || cancelled()) return false;
  const NodalOrdering order = metis_ordering(st->graph);
  if (order.perm.empty() || cancelled()) return false;
  // The symbolic factor from the node graph (grouped_symbolic.hpp); the structure hashed is the
  // one the factorized matrix has, which factorize checks (C's own, where it exists already).
  std::uint64_t hash = st->hash;
  std::int64_t upper_nnz = st->upper_nnz;
  if (C) hash = upper_pattern_hash(*C, &upper_nnz);
  f.analyze_groups(st->graph, order.perm, order.groups, hash, upper_nnz);
  return true;
}

}  // namespace ffr::preproc::detail
