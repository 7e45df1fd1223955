// The State (state.hpp): saved after some steps and restored, the run continues bit for bit as
// it did, for the trapezoidal rule and generalized-alpha, fixed and adaptive steps, on a
// flexible slider-crank (the benchmark's, tools/models) whose steps use every part of the state
// (the frames' predictor, the joint angles' unwrapping, Newton's measured contraction).
#include "support.hpp"
#include "synthetic_bodies.hpp"

#include "models.hpp"  // tools/models: the benchmark's slider-crank

#include "ffr/formats/synthetic.hpp"
#include "ffr/runtime/state.hpp"
#include "ffr/runtime/step_control.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

using namespace ffr::runtime;

namespace {

Model crank(const test::TempDir& dir, const char* scheme) {
  auto chain = ffr::formats::synthetic::spring_chain(bench::rod_params(11, 4));
  test::write_sid_file(chain.sid, dir / "rod.sid.h5");
  Model m = test::model_from(bench::slider_crank_json("rod.sid.h5", 1e-3, 0.1, 150.0), dir.path);
  if (std::strcmp(scheme, "generalized_alpha") == 0) {
    m.settings.integrator = Integrator::GeneralizedAlpha;
    m.settings.spectral_radius = 0.6;
  }
  return m;
}

bool same_bits(const VectorXd& a, const VectorXd& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

}  // namespace

TEST(State, RestoredFixedStepsRepeatBitForBit) {
  for (const char* scheme : {"trapezoidal", "generalized_alpha"}) {
    test::TempDir dir("state_fixed");
    const Model model = crank(dir, scheme);
    Data data(model);
    initialize(model, data);
    for (int i = 0; i < 20; ++i) step(model, data);
    State saved(model);
    save_state(data, saved);
    std::vector<VectorXd> first;
    for (int i = 0; i < 30; ++i) {
      step(model, data);
      first.push_back(data.state.q);
    }
    const VectorXd lambda = data.state.lambda, qdd = data.state.qdd;
    const double t = data.state.t;
    restore_state(saved, data);
    for (int i = 0; i < 30; ++i) {
      step(model, data);
      EXPECT_TRUE(same_bits(data.state.q, first[static_cast<std::size_t>(i)])) << scheme << ", step " << i;
    }
    EXPECT_EQ(data.state.t, t);
    EXPECT_TRUE(same_bits(data.state.lambda, lambda)) << scheme;
    EXPECT_TRUE(same_bits(data.state.qdd, qdd)) << scheme;
    // Through the flat form (the C API's) as well.
    std::vector<double> flat(static_cast<std::size_t>(packed_state_size(model)));
    pack_state(saved, flat.data());
    State back(model);
    unpack_state(model, flat.data(), static_cast<int>(flat.size()), back);
    restore_state(back, data);
    for (int i = 0; i < 30; ++i) step(model, data);
    EXPECT_TRUE(same_bits(data.state.q, first.back())) << scheme;
  }
}

TEST(State, RestoredAdaptiveStepsRepeatBitForBit) {
  test::TempDir dir("state_adaptive");
  Model model = crank(dir, "trapezoidal");
  model.settings.adaptive = true;
  model.settings.rtol = 1e-5;
  model.settings.output_interval = 0.01;
  Data data(model);
  initialize(model, data);
  StepControl control(model, data);
  advance_to(model, data, control, 0.02);
  State saved(model);
  save_state(data, saved);
  const StepControl kept = control;
  advance_to(model, data, control, 0.05);
  const VectorXd q = data.state.q;
  const auto accepted = control.accepted;
  restore_state(saved, data);
  control = kept;
  advance_to(model, data, control, 0.05);
  EXPECT_TRUE(same_bits(data.state.q, q));
  EXPECT_EQ(control.accepted, accepted);
}

TEST(State, AWrongFlatStateIsRefused) {
  test::TempDir dir("state_refused");
  const Model model = crank(dir, "trapezoidal");
  State s(model);
  std::vector<double> flat(static_cast<std::size_t>(packed_state_size(model)), 0.0);
  EXPECT_THROW(unpack_state(model, flat.data(), static_cast<int>(flat.size()) - 1, s), std::invalid_argument);
  flat[20] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(unpack_state(model, flat.data(), static_cast<int>(flat.size()), s), std::invalid_argument);
}
