// Modal stress recovery on shells (QUAD4 = bilinear membrane with incompatible modes + MITC4
// plate, TRI3 = OPT membrane + DKT plate): the three layers (top, middle, bottom) of each shell
// node in the SID's /stress group against closed forms nobody here computed:
//  - patch tests: for an imposed in-plane stretch of a tilted plate the stress on every layer is
//    the plane-stress sigma = E/(1 - nu^2) (eps + nu eps') (Timoshenko & Goodier, Theory of
//    Elasticity, plane stress); for an imposed constant-curvature Kirchhoff field
//    w = (A x1^2 + B x2^2 + C x1 x2) / 2 it is sigma = -z D (w,11, w,22, 2 w,12) at z = +-t/2
//    (Timoshenko & Woinowsky-Krieger, Theory of Plates and Shells, ch. 1-2), and a rigid motion
//    adds nothing (QUAD4, TRI3, and TRI6 as its four TRI3); the same with half the elements'
//    node order reversed (the recovery orients the surface: one normal for every node, the
//    seam's top stress not cancelled); a node of a solid block and its shell skin carries the
//    3-D Hooke stress in its solid row and the plane-stress one in its three shell rows;
//  - a cantilever plate strip under a tip force, reduced by Craig-Bampton with the tip as an
//    interface so that the static load is represented exactly (as tests/stress/recovery_test.cpp
//    does for solids): at sections away from the clamp and the tip the surface stress is the
//    beam theory sigma = 6 M / (b t^2), M = F (L - x) (Timoshenko & Gere, Mechanics of
//    Materials, flexure formula), tension on the upper side; the mid-surface's transverse shear
//    3 Q / (2 t) integrates over the width to the section's shear force V = F (statics);
//  - the same strip against CalculiX 2.20 (S4 shells, which ccx expands into C3D8I bricks) on the
//    identical mesh: in-plane surface stresses at mid-span;
//  - a stress group reaching into beam elements is refused naming the field.
#include "ffr/formats/modal_stress.hpp"
#include "ffr/formats/results_io.hpp"
#include "ffr/formats/sid_io.hpp"
#include "ffr/preproc/mesh/gmsh_import.hpp"
#include "ffr/preproc/model/fe_model.hpp"
#include "ffr/preproc/part/part.hpp"
#include "ffr/preproc/reduce/modal_stress.hpp"
#include "support.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <tuple>

using namespace ffr;

namespace {

using Voigt = Eigen::Matrix<double, 6, 1>;

bool have_gmsh() { return std::system("command -v gmsh > /dev/null 2>&1") == 0; }

Voigt voigt(const Eigen::Matrix3d& S) {
  Voigt v;
  v << S(0, 0), S(1, 1), S(2, 2), S(0, 1), S(1, 2), S(0, 2);
  return v;
}

// Plane stress in the plate's axes (a1, a2) as a global tensor: the textbook Hooke's law for
// sigma_33 = 0, written here apart from ffr's element code.
Eigen::Matrix3d plane_stress(double e11, double e22, double g12, double E, double nu, const Eigen::Vector3d& a1,
                             const Eigen::Vector3d& a2) {
  const double c = E / (1 - nu * nu);
  const double s11 = c * (e11 + nu * e22), s22 = c * (e22 + nu * e11), s12 = E / (2 * (1 + nu)) * g12;
  return s11 * a1 * a1.transpose() + s22 * a2 * a2.transpose() + s12 * (a1 * a2.transpose() + a2 * a1.transpose());
}

struct Plate {
  test::TempDir dir{"shell_stress_patch"};
  preproc::PartSpec part;
  preproc::Mesh mesh;
  preproc::FeModel model;
  int flipped = 0;
  // A 0.1 x 0.06 plate in the plane through `o` spanned by a1, a2, unstructured.
  // flip: the elements beyond x1 = 0.05 get their node order reversed (normal -n), as gmsh
  // gives when two surfaces of one part face opposite ways.
  // order 2: TRI6 elements, which ffr computes as four TRI3 each.
  Plate(bool quads, const Eigen::Vector3d& o, const Eigen::Vector3d& a1, const Eigen::Vector3d& a2, bool flip = false,
        int order = 1) {
    std::ostringstream geo;
    geo.precision(17);
    const Eigen::Vector3d p[4] = {o, o + 0.1 * a1, o + 0.1 * a1 + 0.06 * a2, o + 0.06 * a2};
    for (int i = 0; i < 4; ++i) geo << "Point(" << i + 1 << ") = {" << p[i].x() << ", " << p[i].y() << ", " << p[i].z() << "};\n";
    geo << "Line(1) = {1, 2};\nLine(2) = {2, 3};\nLine(3) = {3, 4};\nLine(4) = {4, 1};\nCurve Loop(1) = {1, 2, 3, 4};\n"
        << "Plane Surface(1) = {1};\nPhysical Surface(\"skin\") = {1};\n"
        << (quads ? "Recombine Surface{1};\n" : "");
    test::write_text(dir / "p.geo", geo.str());
    test::gmsh_mesh(dir / "p.geo", dir / "p.msh", 0.02, order);
    test::write_text(dir / "p.json", R"({"geometry": "p.msh",
      "shells": [{"group": "skin", "thickness": 0.003, "E": 7e10, "nu": 0.33, "rho": 2700}],
      "reduction": {"method": "free", "modes": 1}, "stress": {"group": "skin"}})");
    part = preproc::load_part(dir / "p.json");
    mesh = preproc::load_mesh(part);
    auto& blk = mesh.blocks.front();
    const int nn = preproc::num_nodes(blk.type);
    for (preproc::Index e = 0; flip && e < blk.size(); ++e) {
      preproc::Index* c = blk.conn.data() + e * nn;
      Eigen::Vector3d centre = Eigen::Vector3d::Zero();
      for (int a = 0; a < nn; ++a) centre += mesh.x.row(c[a]).transpose() / nn;
      if ((centre - o).dot(a1) > 0.05) {
        std::reverse(c + 1, c + nn);
        ++flipped;
      }
    }
    model = preproc::build_model(mesh, part);
  }
};

}  // namespace

