#pragma once
// The blocks of K, C, W and T that can be nonzero: each body's diagonal block, and the two
// blocks between a pair of bodies that a force element (spring, bushing, friction damper), a
// geometrically exact beam's element or a constraint block (its penalty term and second
// derivatives) joins. A tyre, a load and a body's own terms stay in its diagonal block. Outside
// these blocks the four matrices are zero (set so at construction, never written), so the step
// clears, combines and multiplies them over the blocks alone: on a model of many bodies (a
// chain, a geometrically exact beam's node bodies) the dense n x n passes were most of what the
// tangent cost besides its LU. Whatever adds a term between two bodies must be listed here
// (tests/runtime/tangent_blocks_test.cpp checks every kind of element).

#include "ffr/runtime/data.hpp"
#include "ffr/runtime/model.hpp"
#include "../model/known_frame.hpp"

#include <algorithm>
#include <array>
#include <vector>

namespace ffr::runtime::detail {

/// The pairs of distinct bodies whose off-diagonal blocks can be nonzero, each once, lower index
/// first (Data::body_pairs). Why once: several elements join the same two bodies (a cab's four
/// mounts), and every pass over the blocks visited their blocks once per element.
std::vector<std::array<int, 2>> coupled_body_pairs(const Model& model);

/// f(a, b) for each pair of Data::body_pairs, both bodies integrated with integrated_only.
template <class F>
void for_each_coupled_pair(const Data& data, bool integrated_only, F&& f) {
  for (const auto& [a, b] : data.body_pairs) {
    if (integrated_only && !(integrated(data, a) && integrated(data, b))) continue;
    f(a, b);
  }
}

/// f(a, b) for each element or constraint block that joins two distinct bodies (a pair may come
/// more than once, in either order): what coupled_body_pairs collects.
template <class F>
void for_each_coupling(const Model& model, F&& f) {
  const auto pair = [&](int a, int b) {
    if (a == kGround || b == kGround || a == b) return;
    f(a, b);
  };
  const auto body = [&](int marker) { return model.markers[static_cast<std::size_t>(marker)].body; };
  for (const SpringDamper& s : model.springs) pair(body(s.m1), body(s.m2));
  for (const Bushing& s : model.bushings) pair(body(s.m1), body(s.m2));
  for (const FrictionDamper& s : model.friction_dampers) pair(body(s.m1), body(s.m2));
  for (const GeBeam& g : model.ge_beams)
    for (std::size_t k = 0; k + 1 < g.node_bodies.size(); ++k) pair(g.node_bodies[k], g.node_bodies[k + 1]);
  for (const ConstraintBlock& b : model.blocks) {
    const int bodies[4] = {b.body1, b.body2, b.body3, b.body4};  // (a coupler may join four)
    for (int x = 0; x < 4; ++x)
      for (int y = x + 1; y < 4; ++y) pair(bodies[x], bodies[y]);
  }
}

/// True when an ancf beam's diagonal block is its band (for_each_body_block; Data::banded holds it
/// per body): its frame is known
/// (known_frame.hpp), so nothing couples two of its nodes but its elements, unless a force
/// element or a joint joins two of its own points.
inline bool banded_beam(const Model& model, int body) {
  const Body& b = model.bodies[static_cast<std::size_t>(body)];
  if (!frame_known(model, b)) return false;
  const auto on = [&](int marker) { return model.markers[static_cast<std::size_t>(marker)].body == body; };
  for (const SpringDamper& s : model.springs)
    if (on(s.m1) && on(s.m2)) return false;
  for (const Bushing& s : model.bushings)
    if (on(s.m1) && on(s.m2)) return false;
  for (const FrictionDamper& s : model.friction_dampers)
    if (on(s.m1) && on(s.m2)) return false;
  for (const ConstraintBlock& c : model.blocks) {
    int n = 0;
    for (int x : {c.body1, c.body2, c.body3, c.body4}) n += x == body;
    if (n > 1) return false;
  }
  return true;
}

/// g(row0, rows, col0, cols) for the blocks of a body's diagonal block that can be nonzero, none
/// visited twice: the whole of it, or of a banded ancf beam (above) its frame's rows and columns
/// (the terms of markers on its nodes and of its held frame's rows) and each node's six rows over
/// its own and its neighbours' columns. Why: its elements and mass couple only neighbouring
/// nodes, and the dense passes over the whole block were a sixth of a 16-element beam's step.
template <class G>
void for_each_body_block(const Model& model, const Data& data, int body, G&& g) {
  const Body& b = model.bodies[static_cast<std::size_t>(body)];
  if (!data.banded[static_cast<std::size_t>(body)]) {
    g(b.offset, b.ncoord(), b.offset, b.ncoord());
    return;
  }
  const int o = b.offset, n = b.ncoord(), last = b.beam->elements;
  g(o, 12, o, n);
  g(o + 12, n - 12, o, 12);
  for (int k = 0; k <= last; ++k) {
    const int first = std::max(k - 1, 0), end = std::min(k + 1, last) + 1;  // nodes [first, end)
    g(o + 12 + 6 * k, 6, o + 12 + 6 * first, 6 * (end - first));
  }
}

/// g(row0, rows, col0, cols) for both off-diagonal blocks (i, j) and (j, i) of each coupled pair
/// (for_each_coupled_pair).
template <class G>
void for_each_pair_block(const Model& model, const Data& data, bool integrated_only, G&& g) {
  for_each_coupled_pair(data, integrated_only, [&](int i, int j) {
    const Body& bi = model.bodies[static_cast<std::size_t>(i)];
    const Body& bj = model.bodies[static_cast<std::size_t>(j)];
    g(bi.offset, bi.ncoord(), bj.offset, bj.ncoord());
    g(bj.offset, bj.ncoord(), bi.offset, bi.ncoord());
  });
}

/// g(row0, rows, col0, cols) for each tangent block: every body's diagonal block (or its blocks,
/// for_each_body_block), then both blocks of each coupled pair (for_each_pair_block). No block is
/// visited twice, but the blocks are for idempotent work (clearing, assigning) and products only.
template <class G>
void for_each_tangent_block(const Model& model, const Data& data, bool integrated_only, G&& g) {
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    if (integrated_only && !data.integrated[i]) continue;
    for_each_body_block(model, data, static_cast<int>(i), g);
  }
  for_each_pair_block(model, data, integrated_only, g);
}

