// The step clears, combines and multiplies K, C, W, T and Phi_q only over their blocks
// (runtime/src/integrator/tangent_blocks.hpp; a constraint block's rows and its bodies'
// columns), relying on every term being written inside
// them. Checked here on models with every kind of element: entries outside the blocks are set
// to a sentinel value before the tangents and the Jacobian are rebuilt, and must keep it (a term
// added between two bodies that set_tangent_blocks does not know would change it); and the
// block products with Phi_q against Eigen's dense products with the same matrix (the oracle).
#include "mixed_model.hpp"
#include "simeon_rod.hpp"
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include "ffr/runtime/constraints.hpp"
#include "ffr/runtime/dynamics.hpp"
#include "ffr/runtime/integrator.hpp"
#include "ffr/runtime/state.hpp"
#include "integrator/tangent_blocks.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

using namespace ffr::runtime;

namespace {

constexpr double kSentinel = 0.75;

// Every kind of element of the runtime's allocation tests: a driven crank, a flexible rod with
// Ke/M1, a slider, a flexible flap with stiffening interface loads on a bushing, springs, point
// loads; couplers, friction dampers with and without series springs, a bushing between two
// bodies, tables; tyres; a geometrically exact beam with a body fixed to its end; an ancf beam.
const std::string kMixed = test::mixed_model_json(R"([
    {"type": "spring_damper", "body1": "slider", "at1": [0.45, 0, 0], "body2": "rod", "node2": "M", "k": 100, "c": 1},
    {"type": "bushing", "body1": "flap", "node1": "B", "body2": "rod", "node2": "M", "stiffness": [1e3, 1e3, 1e3, 10, 10, 10], "damping": [1, 1, 1, 0.1, 0.1, 0.1]},
    {"type": "friction_damper", "body1": "slider", "at1": [0.45, 0.1, 0], "body2": "flap", "node2": "C", "force": 0.5, "series_stiffness": 300},
    {"type": "point_force", "body": "rod", "node": "M", "table": {"t": [0, 1], "value": [[0, 1, 0], [0, -1, 0]]}},
    {"type": "point_torque", "body": "flap", "node": "C", "table": {"t": [0, 1], "value": [[0, 0, 0.1], [0, 0, 0.2]]}}
  ])", R"("solver": {"end": 0.2, "step": 1e-3})");

const char* kCarrier = R"({
  "gravity": [0, -9.81, 0],
  "bodies": [
    {"name": "c", "type": "rigid", "mass": 5, "com": [0, 0, 0], "inertia": [[1.2, 0, 0], [0, 1.2, 0], [0, 0, 2]]},
    {"name": "a", "type": "rigid", "mass": 1, "com": [0.5, 0, 0], "inertia": [[0.15, 0, 0], [0, 0.15, 0], [0, 0, 0.2]]},
    {"name": "b", "type": "rigid", "mass": 2, "com": [-0.5, 0, 0], "inertia": [[0.03, 0, 0], [0, 0.03, 0], [0, 0, 0.05]]},
    {"name": "wheel", "type": "rigid", "mass": 15, "com": [3, 0.2993, 0], "inertia": [[0.7, 0, 0], [0, 0.7, 0], [0, 0, 1.2]],
     "velocity": [3, 0, 0], "angular_velocity": [0, 0, -9]}
  ],
  "roads": [{"name": "bumpy", "direction": [1, 0, 0], "s": [-5, -1, 0, 0.5, 1, 2, 5], "height": [0, 0, 0.002, -0.002, 0.003, 0, 0]}],
  "joints": [
    {"name": "jc", "type": "revolute", "body1": "ground", "body2": "c", "at": [0, 0, 0], "axis": [0, 0, 1]},
    {"name": "ja", "type": "revolute", "body1": "c", "body2": "a", "at": [0.5, 0, 0], "axis": [0, 0, 1]},
    {"name": "jb", "type": "revolute", "body1": "c", "body2": "b", "at": [-0.5, 0, 0], "axis": [0, 0, 1]},
    {"name": "belt", "type": "coupler", "joint1": "jb", "joint2": "ja", "ratio": 3}
  ],
  "motions": [{"joint": "jc", "speed": {"t": [0, 1], "value": [0, 2]}}],
  "forces": [{"type": "point_torque", "body": "a", "table": {"t": [0, 1], "value": [[0, 0, 1.3], [0, 0, 1.3]]}},
             {"type": "tire", "body": "wheel", "axis": [0, 0, 1], "radius": 0.3, "vertical_stiffness": 2e5, "vertical_damping": 2000,
              "longitudinal_stiffness": 1e5, "cornering_stiffness": 5e4, "friction": 0.9, "road": "bumpy"},
             {"type": "spring_damper", "body1": "b", "at1": [-0.5, 0, 0], "body2": "wheel", "at2": [3, 0.2993, 0], "k": 10, "c": 1}],
  "solver": {"end": 0.2, "step": 1e-3, "eliminate_driven_bodies": false}
})";

