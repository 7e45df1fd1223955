// Symbolic factor from the group graph (see grouped_symbolic.hpp for why).
#include "grouped_symbolic.hpp"

#include <algorithm>
#include <cmath>

namespace ffr::preproc::detail {
namespace {

using Long = SuiteSparse_long;

// Allocates `count` SuiteSparse_long with CHOLMOD's allocator, so that cholmod_l_free_factor
// frees them with the factor.
Long* allocate(std::size_t count, cholmod_common* c) {
  return static_cast<Long*>(cholmod_l_malloc(std::max<std::size_t>(count, 1), sizeof(Long), c));
}

// The group graph's upper triangle with its diagonal, pattern only, for cholmod_l_analyze_p.
cholmod_sparse* group_matrix(const QuotientGraph& q, cholmod_common* c) {
  const auto ng = static_cast<Long>(q.first.size()) - 1;
  Long nnz = ng;
  for (Long g = 0; g < ng; ++g)
    for (auto k = q.xadj[static_cast<std::size_t>(g)]; k < q.xadj[static_cast<std::size_t>(g) + 1]; ++k)
      nnz += q.adjncy[static_cast<std::size_t>(k)] < g ? 1 : 0;
  cholmod_sparse* A = cholmod_l_allocate_sparse(static_cast<std::size_t>(ng), static_cast<std::size_t>(ng),
                                                static_cast<std::size_t>(nnz), 1, 1, 1, CHOLMOD_PATTERN, c);
  if (!A) return nullptr;
  auto* p = static_cast<Long*>(A->p);
  auto* i = static_cast<Long*>(A->i);
  Long k = 0;
  for (Long g = 0; g < ng; ++g) {
    p[g] = k;
    const Long start = k;
    for (auto e = q.xadj[static_cast<std::size_t>(g)]; e < q.xadj[static_cast<std::size_t>(g) + 1]; ++e)
      if (const Long h = q.adjncy[static_cast<std::size_t>(e)]; h < g) i[k++] = h;
    i[k++] = g;
    std::sort(i + start, i + k);
  }
  p[ng] = k;
  return A;
}

}  // namespace

std::vector<std::int64_t> group_order(const QuotientGraph& q, const std::vector<std::int64_t>& perm) {
  const auto ng = static_cast<std::int64_t>(q.first.size()) - 1;
  const std::int64_t n = ng >= 0 ? q.first.back() : 0;
  if (ng < 1 || static_cast<std::int64_t>(perm.size()) != n) return {};
  std::vector<std::int64_t> order;
  order.reserve(static_cast<std::size_t>(ng));
  for (std::int64_t k = 0; k < n;) {
    const std::int64_t col = perm[static_cast<std::size_t>(k)];
    if (col < 0 || col >= n) return {};
    const auto g = static_cast<std::int64_t>(std::upper_bound(q.first.begin(), q.first.end(), col) - q.first.begin()) - 1;
    const std::int64_t w = q.first[static_cast<std::size_t>(g) + 1] - q.first[static_cast<std::size_t>(g)];
    if (col != q.first[static_cast<std::size_t>(g)] || k + w > n) return {};
    for (std::int64_t t = 0; t < w; ++t)
      if (perm[static_cast<std::size_t>(k + t)] != col + t) return {};
    order.push_back(g);
    k += w;
  }
  return static_cast<std::int64_t>(order.size()) == ng ? order : std::vector<std::int64_t>{};
}

GroupedSymbolic grouped_symbolic(const QuotientGraph& q, const std::vector<std::int64_t>& group_perm, cholmod_common* c) {
  GroupedSymbolic out;
  const auto ng = static_cast<Long>(q.first.size()) - 1;
  const Long n = q.first.back();
  const auto weight = [&q](Long g) { return q.first[static_cast<std::size_t>(g) + 1] - q.first[static_cast<std::size_t>(g)]; };

  // CHOLMOD's analysis of the group graph, its amalgamation limits scaled to group columns.
  cholmod_sparse* A = group_matrix(q, c);
  if (!A) return out;
  const double mean = static_cast<double>(n) / static_cast<double>(ng);
  size_t nrelax[3];
  for (int r = 0; r < 3; ++r) {
    nrelax[r] = c->nrelax[r];
    c->nrelax[r] = std::max<size_t>(1, static_cast<size_t>(std::lround(static_cast<double>(nrelax[r]) / mean)));
  }
  c->nmethods = 1;
  c->method[0].ordering = CHOLMOD_GIVEN;
  std::vector<Long> perm(group_perm.begin(), group_perm.end());
  cholmod_factor* Lg = cholmod_l_analyze_p(A, perm.data(), nullptr, 0, c);
  cholmod_l_free_sparse(&A, c);
  for (int r = 0; r < 3; ++r) c->nrelax[r] = nrelax[r];
  if (!Lg) return out;
  if (!Lg->is_super) {
    cholmod_l_free_factor(&Lg, c);
    return out;
  }
  const auto* gperm = static_cast<const Long*>(Lg->Perm);
  const auto* gsuper = static_cast<const Long*>(Lg->super);
  const auto* gpi = static_cast<const Long*>(Lg->pi);
  const auto* gs = static_cast<const Long*>(Lg->s);
  const auto* gcount = static_cast<const Long*>(Lg->ColCount);
  const auto nsuper = static_cast<Long>(Lg->nsuper);

  // start[k]: the first column of the group at position k in the new order.
  std::vector<Long> start(static_cast<std::size_t>(ng) + 1, 0);
  for (Long k = 0; k < ng; ++k) start[static_cast<std::size_t>(k) + 1] = start[static_cast<std::size_t>(k)] + weight(gperm[k]);

  cholmod_factor* L = cholmod_l_allocate_factor(static_cast<std::size_t>(n), c);
  if (!L) {
    cholmod_l_free_factor(&Lg, c);
    return out;
  }
  Long ssize = 0, xsize = 0;
  for (Long s = 0; s < nsuper; ++s) {
    Long nsrow = 0;
    for (Long p = gpi[s]; p < gpi[s + 1]; ++p) nsrow += start[static_cast<std::size_t>(gs[p]) + 1] - start[static_cast<std::size_t>(gs[p])];
    const Long nscol = start[static_cast<std::size_t>(gsuper[s + 1])] - start[static_cast<std::size_t>(gsuper[s])];
    ssize += nsrow;
    xsize += nsrow * nscol;
  }
  Long* super = allocate(static_cast<std::size_t>(nsuper) + 1, c);
  Long* pi = allocate(static_cast<std::size_t>(nsuper) + 1, c);
  Long* px = allocate(static_cast<std::size_t>(nsuper) + 1, c);
  Long* rows = allocate(static_cast<std::size_t>(ssize), c);
  if (!super || !pi || !px || !rows) {
    for (Long* a2 : {super, pi, px}) cholmod_l_free(static_cast<std::size_t>(nsuper) + 1, sizeof(Long), a2, c);
    cholmod_l_free(std::max<std::size_t>(static_cast<std::size_t>(ssize), 1), sizeof(Long), rows, c);
    cholmod_l_free_factor(&L, c);
    cholmod_l_free_factor(&Lg, c);
    return out;
  }
  auto* Perm = static_cast<Long*>(L->Perm);
  auto* ColCount = static_cast<Long*>(L->ColCount);
  for (Long k = 0; k < ng; ++k) {
    const Long g = gperm[k];
    for (Long t = 0; t < weight(g); ++t) Perm[start[static_cast<std::size_t>(k)] + t] = q.first[static_cast<std::size_t>(g)] + t;
  }
  for (Long s = 0; s < nsuper; ++s) super[s] = start[static_cast<std::size_t>(gsuper[s])];
  super[nsuper] = n;
  Long maxesize = 0, maxcsize = 1;
  pi[0] = px[0] = 0;
  for (Long s = 0; s < nsuper; ++s) {
    Long r = pi[s];
    for (Long p = gpi[s]; p < gpi[s + 1]; ++p)
      for (Long i = start[static_cast<std::size_t>(gs[p])]; i < start[static_cast<std::size_t>(gs[p]) + 1]; ++i) rows[r++] = i;
    pi[s + 1] = r;
    const Long nscol = super[s + 1] - super[s], nsrow = r - pi[s];
    px[s + 1] = px[s] + nsrow * nscol;
    for (Long j = 0; j < nscol; ++j) ColCount[super[s] + j] = nsrow - j;
    maxesize = std::max(maxesize, nsrow - nscol);
    // The largest update this supernode sends (CHOLMOD's maxcsize): for each ancestor whose
    // columns hold some of its rows, those rows times the rows from them on.
    for (Long a = pi[s] + nscol; a < r;) {
      const Long t = static_cast<Long>(std::upper_bound(super, super + nsuper + 1, rows[a]) - super) - 1;
      Long b = a;
      while (b < r && rows[b] < super[t + 1]) ++b;
      maxcsize = std::max(maxcsize, (b - a) * (r - a));
      a = b;
    }
  }
  // Statistics as CHOLMOD reports them, from the group factor's exact column counts (no
  // amalgamation zeros): column t of a group of w columns whose group column has `count` group
  // rows holds the columns of those groups from its own on, w count - t where they all have w
  // columns (a solid mesh's nodes); an estimate where the sizes differ.
  for (Long k = 0; k < ng; ++k) {
    const Long w = weight(gperm[k]);
    for (Long t = 0; t < w; ++t) {
      const double cnt = static_cast<double>(w * gcount[k] - t);
      out.lnz += cnt;
      out.flops += cnt * cnt;
    }
  }
  cholmod_l_free_factor(&Lg, c);

  L->ordering = CHOLMOD_GIVEN;
  L->is_super = 1;
  L->is_ll = 1;
  L->is_monotonic = 1;
  L->xtype = CHOLMOD_PATTERN;
  L->nsuper = static_cast<size_t>(nsuper);
  L->ssize = static_cast<size_t>(ssize);
  L->xsize = static_cast<size_t>(xsize);
  L->maxesize = static_cast<size_t>(maxesize);
  L->maxcsize = static_cast<size_t>(maxcsize);
  L->super = super;
  L->pi = pi;
  L->px = px;
  L->s = rows;
  L->minor = static_cast<size_t>(n);
  out.L = L;
  return out;
}

}  // namespace ffr::preproc::detail
