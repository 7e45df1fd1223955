// Modal stress recovery against CalculiX 2.20 (`ccx`, an independent FE code) on the identical
// TET10 mesh: a 0.2 x 0.02 x 0.012 m steel bar clamped at x = 0, loaded at its tip face through a
// rigid coupling by a force and a moment.
//
// Why the comparison is exact in principle: the bar is reduced by Craig-Bampton with the tip as
// the second interface (root = frame, held). The static response to any load at the tip's
// interface node is a combination of the tip's six constraint modes, so it lies in the modal
// basis and q = Ke^-1 (phi_tip^T F + psi_tip^T M) reproduces ffr's own full static solution
// u = K^-1 f exactly. CalculiX solves the same discrete problem (C3D10 has ffr's TET10 stiffness
// with the same 4-point rule, tests/solid_elements/ccx_compare_test.cpp; *RIGID BODY is the rigid
// interface's kinematics) and makes nodal stresses the same way: stresses at the 4 integration
// points extrapolated linearly to the nodes, plain mean over the elements at a node
// (preproc/include/ffr/preproc/reduce/modal_stress.hpp). What remains is ccx's printing of 6
// significant digits in the .frd file and the linearisation of its rigid-body constraint; the
// tolerance is the issue's 1 %.
#include "ffr/calculix/deck.hpp"
#include "ffr/formats/modal_stress.hpp"
#include "ffr/formats/results_io.hpp"
#include "ffr/formats/sid_io.hpp"
#include "ffr/formats/text_file.hpp"
#include "ffr/preproc/mesh/gmsh_import.hpp"
#include "ffr/preproc/part/part.hpp"
#include "support.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <map>
#include <sstream>

using namespace ffr;

namespace {

const Eigen::Vector3d kForce(20.0, 10.0, -50.0);  // N, at the tip's interface node
const Eigen::Vector3d kMoment(0.5, 0.0, 0.2);     // N m

struct Bar {
  test::TempDir dir{"stress"};
  Bar(const std::string& stress) {
    test::write_text(dir / "bar.geo", R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.2, 0.02, 0.012};
Physical Volume("body") = {1};
Physical Surface("clamp") = Surface In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};
Physical Surface("tip") = Surface In BoundingBox{0.2 - 1e-6, -1, -1, 0.2 + 1e-6, 1, 1};
Physical Surface("top") = Surface In BoundingBox{-1, -1, 0.012 - 1e-6, 1, 1, 0.012 + 1e-6};
)");
    test::gmsh_mesh(dir / "bar.geo", dir / "bar.msh", 0.004, 2);
    test::write_text(dir / "bar.json", R"({"geometry": "bar.msh",
      "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}],
      "interfaces": [{"name": "root", "group": "clamp"}, {"name": "tip", "group": "tip"}],
      "reduction": {"method": "craig-bampton", "interfaces": ["root", "tip"], "frame": "root", "modes": 2},
      "stress": )" + stress + R"(, "visual": false})");
  }
  test::RunResult reduce() const {
    return test::run(test::bin("ffr-reduce").string() + " " + (dir / "bar.json").string() + " -o " +
                     (dir / "bar.sid.h5").string() + " --quiet");
  }
  preproc::Mesh mesh() const { return preproc::load_mesh(preproc::load_part(dir / "bar.json")); }
};

// The static modal coordinates of the tip load (see the file comment).
Eigen::VectorXd static_q(const formats::Sid& sid) {
  const formats::Node& tip = sid.nodes[static_cast<std::size_t>(sid.find_node("tip"))];
  const Eigen::VectorXd Q = tip.phi.transpose() * kForce + tip.psi.transpose() * kMoment;
  return sid.Ke.ldlt().solve(Q);
}