// A belt between two shafts each turning in its own housing (a coupler whose row touches four
// bodies), the housings fixed to a turning carrier.
const char* kHoused = R"({
  "gravity": [0, -9.81, 0],
  "bodies": [
    {"name": "c", "type": "rigid", "mass": 5, "com": [0, 0, 0], "inertia": [[1.2, 0, 0], [0, 1.2, 0], [0, 0, 2]]},
    {"name": "ha", "type": "rigid", "mass": 0.2, "com": [0.5, 0, 0], "inertia": [[1e-3, 0, 0], [0, 1e-3, 0], [0, 0, 1e-3]]},
    {"name": "hb", "type": "rigid", "mass": 0.2, "com": [-0.5, 0, 0], "inertia": [[1e-3, 0, 0], [0, 1e-3, 0], [0, 0, 1e-3]]},
    {"name": "a", "type": "rigid", "mass": 1, "com": [0.5, 0, 0], "inertia": [[0.15, 0, 0], [0, 0.15, 0], [0, 0, 0.2]]},
    {"name": "b", "type": "rigid", "mass": 2, "com": [-0.5, 0, 0], "inertia": [[0.03, 0, 0], [0, 0.03, 0], [0, 0, 0.05]]}
  ],
  "joints": [
    {"name": "jc", "type": "revolute", "body1": "ground", "body2": "c", "at": [0, 0, 0], "axis": [0, 0, 1]},
    {"name": "fa", "type": "fixed", "body1": "c", "body2": "ha", "at": [0.5, 0, 0]},
    {"name": "fb", "type": "fixed", "body1": "c", "body2": "hb", "at": [-0.5, 0, 0]},
    {"name": "ja", "type": "revolute", "body1": "ha", "body2": "a", "at": [0.5, 0, 0], "axis": [0, 0, 1]},
    {"name": "jb", "type": "revolute", "body1": "hb", "body2": "b", "at": [-0.5, 0, 0], "axis": [0, 0, 1]},
    {"name": "belt", "type": "coupler", "joint1": "jb", "joint2": "ja", "ratio": 3}
  ],
  "motions": [{"joint": "jc", "speed": {"t": [0, 1], "value": [0, 2]}}],
  "forces": [{"type": "point_torque", "body": "a", "table": {"t": [0, 1], "value": [[0, 0, 1.3], [0, 0, 1.3]]}}],
  "solver": {"end": 0.2, "step": 1e-3, "eliminate_driven_bodies": false}
})";

const char* kGeBeam = R"({
  "gravity": [0, 0, -9.81],
  "bodies": [
    {"name": "beam", "type": "beam", "formulation": "geometrically_exact", "start": [0, 0, 0], "end": [1, 0, 0], "elements": 6,
     "E": 2.1e9, "nu": 0.3, "rho": 7850, "section": {"A": 1e-4, "Iy": 8.3e-10, "Iz": 8.3e-10, "J": 1.4e-9},
     "damping": {"strain_rate": 1e-4}},
    {"name": "bob", "type": "rigid", "mass": 0.2, "com": [1.05, 0, 0], "inertia": [[1e-4, 0, 0], [0, 1e-4, 0], [0, 0, 1e-4]]},
    {"name": "arm", "type": "beam", "formulation": "ancf", "start": [1.05, 0, 0], "end": [1.05, 0, -0.5], "elements": 3,
     "E": 2.1e9, "rho": 7850, "section": {"A": 1e-4, "Iy": 8.3e-10, "Iz": 8.3e-10}}
  ],
  "joints": [
    {"name": "pin", "type": "revolute", "body1": "ground", "body2": "beam", "node2": "start", "axis": [0, 1, 0]},
    {"name": "weld", "type": "fixed", "body1": "beam", "node1": "end", "body2": "bob"},
    {"name": "hang", "type": "spherical", "body1": "bob", "body2": "arm", "node2": "start"}
  ],
  "forces": [{"type": "point_torque", "body": "beam", "node": "n3", "table": {"t": [0, 1], "value": [[0.01, 0, 0], [0.01, 0, 0]]}},
             {"type": "spring_damper", "body1": "beam", "node1": "n2", "body2": "arm", "node2": "end", "k": 10, "c": 0.1}],
  "solver": {"end": 0.2, "step": 1e-3}
})";

