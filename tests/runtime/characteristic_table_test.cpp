// Nonlinear and preloaded force elements: a spring-damper's force and damping tables and
// preload, a bushing's per-axis tables and preload. Each settles (damped) to its static
// equilibrium, which is known in closed form: the deflection where the characteristic carries
// the weight (the root of the piecewise-linear table, worked out by hand below), or where the
// preload balances the stiffness (delta = (m g - P)/k; a bushing's small-rotation measure,
// sin(theta) for a rotation about one axis, at -P/k).
#include "support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

using namespace ffr::runtime;

namespace {

using test::error_of;
using test::expect_error;

// A 1 kg mass at the origin on a vertical prismatic joint, g = 9.81, hanging from the ground at
// z = 1 by `spring` (JSON keys after the ends).
std::string hanging(const std::string& spring, double end = 4) {
  return R"({"gravity": [0, 0, -9.81],
   "bodies": [{"name": "mass", "type": "rigid", "mass": 1, "com": [0, 0, 0], "inertia": [[0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]]}],
   "joints": [{"name": "slide", "type": "prismatic", "body1": "ground", "body2": "mass", "at": [0, 0, 0], "axis": [0, 0, 1]}],
   "forces": [{"name": "s", "type": "spring_damper", "body1": "ground", "at1": [0, 0, 1], "body2": "mass", )" +
         spring + R"(}],
   "solver": {"end": )" + std::to_string(end) + R"(, "step": 1e-3}})";
}

// A 1 kg rigid body on a bushing to the ground at its centre (the bushing's axes global), g along
// -z.
std::string on_bushing(const std::string& bushing, double end = 4) {
  return R"({"gravity": [0, 0, -9.81],
   "bodies": [{"name": "mass", "type": "rigid", "mass": 1, "com": [0, 0, 0], "inertia": [[0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]]}],
   "forces": [{"name": "b", "type": "bushing", "body1": "ground", "body2": "mass", "at": [0, 0, 0], )" +
         bushing + R"(}],
   "solver": {"end": )" + std::to_string(end) + R"(, "step": 1e-3}})";
}

Data settle(const Model& model) {
  Data data(model);
  initialize(model, data);
  for (std::int64_t i = 0; i < step_count(model); ++i) step(model, data);
  return data;
}

}  // namespace

// Progressive spring table: 0 N at 0, 5 N at 10 mm, 20 N at 20 mm, 200 N at 50 mm (linear
// between). The weight 9.81 N is carried on the segment [10, 20] mm (slope 1500 N/m):
// delta = 0.01 + (9.81 - 5) / 1500 = 0.013206667 m. The damper is a table too (20 N s/m).
TEST(CharacteristicTables, SpringForceTableStaticDeflection) {
  const Model model = test::model_from(hanging(
      R"("force_table": {"x": [-1, 0, 0.01, 0.02, 0.05], "value": [-1000, 0, 5, 20, 200]}, "damping_table": {"x": [-1, 1], "value": [-20, 20]})"));
  const Data data = settle(model);
  const double delta = 0.01 + (9.81 - 5) / 1500;
  EXPECT_NEAR(-data.state.q(2), delta, 1e-7);
  EXPECT_NEAR(data.state.qd(2), 0, 1e-5);
  std::printf("force table: deflection %.9f m (analytic %.9f)\n", -data.state.q(2), delta);
}

// Preload: tension k delta + P with k = 1000 N/m, P = 4 N carries 9.81 N at delta = 5.81 mm.
TEST(CharacteristicTables, SpringPreloadStaticDeflection) {
  const Model model = test::model_from(hanging(R"("k": 1000, "c": 30, "preload": 4)"));
  const Data data = settle(model);
  const double delta = (9.81 - 4) / 1000;
  EXPECT_NEAR(-data.state.q(2), delta, 1e-8);
  std::printf("spring preload: deflection %.9f m (analytic %.9f)\n", -data.state.q(2), delta);
}

// Bushing: the z axis from a table (a bump stop: 2000 N/m to 4 mm, then 20000 N/m), the preload
// force +2 N along z (the force on body 1, the ground; the mass is pushed by -2 N) and torque
// 5 N m about z with k_rz = 100 N m: F_z(s_z) + P_z = -m g on the table's second segment,
// s_z = -0.004 - (9.81 + 2 - 8) / 20000 = -0.0041905 m; the torque balance sin(theta_z) = -P/k = -0.05.
TEST(CharacteristicTables, BushingTablesAndPreload) {
  const Model model = test::model_from(on_bushing(
      R"("stiffness": [1e4, 1e4, 0, 100, 100, 100], "damping": [50, 50, 50, 2, 2, 2],
         "tables": {"z": {"x": [-1, -0.004, 0, 1], "value": [-19928, -8, 0, 2000]}},
         "preload": {"force": [0, 0, 2], "torque": [0, 0, 5]})",
      6));
  const Data data = settle(model);
  const double sz = -0.004 - (9.81 + 2 - 8) / 20000;
  EXPECT_NEAR(data.state.q(2), sz, 1e-8);
  // The body's x axis u = q(3..5) turned about z: sin(theta) = u_y.
  EXPECT_NEAR(data.state.q(4), -0.05, 1e-8);
  EXPECT_NEAR(data.state.q(0), 0, 1e-10);
  std::printf("bushing: s_z %.9f m (analytic %.9f), sin(theta_z) %.9f (-0.05)\n", data.state.q(2), sz, data.state.q(4));
}

TEST(CharacteristicTables, BadInputRefused) {
  expect_error(hanging(R"("force_table": {"x": [0, 0.02, 0.01], "value": [0, 1, 2]})"), "forces[0].force_table.x",
               "strictly increasing (entry 2)");
  expect_error(hanging(R"("force_table": {"x": [0, 0.01], "value": [0, 1, 2]})"), "forces[0].force_table.value",
               "has 3 entries but x has 2");
  expect_error(hanging(R"("k": 10, "force_table": {"x": [0, 0.01], "value": [0, 1]})"), "forces[0].k", "either k or force_table");
  expect_error(hanging(R"("k": 10, "c": 1, "damping_table": {"x": [0, 0.01], "value": [0, 1]})"), "forces[0].c",
               "either c or damping_table");
  expect_error(hanging(R"("force_table": {"x": [0], "value": [0]})"), "forces[0].force_table.x", "at least two points");
  expect_error(on_bushing(R"("stiffness": [1, 1, 1, 1, 1, 1], "tables": {"z": {"x": [0, 1], "value": [0, 1]}})"),
               "forces[0].stiffness", "tables.z");
  expect_error(on_bushing(R"("stiffness": [1, 1, 1, 1, 1, 1], "tables": {"w": {"x": [0, 1], "value": [0, 1]}})"),
               "forces[0].tables.w", "unknown field");
  expect_error(on_bushing(R"("stiffness": [1, 1, 1, 1, 1, 1], "preload": {"force": [0, 0]})"), "forces[0].preload.force", "");
}
