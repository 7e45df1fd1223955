// After set-up, a time step allocates nothing: global operator new/delete are replaced to count,
// and many steps (with every kind of element, the tangent refreshed and reused, the projections,
// and the recording of outputs) must leave the count unchanged.
#include "mixed_model.hpp"
#include "simeon_rod.hpp"
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include "ffr/runtime/step_control.hpp"

#include "counting_new.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <vector>


// malloc itself, counted apart: Eigen's dynamic matrices allocate through it, not through
// operator new (glibc's own entry points, __libc_*, do the work). Not under AddressSanitizer,
// which interposes malloc itself.
#if defined(__SANITIZE_ADDRESS__)
#define FFR_COUNT_MALLOC 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define FFR_COUNT_MALLOC 0
#endif
#endif
#ifndef FFR_COUNT_MALLOC
#define FFR_COUNT_MALLOC 1
#endif
namespace {
std::atomic<long> g_mallocs{0};
}
#if FFR_COUNT_MALLOC
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* malloc(std::size_t n) {
  ++g_mallocs;
  return __libc_malloc(n);
}
void* calloc(std::size_t a, std::size_t b) {
  ++g_mallocs;
  return __libc_calloc(a, b);
}
void* realloc(void* p, std::size_t n) {
  ++g_mallocs;
  return __libc_realloc(p, n);
}
}
#endif

using namespace ffr::runtime;

namespace {

// Every kind of element: a driven crank, a flexible rod, a slider, a flexible flap on a bushing,
// springs (one between two nodes of the flap, its interface A one of them), point forces and
// torques.
const std::string kMixedModel = test::mixed_model_json(R"([
    {"type": "spring_damper", "body1": "ground", "at1": [0.3, 0.3, 0], "body2": "rod", "node2": "M", "k": 100, "c": 1},
    {"type": "bushing", "body1": "flap", "node1": "B", "body2": "ground", "stiffness": [1e3, 1e3, 1e3, 10, 10, 10], "damping": [1, 1, 1, 0.1, 0.1, 0.1]},
    {"type": "point_force", "body": "rod", "node": "M", "table": {"t": [0, 1], "value": [[0, 1, 0], [0, -1, 0]]}},
    {"type": "point_torque", "body": "flap", "node": "C", "table": {"t": [0, 1], "value": [[0, 0, 0.1], [0, 0, 0.2]]}},
    {"type": "spring_damper", "body1": "flap", "node1": "A", "body2": "flap", "node2": "C", "k": 50, "c": 0.5, "preload": 1}
  ])", R"("solver": {"end": 0.2, "step": 1e-3},
  "outputs": [
    {"name": "tip", "type": "node_deformation", "body": "rod", "node": "M"},
    {"name": "tip_xyz", "type": "node_position", "body": "rod", "node": "M"},
    {"name": "q", "type": "modal_coordinates", "body": "rod"},
    {"name": "angle", "type": "joint_coordinate", "joint": "hub"},
    {"name": "stroke", "type": "joint_coordinate", "joint": "guide"},
    {"name": "energy", "type": "energy"},
    {"name": "rate", "type": "joint_rate", "joint": "hub"},
    {"name": "pin_reaction", "type": "joint_reaction", "joint": "pin"},
    {"name": "tip_velocity", "type": "node_velocity", "body": "rod", "node": "M"},
    {"name": "spin", "type": "body_angular_velocity", "body": "flap"},
    {"name": "spring_force", "type": "element_force", "force": "forces[0]"},
    {"name": "bushing_force", "type": "element_force", "force": "forces[1]"}
  ])");

// The allocations of `steps` steps, each recorded, after one step that leaves nothing to size.
long allocations_of_recorded_steps(const Model& model, Data& data, int steps) {
  Recorder rec(model, 1000);
  step(model, data);
  const long before = counted_allocations();
  for (int i = 0; i < steps; ++i) {
    step(model, data);
    rec.record(model, data);
  }
  return counted_allocations() - before;
}

// Initialises `model` in `data`, then the allocations of `steps` recorded steps, printed with what
// the model holds.
long allocations_from_start(const Model& model, Data& data, int steps, const char* what) {
  initialize(model, data);
  const long allocations = allocations_of_recorded_steps(model, data, steps);
  std::printf("%d steps with %s: %ld allocations\n", steps, what, allocations);
  return allocations;
}

}  // namespace