TEST(ShellStressPatch, MembraneBendingAndRigidMotionOnTiltedPlates) {
  if (!have_gmsh()) GTEST_SKIP() << "gmsh missing";
  const double E = 7e10, nu = 0.33, t = 0.003;
  const Eigen::Vector3d a1 = Eigen::Vector3d(1, 2, 0.5).normalized();
  const Eigen::Vector3d a2 = a1.cross(Eigen::Vector3d(0.3, -0.2, 1)).normalized(), n = a1.cross(a2);
  const Eigen::Vector3d o(0.01, -0.02, 0.03);
  const double e11 = 1e-3, e22 = -4e-4, g12 = 6e-4;  // membrane strains
  const double A = 0.3, B = -0.5, C = 0.4;            // w = (A x1^2 + B x2^2 + C x1 x2) / 2 [1/m]
  const Eigen::Vector3d omega(2e-3, -1e-3, 3e-3), c(1e-4, 2e-4, -3e-4);
  for (const auto& [quads, flip, order] :
       std::vector<std::tuple<bool, bool, int>>{{true, false, 1}, {false, false, 1}, {true, true, 1}, {false, true, 1}, {false, false, 2}}) {
    Plate plate(quads, o, a1, a2, flip, order);
    const auto& model = plate.model;
    const auto& mesh = plate.mesh;
    if (flip) {
      EXPECT_GT(plate.flipped, 5);
      EXPECT_LT(plate.flipped, mesh.blocks.front().size() - 5);
    }
    ASSERT_EQ(mesh.blocks.front().type, quads ? preproc::ElementType::Quad4
                                              : order == 2 ? preproc::ElementType::Tri6 : preproc::ElementType::Tri3);
    // Columns: the stretch, the bending, the stretch plus a rigid motion.
    Eigen::MatrixXd Phi = Eigen::MatrixXd::Zero(model.num_dofs, 3);
    std::vector<preproc::Index> nodes;
    for (preproc::Index k = 0; k < mesh.num_nodes(); ++k) {
      if (model.node_ndof[static_cast<std::size_t>(k)] == 0) continue;
      nodes.push_back(k);
      const Eigen::Vector3d x = mesh.x.row(k).transpose();
      const double x1 = (x - o).dot(a1), x2 = (x - o).dot(a2);
      const Eigen::Vector3d um = a1 * (e11 * x1 + 0.5 * g12 * x2) + a2 * (0.5 * g12 * x1 + e22 * x2);
      // Kirchhoff: the fibre n turns to n - w,1 a1 - w,2 a2, i.e. by theta = w,2 a1 - w,1 a2.
      const double w = 0.5 * (A * x1 * x1 + B * x2 * x2 + C * x1 * x2), w1 = A * x1 + 0.5 * C * x2, w2 = B * x2 + 0.5 * C * x1;
      const Eigen::Vector3d ub = w * n, thb = w2 * a1 - w1 * a2;
      const Eigen::Vector3d ur = c + omega.cross(x);
      for (int i = 0; i < 3; ++i) {
        Phi(model.dof(k, i), 0) = um[i];
        Phi(model.dof(k, i), 1) = ub[i];
        Phi(model.dof(k, 3 + i), 1) = thb[i];
        Phi(model.dof(k, i), 2) = um[i] + ur[i];
        Phi(model.dof(k, 3 + i), 2) = omega[i];
      }
    }
    const formats::ModalStress s = preproc::recover_modal_stress(model, Phi, nodes);
    ASSERT_EQ(s.size(), 3 * static_cast<std::int64_t>(nodes.size()));
    ASSERT_EQ(s.layer.size(), static_cast<std::size_t>(s.size()));
    EXPECT_NO_THROW(formats::check_modal_stress(s, 3));
    const Voigt membrane = voigt(plane_stress(e11, e22, g12, E, nu, a1, a2));
    // Bending strain at height z along n: -z (w,11, w,22, 2 w,12).
    const Voigt bending_top = voigt(plane_stress(-A * t / 2, -B * t / 2, -C * t / 2, E, nu, a1, a2));
    double worst = 0;
    const Eigen::Vector3d n0 = s.normal.row(0).transpose();
    for (Eigen::Index r = 0; r < s.size(); ++r) {
      EXPECT_LT((s.normal.row(r).transpose() - n0).norm(), 1e-12) << "the surface is oriented one way";
      const std::int64_t l = s.layer[static_cast<std::size_t>(r)];
      ASSERT_NE(l, formats::kSolid);
      const double side = s.normal.row(r).dot(n);  // +1: the stored "top" is the +n side
      ASSERT_NEAR(std::abs(side), 1, 1e-12);
      const double z = l == formats::kShellTop ? side : l == formats::kShellBottom ? -side : 0;  // in units of t/2
      const Voigt want[3] = {membrane, z * bending_top, membrane};
      for (int k = 0; k < 3; ++k)
        worst = std::max(worst, (s.modes[static_cast<std::size_t>(k)].row(r).transpose() - want[k]).cwiseAbs().maxCoeff() /
                                    std::max(membrane.cwiseAbs().maxCoeff(), bending_top.cwiseAbs().maxCoeff()));
    }
    std::cout << "[ shell patch ] " << (quads ? "QUAD4" : order == 2 ? "TRI6" : "TRI3") << (flip ? " (half the elements reversed)" : "") << ", "
              << nodes.size()
              << " nodes x 3 layers: max relative stress error " << worst << "\n";
    EXPECT_LT(worst, 1e-9);
  }
}