// A hub with branches, the hub first in the model (a vehicle's frame): two axles on bushings,
// each carrying two wheels on revolute joints, a cab and an engine on bushings.
const char* kHub = R"({
  "gravity": [0, 0, -9.81],
  "bodies": [
    {"name": "frame", "type": "rigid", "mass": 300, "com": [0, 0, 0.8], "inertia": [[60, 0, 0], [0, 400, 0], [0, 0, 420]]},
    {"name": "front", "type": "rigid", "mass": 80, "com": [1.3, 0, 0.4], "inertia": [[20, 0, 0], [0, 2, 0], [0, 0, 20]]},
    {"name": "rear", "type": "rigid", "mass": 90, "com": [-1.3, 0, 0.4], "inertia": [[22, 0, 0], [0, 2, 0], [0, 0, 22]]},
    {"name": "fl", "type": "rigid", "mass": 30, "com": [1.3, 0.7, 0.4], "inertia": [[1.2, 0, 0], [0, 2, 0], [0, 0, 1.2]]},
    {"name": "fr", "type": "rigid", "mass": 30, "com": [1.3, -0.7, 0.4], "inertia": [[1.2, 0, 0], [0, 2, 0], [0, 0, 1.2]]},
    {"name": "rl", "type": "rigid", "mass": 30, "com": [-1.3, 0.7, 0.4], "inertia": [[1.2, 0, 0], [0, 2, 0], [0, 0, 1.2]]},
    {"name": "rr", "type": "rigid", "mass": 30, "com": [-1.3, -0.7, 0.4], "inertia": [[1.2, 0, 0], [0, 2, 0], [0, 0, 1.2]]},
    {"name": "cab", "type": "rigid", "mass": 400, "com": [0.3, 0, 1.5], "inertia": [[240, 0, 0], [0, 810, 0], [0, 0, 860]]},
    {"name": "engine", "type": "rigid", "mass": 200, "com": [1.0, 0, 1.0], "inertia": [[15, 0, 0], [0, 25, 0], [0, 0, 25]]}
  ],
  "joints": [
    {"name": "wfl", "type": "revolute", "body1": "front", "body2": "fl", "at": [1.3, 0.7, 0.4], "axis": [0, 1, 0]},
    {"name": "wfr", "type": "revolute", "body1": "front", "body2": "fr", "at": [1.3, -0.7, 0.4], "axis": [0, 1, 0]},
    {"name": "wrl", "type": "revolute", "body1": "rear", "body2": "rl", "at": [-1.3, 0.7, 0.4], "axis": [0, 1, 0]},
    {"name": "wrr", "type": "revolute", "body1": "rear", "body2": "rr", "at": [-1.3, -0.7, 0.4], "axis": [0, 1, 0]}
  ],
  "forces": [
    {"type": "bushing", "body1": "frame", "body2": "front", "at": [1.3, 0, 0.6], "stiffness": [2e5, 2e5, 1e5, 1e4, 1e4, 1e4], "damping": [2e3, 2e3, 1e3, 10, 10, 10]},
    {"type": "bushing", "body1": "frame", "body2": "rear", "at": [-1.3, 0, 0.6], "stiffness": [2e5, 2e5, 1e5, 1e4, 1e4, 1e4], "damping": [2e3, 2e3, 1e3, 10, 10, 10]},
    {"type": "bushing", "body1": "frame", "body2": "cab", "at": [0.3, 0, 1.1], "stiffness": [1.5e5, 1.5e5, 3e5, 2e4, 2e4, 2e4], "damping": [1.5e3, 1.5e3, 3e3, 20, 20, 20]},
    {"type": "bushing", "body1": "frame", "body2": "engine", "at": [1.0, 0, 0.9], "stiffness": [2e5, 2e5, 3e5, 2e4, 2e4, 2e4], "damping": [1e3, 1e3, 1.5e3, 10, 10, 10]},
    {"type": "bushing", "body1": "ground", "body2": "frame", "at": [0, 0, 0.8], "stiffness": [1e5, 1e5, 1e5, 1e5, 1e5, 1e5], "damping": [1e3, 1e3, 1e3, 1e2, 1e2, 1e2]},
    {"type": "point_torque", "body": "fl", "table": {"t": [0, 1], "value": [[0, 5, 0], [0, 5, 0]]}}
  ],
  "solver": {"end": 0.2, "step": 1e-3}
})";