TEST(Allocation, StepsAllocateNothing) {
  test::TempDir dir("alloc");
  test::write_mixed_sids(dir);
  const Model model = test::model_from(kMixedModel, dir.path);
  ASSERT_TRUE(model.bodies[1].modal_stress && model.bodies[3].modal_stress && model.bodies[3].prestress);
  ASSERT_EQ(model.bodies[3].stiffening->interfaces.size(), 1u);
  Data data(model);
  initialize(model, data);
  set_external_load(data, 3, 1, Eigen::Vector3d(0.1, 0, 0), Eigen::Vector3d::Zero());  // at the flap's node A
  Recorder rec(model, 1000);
  step(model, data);  // first step: nothing left to size
  const long before = counted_allocations();
  const std::int64_t fact0 = data.stats.factorizations;
  for (int i = 0; i < 150; ++i) {
    step(model, data);
    rec.record(model, data);
  }
  const long after = counted_allocations();
  std::printf("150 steps: %ld allocations, %lld factorisations\n", after - before,
              static_cast<long long>(data.stats.factorizations - fact0));
  EXPECT_EQ(after - before, 0);
  EXPECT_GT(data.stats.factorizations - fact0, 0);  // the tangent refresh was exercised too
}

// The generalized-alpha step and adaptive steps (scheme_coefficients.cpp, step_control.cpp:
// error estimates, rejected steps restored from the saved state, steps landing on output times).
TEST(Allocation, GeneralizedAlphaAndAdaptiveStepsAllocateNothing) {
  test::TempDir dir("alloc_schemes");
  test::write_mixed_sids(dir);
  Model model = test::model_from(kMixedModel, dir.path);
  model.settings.integrator = Integrator::GeneralizedAlpha;
  model.settings.spectral_radius = 0.6;
  {
    Data data(model);
    initialize(model, data);
    step(model, data);
    const long before = counted_allocations();
    for (int i = 0; i < 100; ++i) step(model, data);
    EXPECT_EQ(counted_allocations() - before, 0) << "generalized-alpha";
  }
  for (const Integrator scheme : {Integrator::Trapezoidal, Integrator::GeneralizedAlpha}) {
    model.settings.integrator = scheme;
    model.settings.adaptive = true;
    model.settings.rtol = 1e-5;
    model.settings.atol = 1e-6;
    model.settings.output_interval = 0.01;
    model.settings.step = 1e-2;  // too long: the first steps are rejected
    Data data(model);
    initialize(model, data);
    StepControl control(model, data);
    Recorder rec(model, 100);
    advance_to(model, data, control, 0.01);
    const long before = counted_allocations();
    for (int k = 2; k <= 15; ++k) {
      advance_to(model, data, control, 0.01 * k);
      rec.record(model, data);
    }
    const long after = counted_allocations();
    std::printf("adaptive (%s): %lld steps accepted, %lld rejected, %lld Newton failures; %ld allocations\n",
                scheme == Integrator::Trapezoidal ? "trapezoidal" : "generalized-alpha", static_cast<long long>(control.accepted),
                static_cast<long long>(control.rejected), static_cast<long long>(control.newton_failures), after - before);
    EXPECT_EQ(after - before, 0);
    EXPECT_GT(control.rejected, 0);  // the restore was exercised
  }
}