namespace {

// A steel plate strip, L x b x t = 0.2 x 0.02 x 0.002 m in the xy plane, clamped along x = 0,
// reduced by Craig-Bampton with the tip edge x = L as the second interface (rigid).
constexpr double kL = 0.2, kB = 0.02, kT = 0.002, kF = 10.0;  // tip force -kF along z [N]

struct Strip {
  test::TempDir dir{"shell_stress_strip"};
  explicit Strip(bool quads, const std::string& stress = R"({"group": "strip"})") {
    test::write_text(dir / "s.geo", std::string(R"(SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 0.2, 0.02};
Physical Surface("strip") = {1};
Physical Curve("clamp") = Curve In BoundingBox{-1e-6, -1, -1, 1e-6, 1, 1};
Physical Curve("tip") = Curve In BoundingBox{0.2 - 1e-6, -1, -1, 0.2 + 1e-6, 1, 1};
)") + (quads ? "Transfinite Curve{:} = 9;\nTransfinite Curve{1, 3} = 81;\nTransfinite Surface{1};\nRecombine Surface{1};\n" : ""));
    test::gmsh_mesh(dir / "s.geo", dir / "s.msh", 0.0025, 1);
    test::write_text(dir / "s.json", R"({"geometry": "s.msh",
      "shells": [{"group": "strip", "thickness": 0.002, "E": 2.1e11, "nu": 0.3, "rho": 7850}],
      "interfaces": [{"name": "root", "group": "clamp"}, {"name": "tip", "group": "tip"}],
      "reduction": {"method": "craig-bampton", "interfaces": ["root", "tip"], "frame": "root", "modes": 2},
      "stress": )" + stress + R"(, "visual": false})");
  }
  test::RunResult reduce() const {
    return test::run(test::bin("ffr-reduce").string() + " " + (dir / "s.json").string() + " -o " +
                     (dir / "s.sid.h5").string() + " --quiet");
  }
};

// q of the static tip load: the tip's constraint modes represent it exactly (see recovery_test).
Eigen::VectorXd static_q(const formats::Sid& sid) {
  const formats::Node& tip = sid.nodes[static_cast<std::size_t>(sid.find_node("tip"))];
  return sid.Ke.ldlt().solve(tip.phi.transpose() * Eigen::Vector3d(0, 0, -kF));
}

bool have_tools() { return have_gmsh() && std::filesystem::exists(test::bin("ffr-reduce")); }

}  // namespace