// CalculiX's nodal stresses (xx, yy, zz, xy, yz, zx) of the same static problem, by mesh node
// index (the deck numbers node n as n + 1).
std::map<preproc::Index, Eigen::Matrix<double, 6, 1>> calculix_stress(const preproc::Mesh& mesh, const Eigen::Vector3d& ref,
                                                                       const std::filesystem::path& dir) {
  // The model part of the frequency deck (nodes, C3D10 elements in CalculiX's node order, the
  // clamp held, the material), then the rigid tip and a static step.
  calculix::write_frequency_deck(mesh, "body", "clamp", {2.1e11, 0.3, 7850}, 1, dir / "job.inp");
  std::string deck = formats::read_text_file(dir / "job.inp");
  deck = deck.substr(0, deck.find("*STEP"));
  const long long n = mesh.num_nodes(), r1 = n + 1, r2 = n + 2;
  std::ostringstream f;
  f.precision(17);
  f << deck << "*NODE\n" << r1 << ", " << ref.x() << ", " << ref.y() << ", " << ref.z() << "\n"
    << r2 << ", " << ref.x() << ", " << ref.y() << ", " << ref.z() << "\n*NSET, NSET=TIPN\n";
  int k = 0;
  for (auto i : mesh.node_groups.at("tip")) f << i + 1 << (++k % 10 == 0 ? ",\n" : ", ");
  f << "\n*RIGID BODY, NSET=TIPN, REF NODE=" << r1 << ", ROT NODE=" << r2 << "\n*STEP\n*STATIC\n*CLOAD\n";
  for (int c = 0; c < 3; ++c) f << r1 << ", " << c + 1 << ", " << kForce[c] << "\n";
  for (int c = 0; c < 3; ++c) f << r2 << ", " << c + 1 << ", " << kMoment[c] << "\n";
  f << "*NODE FILE\nU\n*EL FILE\nS\n*END STEP\n";
  test::write_text(dir / "job.inp", f.str());
  const auto r = test::run("cd " + dir.string() + " && OMP_NUM_THREADS=1 ccx -i job");
  if (r.status != 0) throw std::runtime_error("ccx failed: " + r.output.substr(0, 2000));
  // .frd (ASCII): the block after " -4  STRESS", data lines " -1" + node (I10) + 6 x E12.5.
  std::ifstream frd(dir / "job.frd");
  std::string line;
  bool in_stress = false;
  std::map<preproc::Index, Eigen::Matrix<double, 6, 1>> out;
  while (std::getline(frd, line)) {
    if (line.rfind(" -4  STRESS", 0) == 0) in_stress = true;
    else if (in_stress && line.rfind(" -3", 0) == 0) break;
    else if (in_stress && line.rfind(" -1", 0) == 0 && line.size() >= 13 + 6 * 12) {
      const long long node = std::stoll(line.substr(3, 10));
      Eigen::Matrix<double, 6, 1> s;
      for (int c = 0; c < 6; ++c) s[c] = std::stod(line.substr(13 + 12 * static_cast<std::size_t>(c), 12));
      if (node <= n) out[node - 1] = s;
    }
  }
  return out;
}

// Von Mises from the stress components: the textbook formula, written here apart from ffr's.
double mises(const Eigen::Matrix<double, 6, 1>& s) {
  const double p = (s[0] + s[1] + s[2]) / 3;
  Eigen::Matrix3d S;
  S << s[0] - p, s[3], s[5], s[3], s[1] - p, s[4], s[5], s[4], s[2] - p;
  return std::sqrt(1.5 * (S.array() * S.array()).sum());
}

bool have_tools() {
  return std::system("command -v ccx > /dev/null 2>&1 && command -v gmsh > /dev/null 2>&1") == 0 &&
         std::filesystem::exists(test::bin("ffr-reduce"));
}

}  // namespace