// Eigen's dynamic vectors allocate through malloc, which the operator new count above does not
// see: a work vector resized by an assignment inside the step allocates unseen, and a later
// solve into it writes past its end when it shrank (the Newton multiplier passes once left the
// coordinate-sized tmp constraint-sized, exact_multipliers' solves then overran it, and the
// projection sized it back). So malloc is counted too, over steps of both schemes.
TEST(Allocation, StepsCallNoMalloc) {
  if (!FFR_COUNT_MALLOC) GTEST_SKIP() << "malloc is not counted under AddressSanitizer";
  test::TempDir dir("alloc_malloc");
  test::write_mixed_sids(dir);
  Model model = test::model_from(kMixedModel, dir.path);
  for (const Integrator scheme : {Integrator::Trapezoidal, Integrator::GeneralizedAlpha}) {
    model.settings.integrator = scheme;
    model.settings.spectral_radius = 0.6;
    Data data(model);
    initialize(model, data);
    step(model, data);
    const std::int64_t solves0 = data.stats.solves, iterations0 = data.stats.newton_iterations;
    const long before = g_mallocs.load();
    for (int i = 0; i < 50; ++i) step(model, data);
    const long mallocs = g_mallocs.load() - before;
    const char* name = scheme == Integrator::Trapezoidal ? "trapezoidal" : "generalized-alpha";
    std::printf("%s: 50 steps, %lld Newton iterations, %lld solves, %ld mallocs\n", name,
                static_cast<long long>(data.stats.newton_iterations - iterations0),
                static_cast<long long>(data.stats.solves - solves0), mallocs);
    EXPECT_EQ(mallocs, 0) << name;
    // more solves than two a Newton iteration: the multiplier passes and the projections ran
    EXPECT_GT(data.stats.solves - solves0, 2 * (data.stats.newton_iterations - iterations0)) << name;
  }
}

// The elements of issue 33: a coupler between two shafts, friction dampers (regularised, and with
// a series spring whose slip is committed each step), a spring-damper with force and damping
// tables and a preload, a bushing with a table and a preload on a flexible body, PCHIP motion and
// linear load tables, the energy output with the dissipated energy.
TEST(Allocation, CouplersFrictionAndTablesAllocateNothing) {
  test::TempDir dir("alloc_elements");
  test::write_mixed_sids(dir);
  const Model model = test::model_from(R"({
  "gravity": [0, -9.81, 0],
  "bodies": [
    {"name": "a", "type": "rigid", "mass": 1, "com": [0, 0, 0], "inertia": [[0.15, 0, 0], [0, 0.15, 0], [0, 0, 0.2]]},
    {"name": "b", "type": "rigid", "mass": 2, "com": [1, 0, 0], "inertia": [[0.03, 0, 0], [0, 0.03, 0], [0, 0, 0.05]]},
    {"name": "mass", "type": "rigid", "mass": 1, "com": [0, -1, 0], "inertia": [[0.1, 0, 0], [0, 0.1, 0], [0, 0, 0.1]]},
    {"name": "flap", "type": "flexible", "sid": "lumpy.sid.h5", "position": [0, 0.5, 0]}
  ],
  "joints": [
    {"name": "ja", "type": "revolute", "body1": "ground", "body2": "a", "at": [0, 0, 0], "axis": [0, 0, 1]},
    {"name": "jb", "type": "revolute", "body1": "ground", "body2": "b", "at": [1, 0, 0], "axis": [0, 0, 1]},
    {"name": "belt", "type": "coupler", "joint1": "jb", "joint2": "ja", "ratio": 3},
    {"name": "slide", "type": "prismatic", "body1": "ground", "body2": "mass", "at": [0, -1, 0], "axis": [0, 1, 0]},
    {"name": "hinge", "type": "spherical", "body1": "ground", "body2": "flap", "node2": "A"}
  ],
  "motions": [{"joint": "ja", "table": {"t": [0, 0.05, 0.1, 1], "value": [0, 0.1, 0.5, 3]}}],
  "forces": [
    {"type": "spring_damper", "body1": "ground", "at1": [0, 0, 0], "body2": "mass", "force_table": {"x": [-1, 0, 0.01, 1], "value": [-100, 0, 5, 2000]},
     "damping_table": {"x": [-1, 1], "value": [-5, 5]}, "preload": 3},
    {"type": "friction_damper", "body1": "ground", "at1": [0, 1, 0], "body2": "mass", "force": 2, "series_stiffness": 300},
    {"type": "friction_damper", "body1": "ground", "at1": [0.5, -1, 0], "body2": "mass", "force": 0.5, "velocity_tolerance": 1e-2},
    {"type": "bushing", "body1": "flap", "node1": "B", "body2": "ground", "stiffness": [1e3, 1e3, 0, 10, 10, 10], "damping": [1, 1, 1, 0.1, 0.1, 0.1],
     "tables": {"z": {"x": [-1, 0, 1], "value": [-500, 0, 2000], "interpolation": "pchip"}}, "preload": {"force": [0, 0, 1], "torque": [0, 0.1, 0]}},
    {"type": "point_force", "body": "mass", "table": {"t": [0, 0.1, 1], "value": [[0, 0, 0], [0, -2, 0], [0, -2, 0]]}}
  ],
  "solver": {"end": 0.2, "step": 1e-3},
  "outputs": [{"name": "energy", "type": "energy"}]
})", dir.path);
  Data data(model);
  initialize(model, data);
  const long allocations = allocations_of_recorded_steps(model, data, 150);
  std::printf("150 steps with couplers, friction and tables: %ld allocations; dissipated %.6g J\n", allocations,
              energy(model, data).dissipated);
  EXPECT_EQ(allocations, 0);
  EXPECT_GT(energy(model, data).dissipated, 0);
}