TEST(ShellStressStrip, TipLoadGivesBeamTheoryBendingStress) {
  if (!have_tools()) GTEST_SKIP() << "gmsh or ffr-reduce missing";
  for (const bool quads : {true, false}) {
    Strip strip(quads);
    const auto red = strip.reduce();
    ASSERT_EQ(red.status, 0) << red.output;
    const formats::Sid sid = formats::read_sid(strip.dir / "s.sid.h5");
    const auto stress = formats::read_modal_stress(strip.dir / "s.sid.h5");
    ASSERT_TRUE(stress.has_value());
    ASSERT_EQ(stress->layer.size(), stress->node.size());
    const Eigen::VectorXd q = static_q(sid);
    double worst = 0, worst_mid = 0, worst_shear = 0, worst_yy = 0;
    int compared = 0;
    std::map<long, std::vector<std::pair<double, double>>> sections;  // x -> (y, sigma_xz) on the mid-surface
    for (Eigen::Index r = 0; r < stress->size(); ++r) {
      const double x = stress->position(r, 0);
      if (x < 0.25 * kL - 1e-9 || x > 0.75 * kL + 1e-9) continue;  // Saint-Venant: away from the clamp and the tip
      Voigt s = Voigt::Zero();
      for (Eigen::Index k = 0; k < sid.nq(); ++k) s += q(k) * stress->modes[static_cast<std::size_t>(k)].row(r).transpose();
      const double up = stress->normal(r, 2);  // +1: "top" is the upper (+z) side
      EXPECT_NEAR(std::abs(up), 1, 1e-12);
      const double beam = 6 * kF * (kL - x) / (kB * kT * kT);  // tension on the upper side
      switch (stress->layer[static_cast<std::size_t>(r)]) {
        case formats::kShellTop: worst = std::max(worst, std::abs(s[0] / (up * beam) - 1)); break;
        case formats::kShellBottom: worst = std::max(worst, std::abs(s[0] / (-up * beam) - 1)); break;
        case formats::kShellMiddle:
          worst_mid = std::max(worst_mid, std::abs(s[0]) / beam);
          sections[std::lround(x / 1e-6)].emplace_back(stress->position(r, 1), s[5]);
          break;
        default: ADD_FAILURE() << "a solid row in a shell part";
      }
      worst_yy = std::max(worst_yy, std::abs(s[1]) / beam);
      ++compared;
    }
    // The transverse shear resultant of a section, Q_x = (2t/3) sigma_xz(mid) integrated over the
    // width (trapezoidal rule on the section's nodes), is the shear force V = F (statics). The
    // Reissner-Mindlin plate concentrates part of it in boundary layers at the free edges (its
    // form of Kirchhoff's edge force from the twisting moment), so the parabolic 3V/(2bt) of
    // beam theory is not pointwise; only the resultant is checked.
    if (quads) {
      for (auto& [key, pts] : sections) {
        std::sort(pts.begin(), pts.end());
        double Q = 0;
        for (std::size_t i = 1; i < pts.size(); ++i)
          Q += 0.5 * (pts[i].first - pts[i - 1].first) * (pts[i].second + pts[i - 1].second) * (2 * kT / 3);
        ASSERT_GT(pts.size(), 5u) << key;
        worst_shear = std::max(worst_shear, std::abs(std::abs(Q) / kF - 1));
      }
    }
    std::cout << "[ shell strip ] " << (quads ? "QUAD4" : "TRI3") << ": " << compared
              << " rows at 0.25 L..0.75 L: max |sigma_xx / (6M/bt^2) - 1| on the surfaces " << worst
              << ", mid-surface sigma_xx / bending " << worst_mid << ", |sigma_yy| / bending " << worst_yy;
    if (quads) std::cout << ", " << sections.size() << " sections: max |shear resultant / V - 1| " << worst_shear;
    std::cout << "\n";
    EXPECT_GT(compared, 50);
    EXPECT_LT(worst, 0.01);
    EXPECT_LT(worst_mid, 1e-3);
    if (quads) {
      EXPECT_LT(worst_shear, 0.01);
    }
  }
}