// A row of links on revolute joints: banded in the model's order already.
const char* kRow = R"({
  "gravity": [0, -9.81, 0],
  "bodies": [
    {"name": "l1", "type": "rigid", "mass": 1, "com": [0.5, 0, 0], "inertia": [[0.01, 0, 0], [0, 0.1, 0], [0, 0, 0.1]]},
    {"name": "l2", "type": "rigid", "mass": 1, "com": [1.5, 0, 0], "inertia": [[0.01, 0, 0], [0, 0.1, 0], [0, 0, 0.1]]},
    {"name": "l3", "type": "rigid", "mass": 1, "com": [2.5, 0, 0], "inertia": [[0.01, 0, 0], [0, 0.1, 0], [0, 0, 0.1]]},
    {"name": "l4", "type": "rigid", "mass": 1, "com": [3.5, 0, 0], "inertia": [[0.01, 0, 0], [0, 0.1, 0], [0, 0, 0.1]]},
    {"name": "l5", "type": "rigid", "mass": 1, "com": [4.5, 0, 0], "inertia": [[0.01, 0, 0], [0, 0.1, 0], [0, 0, 0.1]]},
    {"name": "l6", "type": "rigid", "mass": 1, "com": [5.5, 0, 0], "inertia": [[0.01, 0, 0], [0, 0.1, 0], [0, 0, 0.1]]}
  ],
  "joints": [
    {"name": "j1", "type": "revolute", "body1": "ground", "body2": "l1", "at": [0, 0, 0], "axis": [0, 0, 1]},
    {"name": "j2", "type": "revolute", "body1": "l1", "body2": "l2", "at": [1, 0, 0], "axis": [0, 0, 1]},
    {"name": "j3", "type": "revolute", "body1": "l2", "body2": "l3", "at": [2, 0, 0], "axis": [0, 0, 1]},
    {"name": "j4", "type": "revolute", "body1": "l3", "body2": "l4", "at": [3, 0, 0], "axis": [0, 0, 1]},
    {"name": "j5", "type": "revolute", "body1": "l4", "body2": "l5", "at": [4, 0, 0], "axis": [0, 0, 1]},
    {"name": "j6", "type": "revolute", "body1": "l5", "body2": "l6", "at": [5, 0, 0], "axis": [0, 0, 1]}
  ],
  "solver": {"end": 0.2, "step": 1e-3}
})";

// Per coordinate pair: inside a tangent block (of the bodies integrated now, or of all bodies).
std::vector<std::vector<char>> tangent_mask(const Model& model, const Data& data, bool integrated_only) {
  std::vector<std::vector<char>> in(static_cast<std::size_t>(model.ncoord), std::vector<char>(static_cast<std::size_t>(model.ncoord), 0));
  detail::for_each_tangent_block(model, data, integrated_only, [&](int r0, int nr, int c0, int nc) {
    for (int i = r0; i < r0 + nr; ++i)
      for (int j = c0; j < c0 + nc; ++j) in[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = 1;
  });
  return in;
}

// Entries outside the mask over the leading n x n that were written: neither the sentinel nor
// zero (a model whose blocks cover most of the matrix clears it whole: tangent_blocks_pay).
int changed_outside(const MatrixXd& X, const std::vector<std::vector<char>>& in, int n) {
  int changed = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (!in[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] && X(i, j) != kSentinel && X(i, j) != 0.0) ++changed;
  return changed;
}

void fill_outside(MatrixXd& X, const std::vector<std::vector<char>>& in) {
  for (Eigen::Index i = 0; i < X.rows(); ++i)
    for (Eigen::Index j = 0; j < X.cols(); ++j)
      if (!in[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)]) X(i, j) = kSentinel;
}