// Tyres (tire.cpp): a rigid wheel rolling with slips over a PCHIP road, and a tyre on a node of a
// flexible body (the node terms of its tangent), their contact outputs recorded.
TEST(Allocation, TyresAllocateNothing) {
  test::TempDir dir("alloc_tyres");
  test::write_mixed_sids(dir);
  const Model model = test::model_from(R"({
  "gravity": [0, -9.81, 0],
  "roads": [{"name": "bumpy", "direction": [1, 0, 0], "s": [-5, -1, 0, 0.5, 1, 2, 5], "height": [0, 0, 0.002, -0.002, 0.003, 0, 0]},
            {"name": "low", "direction": [0, 0, 1], "s": [-5, 5], "height": [0.3, 0.3]}],
  "bodies": [
    {"name": "wheel", "type": "rigid", "mass": 15, "com": [0, 0.2993, 0], "inertia": [[0.7, 0, 0], [0, 0.7, 0], [0, 0, 1.2]],
     "velocity": [3, 0, 0], "angular_velocity": [0, 0, -9]},
    {"name": "flap", "type": "flexible", "sid": "lumpy.sid.h5", "position": [0, 0.5, 0]}
  ],
  "joints": [{"name": "hinge", "type": "spherical", "body1": "ground", "body2": "flap", "node2": "A"}],
  "forces": [
    {"name": "t1", "type": "tire", "body": "wheel", "axis": [0, 0, 1], "radius": 0.3, "vertical_stiffness": 2e5, "vertical_damping": 2000,
     "longitudinal_stiffness": 1e5, "cornering_stiffness": 5e4, "friction": 0.9, "road": "bumpy"},
    {"name": "t2", "type": "tire", "body": "flap", "node": "B", "axis": [0, 0, 1], "radius": 0.3, "vertical_stiffness": 100,
     "vertical_damping": 1, "longitudinal_stiffness": 50, "cornering_stiffness": 50, "friction": 0.5, "road": "low"}
  ],
  "solver": {"end": 0.2, "step": 1e-3},
  "outputs": [{"name": "t1", "type": "element_force", "force": "t1"}, {"name": "t2", "type": "element_force", "force": "t2"},
              {"name": "energy", "type": "energy"}]
})", dir.path);
  Data data(model);
  initialize(model, data);
  const long allocations = allocations_of_recorded_steps(model, data, 150);
  double t1[6], t2[6];
  evaluate_output(model, data, model.outputs[0], t1);
  evaluate_output(model, data, model.outputs[1], t2);
  std::printf("150 steps with tyres: %ld allocations; Fn %.4g N and %.4g N\n", allocations, t1[2], t2[2]);
  EXPECT_EQ(allocations, 0);
  EXPECT_GT(t1[2], 0);  // both in contact: their force paths ran
  EXPECT_GT(t2[2], 0);
}