// ffr-info --stress on a run holding the static q: every shell node reports its three layers by
// name; at mid-span the surfaces are in uniaxial bending stress, so von Mises and the principal
// stresses are |sigma|, (sigma, 0, 0) on the tension side and (0, 0, sigma) on the other
// (beam theory as above).
TEST(ShellStressStrip, InfoStressReportsEachLayer) {
  if (!have_tools() || !std::filesystem::exists(test::bin("ffr-info"))) GTEST_SKIP() << "tools missing";
  Strip strip(true);
  ASSERT_EQ(strip.reduce().status, 0);
  const formats::Sid sid = formats::read_sid(strip.dir / "s.sid.h5");
  const Eigen::VectorXd q = static_q(sid);
  formats::Results run;
  run.time = Eigen::Vector2d(0, 1);
  run.outputs.push_back({"q_strip", "modal_coordinates", Eigen::MatrixXd(2, q.size())});
  run.outputs[0].values.row(0).setZero();
  run.outputs[0].values.row(1) = q.transpose();
  formats::write_results(run, strip.dir / "run.h5");
  test::write_text(strip.dir / "model.json", R"({"bodies": [{"name": "strip", "type": "flexible", "sid": "s.sid.h5"}],
    "solver": {"end": 1, "step": 1}, "outputs": [{"name": "q_strip", "type": "modal_coordinates", "body": "strip"}]})");
  const std::string info = test::bin("ffr-info").string() + " " + (strip.dir / "run.h5").string() + " --stress strip --model " +
                           (strip.dir / "model.json").string();
  const auto r = test::run(info + " --json");
  ASSERT_EQ(r.status, 0) << r.output;
  const auto j = nlohmann::json::parse(r.output);
  std::map<std::string, int> layers;
  double worst = 0;
  for (const auto& node : j["nodes"]) {
    const std::string layer = node["layer"];
    ++layers[layer];
    const double x = node["position"][0];
    if (layer == "middle" || x < 0.25 * kL - 1e-9 || x > 0.75 * kL + 1e-9) continue;
    const double beam = 6 * kF * (kL - x) / (kB * kT * kT);
    const auto& p = node["principal"][1];
    const bool tension = p[0].get<double>() > -p[2].get<double>();
    worst = std::max({worst, std::abs(node["von_mises"][1].get<double>() / beam - 1),
                      std::abs((tension ? p[0].get<double>() : -p[2].get<double>()) / beam - 1),
                      std::abs(p[1].get<double>()) / beam});
  }
  std::cout << "[ shell strip ] ffr-info --stress: " << layers["top"] << " top, " << layers["middle"] << " middle, "
            << layers["bottom"] << " bottom rows; max relative difference of von Mises and principal stress to beam "
            << "theory at 0.25 L..0.75 L: " << worst << "\n";
  EXPECT_EQ(layers.size(), 3u);
  EXPECT_EQ(layers["top"], layers["bottom"]);
  EXPECT_EQ(layers["top"], layers["middle"]);
  EXPECT_LT(worst, 0.01);
  const auto text = test::run(info);
  ASSERT_EQ(text.status, 0) << text.output;
  EXPECT_NE(text.output.find("layer"), std::string::npos) << text.output.substr(0, 500);
  EXPECT_NE(text.output.find(" bottom "), std::string::npos);
}

