// After set-up, a step of the relative formulation (FORMULATION.md 18) allocates nothing, as the
// absolute one (allocation_test.cpp; both count with counting_new.cpp): the
// four-bar (a cut joint: Newton's multiplier passes and both projections), the flexible
// slider-crank (its rod placed at a point, a motion), a pendulum chain, a spherical double
// pendulum, a body hung on a beam's node by a spherical joint, and the four-bar under
// generalized-alpha, each step recorded.
#include "simeon_rod.hpp"
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include "formulation_models.hpp"  // tools/bench/formulations
#include "simeon_crank.hpp"
#include "relative_assembly_models.hpp"

#include "ffr/runtime/relative.hpp"

#include "counting_new.hpp"

#include <gtest/gtest.h>

#include <cstdio>

using namespace ffr::runtime;

namespace {

long allocations_in_steps(const Model& model, Data& data, int n) {
  Recorder rec(model, n + 2);
  step(model, data);  // the first step takes the coordinates from the initialized state
  rec.record(model, data);
  const long before = counted_allocations();
  for (int i = 0; i < n; ++i) {
    step(model, data);
    rec.record(model, data);
  }
  return counted_allocations() - before;
}

TEST(RelativeAllocation, StepsAllocateNothing) {
  {
    const Model model = test::model_from(formulations::four_bar::json(1e-3, 1.0, "relative"));
    ASSERT_GT(model.relative->kept_rows, 0);
    Data data(model);
    initialize(model, data);
    EXPECT_EQ(allocations_in_steps(model, data, 200), 0) << "four-bar";
  }
  {
    const Model model = test::model_from(formulations::pendulum_chain_json(20, 1e-3, 1.0, "relative"));
    Data data(model);
    initialize(model, data);
    EXPECT_EQ(allocations_in_steps(model, data, 100), 0) << "chain";
  }
  {
    test::TempDir dir("relative_alloc");
    test::write_sid_file(test::simeon_rod_sid(), dir / "rod.sid.h5");
    const Model model = test::model_from(formulations::with_formulation(test::simeon_crank_json(1e-4, 0.05), "relative"), dir.path);
    Data data(model);
    initialize(model, data);
    EXPECT_EQ(allocations_in_steps(model, data, 100), 0) << "slider-crank";
  }
  // Bodies placed at a joint's point: on a rigid body and the ground, and on an ANCF beam's node.
  {
    const Model model = test::model_from(relative_assembly::spherical_double_pendulum_json(1e-3, 1.0, "relative"));
    ASSERT_TRUE(model.relative->bodies[1].point);
    Data data(model);
    initialize(model, data);
    EXPECT_EQ(allocations_in_steps(model, data, 100), 0) << "spherical double pendulum";
  }
  {
    const Model model = test::model_from(relative_assembly::hung_bob_json("ancf", R"({"formulation": "relative", "end": 1.0, "step": 1e-3})"));
    ASSERT_TRUE(model.relative->bodies[1].point);
    Data data(model);
    initialize(model, data);
    EXPECT_EQ(allocations_in_steps(model, data, 50), 0) << "bob on a beam node";
  }
  // Generalized-alpha (its start step is inside the first, uncounted step).
  {
    std::string json = formulations::four_bar::json(1e-3, 1.0, "relative");
    json.insert(json.find("\"solver\": {") + 11, R"("integrator": "generalized_alpha", "spectral_radius": 0.8, )");
    const Model model = test::model_from(json);
    ASSERT_EQ(model.settings.integrator, Integrator::GeneralizedAlpha);
    Data data(model);
    initialize(model, data);
    EXPECT_EQ(allocations_in_steps(model, data, 100), 0) << "four-bar, generalized-alpha";
  }
}

}  // namespace