// A coupler whose two joints move three bodies (a belt between two shafts in a turning,
// integrated carrier): its row's Jacobian, penalty tangent and Hessian over three bodies.
TEST(Allocation, CouplerInAMovingCarrierAllocatesNothing) {
  const Model model = test::model_from(R"({
  "bodies": [
    {"name": "c", "type": "rigid", "mass": 5, "com": [0, 0, 0], "inertia": [[1.2, 0, 0], [0, 1.2, 0], [0, 0, 2]]},
    {"name": "a", "type": "rigid", "mass": 1, "com": [0.5, 0, 0], "inertia": [[0.15, 0, 0], [0, 0.15, 0], [0, 0, 0.2]]},
    {"name": "b", "type": "rigid", "mass": 2, "com": [-0.5, 0, 0], "inertia": [[0.03, 0, 0], [0, 0.03, 0], [0, 0, 0.05]]}
  ],
  "joints": [
    {"name": "jc", "type": "revolute", "body1": "ground", "body2": "c", "at": [0, 0, 0], "axis": [0, 0, 1]},
    {"name": "ja", "type": "revolute", "body1": "c", "body2": "a", "at": [0.5, 0, 0], "axis": [0, 0, 1]},
    {"name": "jb", "type": "revolute", "body1": "c", "body2": "b", "at": [-0.5, 0, 0], "axis": [0, 0, 1]},
    {"name": "belt", "type": "coupler", "joint1": "jb", "joint2": "ja", "ratio": 3}
  ],
  "motions": [{"joint": "jc", "speed": {"t": [0, 1], "value": [0, 2]}}],
  "forces": [{"type": "point_torque", "body": "a", "table": {"t": [0, 1], "value": [[0, 0, 1.3], [0, 0, 1.3]]}}],
  "solver": {"end": 0.2, "step": 1e-3, "eliminate_driven_bodies": false},
  "outputs": [{"name": "belt_rate", "type": "joint_rate", "joint": "jb"}]
})");
  Data data(model);
  EXPECT_EQ(allocations_from_start(model, data, 150, "a coupler over three bodies"), 0);
  EXPECT_GT(joint_coordinate_rate(model, data, 2, JointCoordinate::Angle), 0.1);  // it turned
}

// A beam body (FORMULATION.md 15): clamped, a rigid body hung at its end by a spherical joint,
// strain-rate damping, a point force at a node, its node outputs and energy recorded.
TEST(Allocation, BeamBodiesAllocateNothing) {
  const Model model = test::model_from(R"({
  "gravity": [0, 0, -9.81],
  "bodies": [
    {"name": "beam", "type": "beam", "formulation": "ancf", "start": [0, 0, 0], "end": [1, 0, 0], "elements": 6,
     "E": 2.1e9, "rho": 7850, "section": {"A": 1e-4, "Iy": 8.3e-10, "Iz": 8.3e-10}, "damping": {"strain_rate": 1e-4}},
    {"name": "bob", "type": "rigid", "mass": 0.2, "com": [1, 0, 0], "inertia": [[1e-4, 0, 0], [0, 1e-4, 0], [0, 0, 1e-4]]}
  ],
  "joints": [
    {"name": "clamp", "type": "fixed", "body1": "ground", "body2": "beam", "node2": "start"},
    {"name": "hang", "type": "spherical", "body1": "beam", "node1": "end", "body2": "bob"}
  ],
  "forces": [{"type": "point_force", "body": "beam", "node": "n3", "table": {"t": [0, 1], "value": [[0, 1, 0], [0, 1, 0]]}}],
  "solver": {"end": 0.2, "step": 1e-3},
  "outputs": [{"name": "energy", "type": "energy"}, {"name": "tip", "type": "node_position", "body": "beam", "node": "end"},
              {"name": "v", "type": "node_velocity", "body": "beam", "node": "n3"}]
})");
  Data data(model);
  EXPECT_EQ(allocations_from_start(model, data, 100, "a beam body"), 0);
}

// A plate body (FORMULATION.md 16): an edge clamped, strain-rate damping, a rigid body hung at a
// node by a spherical joint, a point force at a node, its node outputs and energy recorded.
TEST(Allocation, PlateBodiesAllocateNothing) {
  const Model model = test::model_from(R"({
  "gravity": [0, 0, -9.81],
  "bodies": [
    {"name": "plate", "type": "plate", "corners": [[0, 0, 0], [0.4, 0, 0], [0.4, 0.3, 0], [0, 0.3, 0]], "elements": [2, 2],
     "thickness": 0.005, "E": 7e10, "nu": 0.33, "rho": 2700, "damping": {"strain_rate": 1e-4}, "supports": {"x0": "clamped"}},
    {"name": "bob", "type": "rigid", "mass": 0.2, "com": [0.4, 0.15, -0.05], "inertia": [[1e-4, 0, 0], [0, 1e-4, 0], [0, 0, 1e-4]]}
  ],
  "joints": [{"name": "hang", "type": "spherical", "body1": "plate", "node1": "n2_1", "body2": "bob"}],
  "forces": [{"type": "point_force", "body": "plate", "node": "n1_2", "table": {"t": [0, 1], "value": [[0, 0, 1], [0, 0, 1]]}}],
  "solver": {"end": 0.2, "step": 1e-3},
  "outputs": [{"name": "energy", "type": "energy"}, {"name": "tip", "type": "node_position", "body": "plate", "node": "n2_2"},
              {"name": "v", "type": "node_velocity", "body": "plate", "node": "n1_1"}]
})");
  Data data(model);
  EXPECT_EQ(allocations_from_start(model, data, 100, "a plate body"), 0);
}