// A stress group that reaches a node held only by a beam is refused, naming the part file's
// field, before the reduction runs; the shell nodes of the same part are accepted.
TEST(ShellStressStrip, GroupWithBeamNodesIsRefused) {
  if (!have_tools()) GTEST_SKIP() << "gmsh or ffr-reduce missing";
  test::TempDir dir("shell_stress_beam");
  // Built-in kernel: the rectangle and the spar share point 2, so the beam hangs on the shell.
  test::write_text(dir / "m.geo", R"(Point(1) = {0, 0, 0}; Point(2) = {0.2, 0, 0}; Point(3) = {0.2, 0.02, 0};
Point(4) = {0, 0.02, 0}; Point(5) = {0.25, 0, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1}; Line(5) = {2, 5};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Physical Surface("strip") = {1}; Physical Curve("spar") = {5}; Physical Curve("clamp") = {4};
)");
  test::gmsh_mesh(dir / "m.geo", dir / "m.msh", 0.01, 1);
  for (const auto& [group, ok] : std::vector<std::pair<std::string, bool>>{{"spar", false}, {"strip", true}}) {
    test::write_text(dir / "m.json", R"({"geometry": "m.msh",
      "shells": [{"group": "strip", "thickness": 0.002, "E": 2.1e11, "nu": 0.3, "rho": 7850}],
      "beams": [{"group": "spar", "E": 2.1e11, "nu": 0.3, "rho": 7850,
                 "section": {"A": 1e-5, "Iy": 1e-10, "Iz": 1e-10, "J": 2e-10}, "y_axis": [0, 1, 0]}],
      "interfaces": [{"name": "root", "group": "clamp"}],
      "reduction": {"method": "clamped", "interface": "root", "modes": 2},
      "stress": {"group": ")" + group + R"("}, "visual": false})");
    const auto r = test::run(test::bin("ffr-reduce").string() + " " + (dir / "m.json").string() + " -o " +
                             (dir / "m.sid.h5").string() + " --quiet");
    if (ok) {
      EXPECT_EQ(r.status, 0) << r.output;
      continue;
    }
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find("m.json: stress.group: node "), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("of group 'spar' belongs to no solid or shell element"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "m.sid.h5"));
  }
}

namespace {

// CalculiX's static solution of the same strip mesh with S4 shells: the deck is written here
// (nodes and elements as ffr reads them, the clamp edge held in all six DOFs, the tip force as
// consistent nodal forces along the tip edge). ccx expands each S4 into a C3D8I brick through
// the thickness and, with OUTPUT=3D, prints the stress at the expanded nodes x +- (t/2) n.
// Returns (position, stress) of every node of the .frd's stress block.
std::vector<std::pair<Eigen::Vector3d, Voigt>> calculix_strip(const preproc::Mesh& mesh, const std::filesystem::path& dir) {
  std::ostringstream f;
  f.precision(17);
  f << "*NODE, NSET=NALL\n";
  for (preproc::Index i = 0; i < mesh.num_nodes(); ++i)
    f << i + 1 << ", " << mesh.x(i, 0) << ", " << mesh.x(i, 1) << ", " << mesh.x(i, 2) << "\n";
  const auto& blk = *std::find_if(mesh.blocks.begin(), mesh.blocks.end(),
                                  [](const auto& b) { return b.type == preproc::ElementType::Quad4; });
  f << "*ELEMENT, TYPE=S4, ELSET=EALL\n";
  for (preproc::Index e = 0; e < blk.size(); ++e) {
    f << e + 1;
    for (int a = 0; a < 4; ++a) f << ", " << blk.element(e)[a] + 1;
    f << "\n";
  }
  f << "*NSET, NSET=CLAMP\n";
  for (auto i : mesh.node_groups.at("clamp")) f << i + 1 << ",\n";
  f << "*MATERIAL, NAME=STEEL\n*ELASTIC\n2.1e11, 0.3\n*SHELL SECTION, ELSET=EALL, MATERIAL=STEEL\n" << kT
    << "\n*BOUNDARY\nCLAMP, 1, 6\n*STEP\n*STATIC\n*CLOAD\n";
  std::vector<std::pair<double, preproc::Index>> tip;
  for (auto i : mesh.node_groups.at("tip")) tip.emplace_back(mesh.x(i, 1), i);
  std::sort(tip.begin(), tip.end());
  for (std::size_t k = 0; k < tip.size(); ++k) {
    const double w = (k == 0 || k + 1 == tip.size() ? 0.5 : 1.0) / static_cast<double>(tip.size() - 1);
    f << tip[k].second + 1 << ", 3, " << -kF * w << "\n";
  }
  f << "*NODE FILE, OUTPUT=3D\nU\n*EL FILE, OUTPUT=3D\nS\n*END STEP\n";
  test::write_text(dir / "ccx.inp", f.str());
  const auto r = test::run("cd " + dir.string() + " && OMP_NUM_THREADS=1 ccx -i ccx");
  if (r.status != 0 || r.output.find("*ERROR") != std::string::npos)
    throw std::runtime_error("ccx failed: " + r.output.substr(r.output.size() > 2000 ? r.output.size() - 2000 : 0));
  std::ifstream frd(dir / "ccx.frd");
  std::string line;
  std::map<long long, Eigen::Vector3d> at;
  std::vector<std::pair<Eigen::Vector3d, Voigt>> out;
  enum { kNone, kNodes, kStress } block = kNone;
  while (std::getline(frd, line)) {
    if (line.rfind("    2C", 0) == 0) block = kNodes;
    else if (line.rfind(" -4  STRESS", 0) == 0) block = kStress;
    else if (line.rfind(" -3", 0) == 0) block = kNone;
    else if (block != kNone && line.rfind(" -1", 0) == 0) {
      const long long node = std::stoll(line.substr(3, 10));
      if (block == kNodes && line.size() >= 13 + 3 * 12) {
        Eigen::Vector3d x;
        for (int c = 0; c < 3; ++c) x[c] = std::stod(line.substr(13 + 12 * static_cast<std::size_t>(c), 12));
        at[node] = x;
      } else if (block == kStress && line.size() >= 13 + 6 * 12 && at.count(node)) {
        Voigt s;
        for (int c = 0; c < 6; ++c) s[c] = std::stod(line.substr(13 + 12 * static_cast<std::size_t>(c), 12));
        out.emplace_back(at[node], s);
      }
    }
  }
  return out;
}

}  // namespace