TEST(StressRecovery, TipLoadThroughCraigBamptonModesMatchesCalculix) {
  if (!have_tools()) GTEST_SKIP() << "ccx, gmsh or ffr-reduce missing";
  Bar bar(R"({"group": "top"})");
  const auto red = bar.reduce();
  ASSERT_EQ(red.status, 0) << red.output;
  const formats::Sid sid = formats::read_sid(bar.dir / "bar.sid.h5");
  const auto stress = formats::read_modal_stress(bar.dir / "bar.sid.h5");
  ASSERT_TRUE(stress.has_value());
  EXPECT_FALSE(sid.stress.has_value()) << "read_sid must leave /stress to read_modal_stress";
  EXPECT_EQ(stress->selection, "group:top");
  ASSERT_EQ(static_cast<Eigen::Index>(stress->modes.size()), sid.nq());

  const preproc::Mesh mesh = bar.mesh();
  std::map<std::int64_t, preproc::Index> by_tag;
  for (preproc::Index i = 0; i < mesh.num_nodes(); ++i) by_tag[static_cast<std::int64_t>(mesh.node_tag(i))] = i;
  ASSERT_EQ(stress->size(), static_cast<std::int64_t>(mesh.node_groups.at("top").size()));

  const Eigen::VectorXd q = static_q(sid);
  const auto ccx = calculix_stress(mesh, sid.nodes[static_cast<std::size_t>(sid.find_node("tip"))].origin, bar.dir.path());
  double smax = 0, vmax = 0;
  for (const auto& [i, s] : ccx) smax = std::max(smax, s.cwiseAbs().maxCoeff()), vmax = std::max(vmax, mises(s));
  ASSERT_GT(smax, 1e6);  // about 1e8 Pa of bending stress at the root
  double worst = 0, worst_vm = 0;
  for (std::int64_t p = 0; p < stress->size(); ++p) {
    const preproc::Index i = by_tag.at(stress->node[static_cast<std::size_t>(p)]);
    ASSERT_TRUE((stress->position.row(p) - mesh.x.row(i)).norm() == 0);
    ASSERT_TRUE(ccx.count(i)) << "CalculiX has no stress at node " << i + 1;
    Eigen::Matrix<double, 6, 1> s = Eigen::Matrix<double, 6, 1>::Zero();
    for (Eigen::Index k = 0; k < sid.nq(); ++k) s += q(k) * stress->modes[static_cast<std::size_t>(k)].row(p).transpose();
    const auto& c = ccx.at(i);
    worst = std::max(worst, (s - c).cwiseAbs().maxCoeff() / smax);
    if (mises(c) > 0.1 * vmax) worst_vm = std::max(worst_vm, std::abs(formats::von_mises(s) / mises(c) - 1));
  }
  std::cout << "[ stress ] " << stress->size() << " nodes of 'top': max |sigma - sigma_ccx| / max |sigma_ccx| = " << worst
            << ", max relative von Mises difference (nodes above 10 % of the peak) = " << worst_vm << "\n";
  EXPECT_LT(worst, 0.01);
  EXPECT_LT(worst_vm, 0.01);
}

// ffr-info --stress on a run's modal coordinates: the run holds q = 0, the static q and 2 q; the
// von Mises stress it prints is CalculiX's at 0, 1 and 2 times the load (linear elasticity), and
// the principal stresses are the eigenvalues of CalculiX's stress tensor.
TEST(StressRecovery, InfoStressCombinesARunWithTheModes) {
  if (!have_tools() || !std::filesystem::exists(test::bin("ffr-info"))) GTEST_SKIP() << "tools missing";
  Bar bar(R"({"surface": true})");
  const auto red = bar.reduce();
  ASSERT_EQ(red.status, 0) << red.output;
  const formats::Sid sid = formats::read_sid(bar.dir / "bar.sid.h5");
  const Eigen::VectorXd q = static_q(sid);
  formats::Results run;
  run.time = Eigen::Vector3d(0, 1, 2);
  run.outputs.push_back({"q_bar", "modal_coordinates", Eigen::MatrixXd(3, q.size())});
  for (int t = 0; t < 3; ++t) run.outputs[0].values.row(t) = t * q.transpose();
  formats::write_results(run, bar.dir / "run.h5");
  test::write_text(bar.dir / "model.json", R"({"bodies": [{"name": "bar", "type": "flexible", "sid": "bar.sid.h5"}],
    "solver": {"end": 2, "step": 1}, "outputs": [{"name": "q_bar", "type": "modal_coordinates", "body": "bar"}]})");
  const auto r = test::run(test::bin("ffr-info").string() + " " + (bar.dir / "run.h5").string() + " --stress bar --model " +
                           (bar.dir / "model.json").string() + " --json");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  ASSERT_EQ(j["time"].size(), 3u);

  const preproc::Mesh mesh = bar.mesh();
  const auto ccx = calculix_stress(mesh, sid.nodes[static_cast<std::size_t>(sid.find_node("tip"))].origin, bar.dir.path());
  double vmax = 0;
  for (const auto& [i, s] : ccx) vmax = std::max(vmax, mises(s));
  std::map<std::int64_t, preproc::Index> by_tag;
  for (preproc::Index i = 0; i < mesh.num_nodes(); ++i) by_tag[static_cast<std::int64_t>(mesh.node_tag(i))] = i;
  double worst = 0, worst_p = 0;
  int compared = 0;
  for (const auto& node : j["nodes"]) {
    const auto& c = ccx.at(by_tag.at(node["node"].get<std::int64_t>()));
    ASSERT_EQ(node["von_mises"].size(), 3u);
    EXPECT_EQ(node["von_mises"][0].get<double>(), 0.0);
    if (mises(c) < 0.1 * vmax) continue;
    ++compared;
    for (int t = 1; t < 3; ++t) {
      worst = std::max(worst, std::abs(node["von_mises"][t].get<double>() / (t * mises(c)) - 1));
      Eigen::Matrix3d S;
      S << c[0], c[3], c[5], c[3], c[1], c[4], c[5], c[4], c[2];
      const Eigen::Vector3d e = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(S).eigenvalues();  // ascending
      for (int a = 0; a < 3; ++a)
        worst_p = std::max(worst_p, std::abs(node["principal"][t][a].get<double>() - t * e[2 - a]) / (t * vmax));
    }
  }
  std::cout << "[ stress ] surface: " << j["nodes"].size() << " nodes, " << compared
            << " above 10 % of the peak von Mises: max relative difference to CalculiX " << worst
            << ", principal stresses max difference / peak " << worst_p << "\n";
  EXPECT_GT(compared, 10);
  EXPECT_LT(worst, 0.01);
  EXPECT_LT(worst_p, 0.01);
}

