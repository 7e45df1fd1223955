#include "weighted_gram.hpp"

#include "../integrator/kernel_clones.hpp"

#include <algorithm>

// Compiled at -O3 and for AVX2 as well (../integrator/kernel_clones.hpp).

namespace ffr::runtime::detail {
namespace {

// T(:, c) += sum_r Jb(r, c) buf(:, r) for every column c, R rows at once: one loop over the
// column's entries for all rows (a loop per row and column, with its set-up, cost more than
// its few multiply-adds).
template <int R>
inline void add_columns(const double* Jb, Eigen::Index ld, int rows, int na, int nb, const double* buf, double* T,
                        Eigen::Index ldt) {
  const int nr = R > 0 ? R : rows;
  for (int c = 0; c < nb; ++c) {
    double* __restrict t = T + c * ldt;
    double s[R > 0 ? R : 8];
    for (int r = 0; r < nr; ++r) s[r] = Jb[r + c * ld];
    for (int i = 0; i < na; ++i) {
      double acc = t[i];
      for (int r = 0; r < nr; ++r) acc += s[r] * buf[i + r * na];
      t[i] = acc;
    }
  }
}

}  // namespace

FFR_RT_CLONES
void weight_rows(const double* Ja, Eigen::Index ld, int rows, int na, const double* w, double* buf) {
  for (int r = 0; r < rows; ++r)
    for (int i = 0; i < na; ++i) buf[i + r * na] = w[r] * Ja[r + i * ld];
}

FFR_RT_CLONES
void add_weighted_product(const double* buf, int rows, int na, const double* Jb, Eigen::Index ld, int nb, double* T,
                          Eigen::Index ldt) {
  switch (rows) {
    case 1: add_columns<1>(Jb, ld, rows, na, nb, buf, T, ldt); break;
    case 2: add_columns<2>(Jb, ld, rows, na, nb, buf, T, ldt); break;
    case 3: add_columns<3>(Jb, ld, rows, na, nb, buf, T, ldt); break;
    case 4: add_columns<4>(Jb, ld, rows, na, nb, buf, T, ldt); break;
    case 5: add_columns<5>(Jb, ld, rows, na, nb, buf, T, ldt); break;
    case 6: add_columns<6>(Jb, ld, rows, na, nb, buf, T, ldt); break;
    default:
      for (int r0 = 0; r0 < rows; r0 += 6)  // blocks of at most 6 rows
        add_columns<0>(Jb + r0, ld, std::min(6, rows - r0), na, nb, buf + r0 * na, T, ldt);
  }
}

void add_weighted_gram(const double* Ja, const double* Jb, Eigen::Index ld, int rows, int na, int nb,
                       const double* w, double* buf, double* T, Eigen::Index ldt) {
  weight_rows(Ja, ld, rows, na, w, buf);
  add_weighted_product(buf, rows, na, Jb, ld, nb, T, ldt);
}

}  // namespace ffr::runtime::detail