void check_model(const char* name, const Model& model) {
  SCOPED_TRACE(name);
  Data data(model);
  initialize(model, data);
  for (int s = 0; s < 20; ++s) step(model, data);  // moving, the friction sliding, the tyre in contact
  const int nf = data.nf, na = data.na;
  const auto all = tangent_mask(model, data, false);
  const auto unknowns = tangent_mask(model, data, true);
  fill_outside(data.K, all);
  fill_outside(data.C, all);
  fill_outside(data.W, unknowns);
  // T keeps its zeros outside the blocks: the factorisation reads it there (a debug build
  // asserts they are zero where the blocks pay), so a write shows as a nonzero entry.
  // The Jacobian: outside the blocks' rows x their bodies' columns.
  std::vector<std::vector<char>> jin(static_cast<std::size_t>(model.nconstraints), std::vector<char>(static_cast<std::size_t>(model.ncoord), 0));
  for (int bi = 0; bi < data.nblocks; ++bi) {
    const ConstraintBlock& b = model.blocks[static_cast<std::size_t>(bi)];
    for (int body : {b.body1, b.body2, b.body3, b.body4}) {
      if (!integrated(data, body)) continue;
      const Body& B = model.bodies[static_cast<std::size_t>(body)];
      for (int i = b.row0; i < b.row0 + b.rows; ++i)
        for (int j = B.offset; j < B.offset + B.ncoord(); ++j) jin[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] = 1;
    }
  }
  for (int i = 0; i < na; ++i)
    for (int j = 0; j < nf; ++j)
      if (!jin[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)]) data.Phiq(i, j) = kSentinel;
  const double t = data.state.t;
  evaluate(model, data, t, Scope::All);
  refresh_tangent(model, data, t, data.state.lambda, true);
  EXPECT_EQ(changed_outside(data.K, all, model.ncoord), 0) << "K written outside the tangent blocks";
  EXPECT_EQ(changed_outside(data.C, all, model.ncoord), 0) << "C written outside the tangent blocks";
  EXPECT_EQ(changed_outside(data.W, unknowns, nf), 0) << "W written outside the tangent blocks";
  EXPECT_EQ(changed_outside(data.T, unknowns, nf), 0) << "T written outside the tangent blocks";
  int jchanged = 0;
  for (int i = 0; i < na; ++i)
    for (int j = 0; j < nf; ++j)
      if (!jin[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] && data.Phiq(i, j) != kSentinel && data.Phiq(i, j) != 0.0) ++jchanged;
  EXPECT_EQ(jchanged, 0) << "Phi_q written outside its blocks' columns";
  // The sentinel outside the Jacobian's blocks made zero again for the products below.
  for (int i = 0; i < na; ++i)
    for (int j = 0; j < nf; ++j)
      if (!jin[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)]) data.Phiq(i, j) = 0;
  // The block products against Eigen's dense ones (a vector with every entry nonzero).
  const MatrixXd J = data.Phiq.topLeftCorner(na, nf);
  VectorXd v = VectorXd::LinSpaced(model.ncoord, 0.3, 1.7);
  VectorXd lam = VectorXd::LinSpaced(model.nconstraints, -1.1, 0.9);
  VectorXd out = VectorXd::Constant(model.nconstraints, kSentinel);
  constraint_times(model, data, v, out);
  const VectorXd dense = J * v.head(nf);
  const double scale_v = J.cwiseAbs().maxCoeff() * v.cwiseAbs().sum();
  EXPECT_LE((out.head(na) - dense).cwiseAbs().maxCoeff(), 1e-14 * scale_v);
  if (na < model.nconstraints) {
    EXPECT_EQ(out.tail(model.nconstraints - na).cwiseAbs().maxCoeff(), 0.0);
  }
  VectorXd f = VectorXd::LinSpaced(model.ncoord, -2, 2);
  const VectorXd f0 = f;
  add_constraint_forces(model, data, lam, f);
  const VectorXd dense_f = J.transpose() * lam.head(na);
  EXPECT_LE((f.head(nf) - f0.head(nf) - dense_f).cwiseAbs().maxCoeff(), 1e-14 * J.cwiseAbs().maxCoeff() * lam.cwiseAbs().sum());
  if (nf < model.ncoord) {
    EXPECT_EQ((f.tail(model.ncoord - nf) - f0.tail(model.ncoord - nf)).cwiseAbs().maxCoeff(), 0.0);
  }
}

}  // namespace