// The strip's surface stresses against CalculiX 2.20's on the identical shell mesh. The two are
// different discretisations of the same problem (ffr: flat MITC4 + incompatible-mode membrane;
// ccx: the S4 expanded to a C3D8I brick through the thickness), so they agree where both are
// converged: at sections away from the clamp and the tip (where the two models also hold and
// load the edges differently: a rigid interface against held nodes and nodal forces). Only the
// in-plane stresses are compared: the single C3D8I layer carries a constant transverse shear
// and a small sigma_zz through its thickness, where the shell's surfaces are traction-free by
// the plane-stress assumption (sigma_xz = sigma_yz = sigma_zz = 0 there).
TEST(ShellStressStrip, SurfaceStressMatchesCalculixAtMidSpan) {
  if (!have_tools() || std::system("command -v ccx > /dev/null 2>&1") != 0) GTEST_SKIP() << "ccx, gmsh or ffr-reduce missing";
  Strip strip(true);
  ASSERT_EQ(strip.reduce().status, 0);
  const formats::Sid sid = formats::read_sid(strip.dir / "s.sid.h5");
  const auto stress = formats::read_modal_stress(strip.dir / "s.sid.h5");
  ASSERT_TRUE(stress.has_value());
  const Eigen::VectorXd q = static_q(sid);
  const preproc::Mesh mesh = preproc::load_mesh(preproc::load_part(strip.dir / "s.json"));
  const auto ccx = calculix_strip(mesh, strip.dir.path());
  ASSERT_GT(ccx.size(), 2u * static_cast<std::size_t>(mesh.num_nodes()) - 1);
  double worst = 0;
  int compared = 0;
  for (Eigen::Index r = 0; r < stress->size(); ++r) {
    const std::int64_t l = stress->layer[static_cast<std::size_t>(r)];
    const double x = stress->position(r, 0);
    if (l == formats::kShellMiddle || x < 0.25 * kL - 1e-9 || x > 0.75 * kL + 1e-9) continue;
    const Eigen::Vector3d p = stress->position.row(r).transpose() +
                              (l == formats::kShellTop ? 0.5 : -0.5) * kT * stress->normal.row(r).transpose();
    const Voigt* c = nullptr;
    for (const auto& [y, s] : ccx)
      if ((y - p).norm() < 1e-6) c = &s;
    ASSERT_NE(c, nullptr) << "CalculiX has no expanded node at " << p.transpose();
    Voigt s = Voigt::Zero();
    for (Eigen::Index k = 0; k < sid.nq(); ++k) s += q(k) * stress->modes[static_cast<std::size_t>(k)].row(r).transpose();
    const double beam = 6 * kF * (kL - x) / (kB * kT * kT);
    // The in-plane components (xx, yy, xy); see the test's comment for the others.
    for (const int k : {0, 1, 3}) worst = std::max(worst, std::abs(s[k] - (*c)[k]) / beam);
    ++compared;
  }
  std::cout << "[ shell strip ] CalculiX S4 (C3D8I expansion): " << compared
            << " surface rows at 0.25 L..0.75 L, max |sigma - sigma_ccx| / (6M/bt^2) of xx, yy, xy = " << worst << "\n";
  EXPECT_GT(compared, 500);
  EXPECT_LT(worst, 0.01);
}