// A geometrically exact beam (FORMULATION.md 17): pinned by a revolute joint, a rigid body fixed
// to its end (a node that turns), strain-rate damping, a point torque at a node, outputs, energy.
TEST(Allocation, GeometricallyExactBeamsAllocateNothing) {
  const Model model = test::model_from(R"({
  "gravity": [0, 0, -9.81],
  "bodies": [
    {"name": "beam", "type": "beam", "formulation": "geometrically_exact", "start": [0, 0, 0], "end": [1, 0, 0], "elements": 6,
     "E": 2.1e9, "nu": 0.3, "rho": 7850, "section": {"A": 1e-4, "Iy": 8.3e-10, "Iz": 8.3e-10, "J": 1.4e-9},
     "damping": {"strain_rate": 1e-4}},
    {"name": "bob", "type": "rigid", "mass": 0.2, "com": [1.05, 0, 0], "inertia": [[1e-4, 0, 0], [0, 1e-4, 0], [0, 0, 1e-4]]}
  ],
  "joints": [
    {"name": "pin", "type": "revolute", "body1": "ground", "body2": "beam", "node2": "start", "axis": [0, 1, 0]},
    {"name": "weld", "type": "fixed", "body1": "beam", "node1": "end", "body2": "bob"}
  ],
  "forces": [{"type": "point_torque", "body": "beam", "node": "n3", "table": {"t": [0, 1], "value": [[0.01, 0, 0], [0.01, 0, 0]]}}],
  "solver": {"end": 0.2, "step": 1e-3},
  "outputs": [{"name": "energy", "type": "energy"}, {"name": "tip", "type": "node_position", "body": "beam", "node": "end"},
              {"name": "v", "type": "node_velocity", "body": "beam", "node": "n3"}]
})");
  Data data(model);
  EXPECT_EQ(allocations_from_start(model, data, 100, "a geometrically exact beam"), 0);
}

// The counter sees allocations at all (counting_new.cpp replaces operator new in this program):
// without it every zero above would hold trivially.
TEST(Allocation, TheCounterCountsOperatorNew) {
  const long before = counted_allocations();
  std::vector<double> v(16, 1.0);
  EXPECT_EQ(counted_allocations() - before, 1) << v.size();
}

// A rigid body welded to a plate node (FORMULATION.md 16, "Welds"): the node's exact triad in
// the rows, their bias and second derivatives; in both formulations (the relative one places the
// body at the node's point and keeps the weld's rotation rows).
TEST(Allocation, PlateWeldsAllocateNothing) {
  for (const std::string formulation : {"absolute", "relative"}) {
    const Model model = test::model_from(R"({
  "gravity": [0, 0, -9.81],
  "bodies": [
    {"name": "plate", "type": "plate", "corners": [[0, 0, 0], [0.4, 0, 0], [0.4, 0.3, 0], [0, 0.3, 0]], "elements": [2, 1],
     "thickness": 0.005, "E": 7e10, "nu": 0.33, "rho": 2700, "supports": {"x0": "clamped"}},
    {"name": "bob", "type": "rigid", "mass": 0.2, "com": [0.45, 0.15, -0.05], "inertia": [[1e-4, 0, 0], [0, 1e-4, 0], [0, 0, 1e-4]]}
  ],
  "joints": [{"name": "weld", "type": "fixed", "body1": "plate", "node1": "n2_1", "body2": "bob", "axis": [0, 0.6, 0.8]}],
  "solver": {"end": 0.2, "step": 1e-3, "formulation": ")" + formulation + R"("},
  "outputs": [{"name": "energy", "type": "energy"}]
})");
    Data data(model);
    EXPECT_EQ(allocations_from_start(model, data, 100, ("a plate weld, " + formulation).c_str()), 0);
  }
}