TEST(TangentBlocks, EveryTermInsideTheBlocksAndBlockProductsAsDense) {
  test::TempDir dir("tangent_blocks");
  test::write_mixed_sids(dir);
  check_model("mixed", test::model_from(kMixed, dir.path));
  check_model("carrier, tyre", test::model_from(kCarrier, dir.path));
  check_model("housed shafts, coupler of four bodies", test::model_from(kHoused, dir.path));
  check_model("beams", test::model_from(kGeBeam, dir.path));
}

// The envelope an LU without pivoting fills, in an order (pos: coordinate -> position, -1 for a
// known coordinate), from the tangent blocks' pattern: per column, its position less the first
// position of a row that the blocks reach (the pattern is symmetric).
long envelope(const std::vector<std::vector<char>>& pattern, const std::vector<int>& pos) {
  long sum = 0;
  for (std::size_t j = 0; j < pos.size(); ++j) {
    if (pos[j] < 0) continue;
    int first = pos[j];
    for (std::size_t i = 0; i < pos.size(); ++i)
      if (pos[i] >= 0 && pattern[i][j]) first = std::min(first, pos[i]);
    sum += pos[j] - first;
  }
  return sum;
}

// The factorisation's order (tangent_blocks.hpp, factorisation_order): a hub first in the model
// is taken among the last two bodies (minimum degree: at the end the hub and its last branch
// are left, coupled only to each other), the envelope the LU fills shrinks against the model's
// order (counted here from the blocks' pattern), and the solve in that order agrees with the
// tangent itself (T x = b to round-off, T unscaled and in the model's order: the oracle); a row
// of links keeps the model's order.
TEST(TangentBlocks, HubFactorisedLastAndSolvedAsTheTangent) {
  test::TempDir dir("tangent_blocks_order");
  {
    const Model model = test::model_from(kHub, dir.path);
    Data data(model);
    initialize(model, data);
    for (int s = 0; s < 10; ++s) step(model, data);
    ASSERT_TRUE(data.tangent_blocks_pay);
    const Body& frame = model.bodies[0];
    int frame_first = data.nf;
    for (int c = frame.offset; c < frame.offset + frame.ncoord(); ++c) frame_first = std::min(frame_first, data.lu_pos[static_cast<std::size_t>(c)]);
    int after_frame = 0;
    for (std::size_t b = 1; b < model.bodies.size(); ++b) {
      const Body& B = model.bodies[b];
      bool after = false;
      for (int c = B.offset; c < B.offset + B.ncoord(); ++c) after = after || data.lu_pos[static_cast<std::size_t>(c)] > frame_first;
      if (after) ++after_frame;
    }
    EXPECT_LE(after_frame, 1) << "bodies factorised after the hub";
    std::vector<int> natural(data.lu_pos.size(), -1);
    int next = 0;
    for (std::size_t c = 0; c < natural.size(); ++c)
      if (data.lu_pos[c] >= 0) natural[c] = next++;
    const auto pattern = tangent_mask(model, data, true);
    const long chosen = envelope(pattern, data.lu_pos), model_order = envelope(pattern, natural);
    EXPECT_LT(chosen, model_order / 2) << "envelope " << chosen << " against " << model_order << " in the model's order";
    const double t = data.state.t;
    evaluate(model, data, t, Scope::All);
    refresh_tangent(model, data, t, data.state.lambda, true);
    const int nf = data.nf;
    VectorXd rhs = VectorXd::Zero(model.ncoord), x = VectorXd::Zero(model.ncoord);
    rhs.head(nf) = VectorXd::LinSpaced(nf, -1.0, 2.0);
    solve_tangent(data, rhs, x);
    // Every coordinate is an unknown here (no driven bodies, no known frame vectors).
    ASSERT_TRUE(data.unknowns.empty() || static_cast<int>(data.unknowns.size()) == nf);
    const MatrixXd T = data.T.topLeftCorner(nf, nf);
    const double residual = (T * x.head(nf) - rhs.head(nf)).cwiseAbs().maxCoeff();
    EXPECT_LE(residual, 1e-12 * T.cwiseAbs().maxCoeff() * x.head(nf).cwiseAbs().maxCoeff());
    EXPECT_GT(x.head(nf).cwiseAbs().maxCoeff(), 0.0);
  }
  {
    const Model model = test::model_from(kRow, dir.path);
    Data data(model);
    initialize(model, data);
    step(model, data);
    ASSERT_TRUE(data.tangent_blocks_pay);
    for (int c = 0; c < data.nf; ++c) {
      if (data.lu_pos[static_cast<std::size_t>(c)] < 0) continue;
      EXPECT_EQ(data.lu_pos[static_cast<std::size_t>(c)], data.unknowns.empty() ? c : static_cast<int>(std::lower_bound(data.unknowns.begin(), data.unknowns.end(), c) - data.unknowns.begin()));
    }
  }
}