// A node held by solid and shell elements (a 1 mm skin on a block's top face) has a solid row
// and then its three shell rows. For a uniform in-plane strain of the whole part the solid row is
// the 3-D Hooke's law sigma = lambda tr(eps) I + 2 mu eps and the shell rows the plane-stress law
// of the skin's material (both textbook forms, written here).
TEST(ShellStressPatch, NodeOfSolidAndShellHasBothStresses) {
  if (!have_gmsh()) GTEST_SKIP() << "gmsh missing";
  test::TempDir dir("shell_stress_skin");
  test::write_text(dir / "b.geo", R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.1, 0.04, 0.03};
Physical Volume("body") = {1};
Physical Surface("top") = Surface In BoundingBox{-1, -1, 0.03 - 1e-6, 1, 1, 0.03 + 1e-6};
)");
  test::gmsh_mesh(dir / "b.geo", dir / "b.msh", 0.015, 1);
  test::write_text(dir / "b.json", R"({"geometry": "b.msh",
    "materials": [{"group": "body", "E": 7e10, "nu": 0.33, "rho": 2700}],
    "shells": [{"group": "top", "thickness": 0.001, "E": 2.1e11, "nu": 0.3, "rho": 7850}],
    "reduction": {"method": "free", "modes": 1}, "stress": {"group": "top"}})");
  const preproc::PartSpec part = preproc::load_part(dir / "b.json");
  const preproc::Mesh mesh = preproc::load_mesh(part);
  const preproc::FeModel model = preproc::build_model(mesh, part);
  const std::vector<preproc::Index> nodes = preproc::stress_nodes(model);
  // u = G x with an in-plane strain (exx, eyy, gxy) and a rigid rotation about z.
  const double exx = 8e-4, eyy = -3e-4, gxy = 5e-4, wz = 2e-3;
  Eigen::Matrix3d G = Eigen::Matrix3d::Zero();
  G(0, 0) = exx;
  G(1, 1) = eyy;
  G(0, 1) = 0.5 * gxy - wz;
  G(1, 0) = 0.5 * gxy + wz;
  Eigen::MatrixXd Phi = Eigen::MatrixXd::Zero(model.num_dofs, 1);
  for (preproc::Index k = 0; k < mesh.num_nodes(); ++k) {
    const int nd = model.node_ndof[static_cast<std::size_t>(k)];
    if (nd == 0) continue;
    const Eigen::Vector3d u = G * mesh.x.row(k).transpose();
    for (int i = 0; i < 3; ++i) Phi(model.dof(k, i), 0) = u[i];
    if (nd == 6) Phi(model.dof(k, 5), 0) = wz;
  }
  const formats::ModalStress s = preproc::recover_modal_stress(model, Phi, nodes);
  ASSERT_EQ(s.size(), 4 * static_cast<std::int64_t>(nodes.size()));
  const double E = 7e10, nu = 0.33, lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  Voigt solid;
  solid << lambda * (exx + eyy) + 2 * mu * exx, lambda * (exx + eyy) + 2 * mu * eyy, lambda * (exx + eyy), mu * gxy, 0, 0;
  const Voigt skin = voigt(plane_stress(exx, eyy, gxy, 2.1e11, 0.3, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY()));
  double worst = 0;
  for (Eigen::Index r = 0; r < s.size(); ++r) {
    const std::int64_t want_layer = r % 4;  // solid, top, middle, bottom
    ASSERT_EQ(s.layer[static_cast<std::size_t>(r)], want_layer) << "row " << r;
    ASSERT_EQ(s.node[static_cast<std::size_t>(r)], s.node[static_cast<std::size_t>(r - want_layer)]);
    const Voigt& want = want_layer == formats::kSolid ? solid : skin;
    worst = std::max(worst, (s.modes[0].row(r).transpose() - want).cwiseAbs().maxCoeff() / skin.cwiseAbs().maxCoeff());
  }
  std::cout << "[ shell patch ] skin on a TET4 block: " << nodes.size() << " nodes x 4 rows, max relative error " << worst << "\n";
  EXPECT_LT(worst, 1e-9);
}
