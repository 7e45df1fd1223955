// meshes/models/slider_crank_rod.json with the rod of meshes/rod reduced by ffr-reduce, as the
// demo runs it (shortened to 0.15 s: the spin-up to 1500 rpm and a few revolutions).
//
// Reference: the closed-form kinematics of the rigid slider-crank, x_B = r cos(theta) +
// sqrt(L^2 - r^2 sin^2(theta)). The flexible rod may differ from it only by its elastic
// shortening and bending, a few micrometres here (axial constraint mode at 4.2 kHz against a
// 25 Hz crank); an error in the joints, the frame kinematics or the node data of the SID would
// show at the millimetre level.
#include "ffr/formats/results_io.hpp"
#include "../reduce/support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>

using namespace ffr;

namespace {

const formats::Results::Output& channel(const formats::Results& r, const std::string& name) {
  for (const auto& o : r.outputs)
    if (o.name == name) return o;
  throw std::runtime_error("no output channel " + name);
}

}  // namespace

TEST(Examples, SliderCrankWithTheReducedRodFollowsTheRigidKinematicsToMicrometres) {
  test::TempDir dir("example_slider_crank");
  const auto red = test::run(test::bin("ffr-reduce").string() + " " + test::source("meshes/rod/rod.json").string() +
                             " -o " + (dir / "rod.sid.h5").string() + " --quiet");
  ASSERT_EQ(red.status, 0) << red.output;

  nlohmann::json model;
  std::ifstream(test::source("meshes/models/slider_crank_rod.json")) >> model;
  model["solver"]["end"] = 0.15;
  std::ofstream(dir / "model.json") << model.dump(1);
  const auto sim = test::run(test::bin("ffr-sim").string() + " " + (dir / "model.json").string() + " -o " +
                             (dir / "out.h5").string() + " --quiet");
  ASSERT_EQ(sim.status, 0) << sim.output;

  const auto res = formats::read_results(dir / "out.h5");
  const auto& angle = channel(res, "crank_angle").values;
  const auto& slider = channel(res, "slider_x").values;
  const auto& mid = channel(res, "rod_mid_deformation").values;
  const double r = 0.08, L = 0.3, theta0 = M_PI / 6;  // the model's crank, rod and start angle
  auto x_rigid = [&](double th) { return r * std::cos(th) + std::sqrt(L * L - std::pow(r * std::sin(th), 2)); };
  double worst = 0, deform = 0;
  for (Eigen::Index i = 0; i < res.time.size(); ++i) {
    worst = std::max(worst, std::abs(slider(i, 0) - (x_rigid(theta0 + angle(i, 0)) - x_rigid(theta0))));
    deform = std::max(deform, mid.row(i).norm());
  }
  std::printf("slider vs rigid kinematics: %.3g m; rod mid-point deformation up to %.3g m; %.1f revolutions\n", worst,
              deform, angle(angle.rows() - 1, 0) / (2 * M_PI));
  EXPECT_GT(angle(angle.rows() - 1, 0), 2 * M_PI * 1.5);  // it did turn at speed
  EXPECT_LT(worst, 5e-5);
  EXPECT_GT(deform, 1e-7);  // the rod is flexible: it deforms under the inertia loads ...
  EXPECT_LT(deform, 1e-3);  // ... by micrometres, not millimetres

  // The demo's plot of the run.
  const auto png = dir / "run.png";
  const auto plot = test::run(test::bin("ffr-info").string() + " " + (dir / "out.h5").string() +
                              " --plot slider_x,rod_mid_deformation --png " + png.string());
  EXPECT_EQ(plot.status, 0) << plot.output;
  EXPECT_TRUE(std::filesystem::exists(png));
}