// NewtonPolicy::bushing_tangent_steps: a step's first tangent taking the bushings' part of one
// built up to three steps before converges as fast (the same Newton iterations within 2 %) and
// moves the result far less than the step's truncation error (the same run at h/2 is the
// yardstick: the difference must stay below 1 % of it); with 1 every tangent builds its own.
TEST(TangentBlocks, BushingTangentKeptOverStepsKeepsTheIntegratorsAccuracy) {
  test::TempDir dir("tangent_blocks_bushing");
  const auto run = [&](int keep, double h, std::int64_t& iterations, int& oldest) {
    Model model = test::model_from(kHub, dir.path);
    model.settings.policy.newton.bushing_tangent_steps = keep;
    Data data(model);
    initialize(model, data);
    oldest = 0;
    for (int s = 0; s < static_cast<int>(0.2 / h + 0.5); ++s) {
      step(model, data, h);
      oldest = std::max(oldest, data.bushing_tangent_age);
    }
    iterations = data.stats.newton_iterations;
    return VectorXd(data.state.q);
  };
  std::int64_t it1 = 0, it4 = 0, it_half = 0;
  int age1 = 0, age4 = 0, age_half = 0;
  const VectorXd q1 = run(1, 1e-3, it1, age1);
  const VectorXd q4 = run(4, 1e-3, it4, age4);
  const VectorXd q_half = run(1, 5e-4, it_half, age_half);
  EXPECT_EQ(age1, 0);
  EXPECT_EQ(age4, 3);
  EXPECT_LE(it4, it1 + it1 / 50);
  const double truncation = (q1 - q_half).cwiseAbs().maxCoeff();
  ASSERT_GT(truncation, 0.0);
  EXPECT_LE((q4 - q1).cwiseAbs().maxCoeff(), 0.01 * truncation) << "truncation error " << truncation;
}

// A restored state (step control's retry, the C API's ffr_restore_state) takes no bushing
// tangent kept at another state: its next step builds one.
TEST(TangentBlocks, RestoredStateBuildsItsOwnBushingTangent) {
  test::TempDir dir("tangent_blocks_bushing_restore");
  const Model model = test::model_from(kHub, dir.path);
  ASSERT_GE(model.settings.policy.newton.bushing_tangent_steps, 2);
  Data data(model);
  initialize(model, data);
  EXPECT_EQ(data.bushing_tangent_age, -1) << "kept from the initial settling";
  State saved(model);
  save_state(data, saved);
  for (int s = 0; s < 6; ++s) step(model, data);
  ASSERT_GE(data.bushing_tangent_age, 0);
  restore_state(saved, data);
  EXPECT_EQ(data.bushing_tangent_age, -1);
  step(model, data);
  EXPECT_EQ(data.bushing_tangent_age, 0);
}
