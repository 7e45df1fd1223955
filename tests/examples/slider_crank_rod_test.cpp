// meshes/models/slider_crank_rod.json with the rod of meshes/rod reduced by ffr-reduce, as the
// demo runs it (shortened to 0.15 s: the spin-up to 1500 rpm and a few revolutions).
//
// Reference: the closed-form kinematics of the rigid slider-crank, x_B = r cos(theta) +
// sqrt(L^2 - r^2 sin^2(theta)). The flexible rod may differ from it only by its elastic
// shortening and bending, a few micrometres here (axial constraint mode at 4.2 kHz against a
// 25 Hz crank); an error in the joints, the frame kinematics or the node data of the SID would
// show at the millimetre level.
#include "ffr/formats/results_io.hpp"
#include "ffr/formats/sid_io.hpp"
#include "../reduce/support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <functional>

using namespace ffr;

namespace {

const formats::Results::Output& channel(const formats::Results& r, const std::string& name) {
  for (const auto& o : r.outputs)
    if (o.name == name) return o;
  throw std::runtime_error("no output channel " + name);
}

// meshes/rod/rod.json meshed with the given TET10 size, reduced, and the example model run with
// it for `end` seconds. Returns the results and the SID.
struct RodRun {
  formats::Results results;
  formats::Sid sid;
  long dof = 0;
};

RodRun run_rod(const std::filesystem::path& dir, double size, double end,
               const std::function<void(nlohmann::json&)>& edit = {}) {
  nlohmann::json part;
  std::ifstream(test::source("meshes/rod/rod.json")) >> part;
  part["geometry"] = test::source("meshes/rod/rod.geo").string();
  part["mesh"]["size"] = size;
  std::ofstream(dir / "rod.json") << part.dump(1);
  const auto red = test::run(test::bin("ffr-reduce").string() + " " + (dir / "rod.json").string() + " -o " +
                             (dir / "rod.sid.h5").string());
  if (red.status != 0) throw std::runtime_error(red.output);
  RodRun r;
  const auto at = red.output.find("model: ");
  if (at != std::string::npos) r.dof = std::stol(red.output.substr(at + 7));
  nlohmann::json model;
  std::ifstream(test::source("meshes/models/slider_crank_rod.json")) >> model;
  model["solver"]["end"] = end;
  if (edit) edit(model);
  std::ofstream(dir / "model.json") << model.dump(1);
  const auto sim = test::run(test::bin("ffr-sim").string() + " " + (dir / "model.json").string() + " -o " +
                             (dir / "out.h5").string() + " --quiet");
  if (sim.status != 0) throw std::runtime_error(sim.output);
  r.results = formats::read_results(dir / "out.h5");
  r.sid = formats::read_sid(dir / "rod.sid.h5");
  return r;
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

// The same part meshed at two very different sizes (about 5k and 33k DOF): the runtime sees only
// the invariants and node data, so the runs may differ only as much as the modes do. The
// quasi-static deformation under the inertia loads goes as 1 / f^2, so the rod's deformation
// may differ by about twice the largest relative frequency difference of the modes (bound:
// three times that); the slider, whose motion differs from the rigid kinematics only by the
// rod's deformation, by that fraction of the deformation. The step works on the same number
// of coordinates, and Newton needs the same iterations (per-step time: tools/bench/runtime_step).
TEST(Examples, TheRodMeshedCoarseAndFineGivesTheSameMotion) {
  test::TempDir coarse_dir("example_rod_coarse"), fine_dir("example_rod_fine");
  const RodRun coarse = run_rod(coarse_dir.path(), 0.012, 0.15);
  const RodRun fine = run_rod(fine_dir.path(), 0.0045, 0.15);
  ASSERT_GT(fine.dof, 5 * coarse.dof);
  ASSERT_EQ(coarse.sid.nq(), fine.sid.nq());
  double df = 0;
  for (Eigen::Index k = 0; k < fine.sid.nq(); ++k)
    df = std::max(df, std::abs(coarse.sid.refmod.frequency_hz(k) / fine.sid.refmod.frequency_hz(k) - 1));
  const auto& mid_c = channel(coarse.results, "rod_mid_deformation").values;
  const auto& mid_f = channel(fine.results, "rod_mid_deformation").values;
  const auto& x_c = channel(coarse.results, "slider_x").values;
  const auto& x_f = channel(fine.results, "slider_x").values;
  ASSERT_EQ(mid_c.rows(), mid_f.rows());
  double deform = 0, d_mid = 0, d_x = 0;
  for (Eigen::Index i = 0; i < mid_f.rows(); ++i) {
    deform = std::max(deform, mid_f.row(i).norm());
    d_mid = std::max(d_mid, (mid_c.row(i) - mid_f.row(i)).norm());
    d_x = std::max(d_x, std::abs(x_c(i, 0) - x_f(i, 0)));
  }
  const double it_c = double(coarse.results.newton_iterations) / double(coarse.results.steps);
  const double it_f = double(fine.results.newton_iterations) / double(fine.results.steps);
  std::printf("%ld vs %ld DOF: modes differ by up to %.2f %%; rod mid-point deformation up to %.3g m, runs differ by "
              "%.3g m (%.2f %%); slider differs by %.3g m; Newton iterations per step %.2f vs %.2f\n",
              coarse.dof, fine.dof, 100 * df, deform, d_mid, 100 * d_mid / deform, d_x, it_c, it_f);
  EXPECT_GT(deform, 1e-6);
  EXPECT_LT(d_mid, 3 * 2 * df * deform);
  EXPECT_LT(d_x, 3 * 2 * df * deform);
  EXPECT_NEAR(it_c, it_f, 0.05 * it_f);
}

// The same model started at full speed: the crank turns at 1500 rpm from t = 0 (no spin-up) and
// the step is 1 ms (0.157 rad per step). The rod starts undeformed with the velocities the
// joints impose, so its constraint modes ring. Newton used to diverge in the first step (a
// tangent built at the predictor threw the second iterate out by a scaled 11); it must run,
// keep the joints closed to round-off, and follow the rigid kinematics to within the ringing.
TEST(Examples, TheRodStartedAtFullSpeedWithMillisecondSteps) {
  test::TempDir dir("example_rod_abrupt");
  const double omega = 1500 * 2 * M_PI / 60;
  const RodRun run = run_rod(dir.path(), 0.006, 0.05, [&](nlohmann::json& m) {
    m["motions"][0]["table"] = {{"t", {0.0, 1.0}}, {"value", {0.0, omega}}};
    m["solver"]["step"] = 1e-3;
  });
  const auto& angle = channel(run.results, "crank_angle").values;
  const auto& slider = channel(run.results, "slider_x").values;
  const double r = 0.08, L = 0.3, theta0 = M_PI / 6;
  auto x_rigid = [&](double th) { return r * std::cos(th) + std::sqrt(L * L - std::pow(r * std::sin(th), 2)); };
  double worst = 0;
  for (Eigen::Index i = 0; i < angle.rows(); ++i)
    worst = std::max(worst, std::abs(slider(i, 0) - (x_rigid(theta0 + angle(i, 0)) - x_rigid(theta0))));
  const double iterations = double(run.results.newton_iterations) / double(run.results.steps);
  std::printf("started at %.1f rad/s, h = 1 ms: %ld steps, %.2f Newton iterations per step; slider vs rigid "
              "kinematics %.3g m\n", omega, (long)run.results.steps, iterations, worst);
  EXPECT_EQ(run.results.steps, 50);
  EXPECT_NEAR(angle(angle.rows() - 1, 0), omega * 0.05, 1e-9);
  EXPECT_LT(worst, 1e-4);
}
