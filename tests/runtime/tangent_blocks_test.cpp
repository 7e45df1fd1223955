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
#include "integrator/tangent_blocks.hpp"

#include <gtest/gtest.h>

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