/// True when the integrated bodies' tangent blocks cover less than half of the unknowns' nf x nf
/// matrix (blocks visited twice counted twice): then the passes over the blocks are cheaper than
/// the dense ones. On a model of a few large, mutually coupled bodies (a washing machine's tub,
/// cabinet, drum and rotor) the blocks cover most of the matrix, and the many small block
/// operations cost more than one vectorised pass over it.
inline bool decide_tangent_blocks_pay(const Model& model, const Data& data) {
  long area = 0;
  for_each_tangent_block(model, data, true, [&](int, int nr, int, int nc) { area += static_cast<long>(nr) * nc; });
  return 2 * area < static_cast<long>(data.nf) * data.nf;
}

/// Per factorised column j < k (positions given by pos: coordinate -> position, -1 for a known
/// coordinate), the first and last row that the integrated bodies' tangent blocks reach.
void column_spans(const Model& model, const Data& data, const std::vector<int>& pos, int k, int* first, int* last);

/// Data::lu_runs and lu_pos: the order of the factorised tangent's rows and columns, body by body
/// (each body's unknowns in their own order): the model's, or a minimum-degree order of the
/// body-coupling graph postordered along its elimination tree where that saves a tenth of the
/// factorisation's estimated work.
void factorisation_order(const Model& model, Data& data);

/// Where the blocks pay (else nothing): the factorisation's order (factorisation_order), then
/// Data::lu_first and lu_last, in that order, from the tangent blocks of the integrated bodies:
/// the penalty terms, the constraint Hessian and the modal acceleration terms that
/// refresh_constraint_tangent adds lie in the same blocks.
void tangent_row_spans(const Model& model, Data& data);

/// True when the constraint blocks' rows times their integrated bodies' columns cover less than
/// half of the unknowns' na x nf Jacobian (constraints.cpp).
bool decide_block_columns_pay(const Model& model, const Data& data);

}  // namespace ffr::runtime::detail