// The SID with a /stress group runs in ffr-sim like any other (the runtime does not load the
// group), and ffr-info --stress finds the model through the run's `model` attribute.
TEST(StressRecovery, SimulatorRunsTheSidAndInfoFindsTheModel) {
  if (!have_tools() || !std::filesystem::exists(test::bin("ffr-sim"))) GTEST_SKIP() << "tools missing";
  Bar bar(R"({"group": "top"})");
  ASSERT_EQ(bar.reduce().status, 0);
  test::write_text(bar.dir / "model.json", R"({"bodies": [{"name": "bar", "type": "flexible", "sid": "bar.sid.h5"}],
    "joints": [{"name": "clamp", "type": "fixed", "body1": "ground", "body2": "bar", "node2": "root"}],
    "gravity": [0, 0, -9.81], "solver": {"end": 0.01, "step": 0.001},
    "outputs": [{"name": "q", "type": "modal_coordinates", "body": "bar"}]})");
  const auto sim = test::run("cd " + bar.dir.path().string() + " && " + test::bin("ffr-sim").string() + " model.json -o run.h5");
  ASSERT_EQ(sim.status, 0) << sim.output;
  const auto r = test::run("cd " + bar.dir.path().string() + " && " + test::bin("ffr-info").string() + " run.h5 --stress bar --json");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  EXPECT_EQ(j["time"].size(), formats::read_results(bar.dir / "run.h5").time.size());
  EXPECT_GT(j["nodes"][0]["von_mises"].back().template get<double>(), 0.0);  // gravity bends the bar
}

TEST(StressRecovery, BadRequestsAreRefusedNamingTheField) {
  if (!have_tools()) GTEST_SKIP() << "gmsh or ffr-reduce missing";
  for (const auto& [request, expect] : std::vector<std::pair<std::string, std::string>>{
           {R"({"group": "nope"})", "stress.group: no group 'nope'"},
           {R"({"group": "top", "surface": true})", "not both"},
           {R"({})", "give \"group\""},
           {R"({"groups": "top"})", "groups"},
           {R"("top")", "expected an object"}}) {
    Bar bar(request);
    const auto r = bar.reduce();
    EXPECT_EQ(r.status, 2) << request << ": " << r.output;
    EXPECT_NE(r.output.find(expect), std::string::npos) << request << ": " << r.output;
    EXPECT_FALSE(std::filesystem::exists(bar.dir / "bar.sid.h5"));
  }
  // ffr-info --stress on a SID without the group, and for a body that is not in the model.
  Bar plain(R"({"group": "top"})");
  test::write_text(plain.dir / "bar.json", R"({"geometry": "bar.msh",
      "materials": [{"group": "body", "E": 2.1e11, "nu": 0.3, "rho": 7850}],
      "interfaces": [{"name": "root", "group": "clamp"}],
      "reduction": {"method": "clamped", "interface": "root", "modes": 2}, "visual": false})");
  ASSERT_EQ(plain.reduce().status, 0);
  formats::Results run;
  run.time = Eigen::Vector2d(0, 1);
  run.outputs.push_back({"q", "modal_coordinates", Eigen::MatrixXd::Zero(2, 2)});
  formats::write_results(run, plain.dir / "run.h5");
  test::write_text(plain.dir / "model.json", R"({"bodies": [{"name": "bar", "type": "flexible", "sid": "bar.sid.h5"}],
    "outputs": [{"name": "q", "type": "modal_coordinates", "body": "bar"}]})");
  const std::string info = test::bin("ffr-info").string() + " " + (plain.dir / "run.h5").string() + " --model " +
                           (plain.dir / "model.json").string() + " --stress ";
  auto r = test::run(info + "bar");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("/stress: the SID has no stress group"), std::string::npos) << r.output;
  r = test::run(info + "rod");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("no body named 'rod'"), std::string::npos) << r.output;
}
