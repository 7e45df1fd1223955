// Nodal stress recovery reproduces a constant stress exactly (the patch test of stress
// recovery): for the linear displacement u = E x every element's stress is the analytic
// sigma = lambda tr(eps) I + 2 mu eps, eps = (E + E^T) / 2, at every point, so the fit through the
// stiffness-rule points, its value at the nodes and the mean over the elements must all return
// it, on the sheared HEX8 grid of the reduction tests (incompatible modes, Taylor correction:
// they vanish for a linear field) and on gmsh TET4 and TET10 meshes (TET4's one-point rule: the
// constant). A quadratic displacement gives a linear stress, which TET10 and HEX20 (complete
// quadratic fields, affine elements) carry exactly and the linear fit through their points
// returns exactly at every node.
#include "ffr/preproc/mesh/gmsh_import.hpp"
#include "ffr/preproc/model/fe_model.hpp"
#include "ffr/preproc/part/part.hpp"
#include "ffr/preproc/reduce/modal_stress.hpp"
#include "support.hpp"

#include <gtest/gtest.h>

#include <array>

using namespace ffr;

namespace {

Eigen::Matrix<double, 6, 1> analytic(const Eigen::Matrix3d& E, double Ey, double nu) {
  const Eigen::Matrix3d eps = 0.5 * (E + E.transpose());
  const double lambda = Ey * nu / ((1 + nu) * (1 - 2 * nu)), mu = Ey / (2 * (1 + nu));
  const Eigen::Matrix3d S = lambda * eps.trace() * Eigen::Matrix3d::Identity() + 2 * mu * eps;
  Eigen::Matrix<double, 6, 1> s;
  s << S(0, 0), S(1, 1), S(2, 2), S(0, 1), S(1, 2), S(0, 2);
  return s;
}

// u_i = (E x)_i + 1/2 x^T H_i x: grad u = E + [x^T H_i] rows, a linear stress field.
using Curvature = std::array<Eigen::Matrix3d, 3>;

double worst_error(const preproc::FeModel& model, const Eigen::Matrix3d& E, double Ey, double nu,
                   const Curvature& H = {Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()}) {
  const preproc::Mesh& mesh = *model.mesh;
  Eigen::MatrixXd Phi = Eigen::MatrixXd::Zero(model.num_dofs, 1);
  std::vector<preproc::Index> nodes;
  for (preproc::Index n = 0; n < mesh.num_nodes(); ++n) {
    if (model.node_ndof[static_cast<std::size_t>(n)] == 0) continue;
    nodes.push_back(n);
    const Eigen::Vector3d x = mesh.x.row(n).transpose();
    const Eigen::Vector3d u = E * x;
    for (int i = 0; i < 3; ++i) Phi(model.dof(n, i), 0) = u[i] + 0.5 * x.dot(H[static_cast<std::size_t>(i)] * x);
  }
  const auto s = preproc::recover_modal_stress(model, Phi, nodes);
  double worst = 0, scale = 0;
  std::vector<Eigen::Matrix<double, 6, 1>> want;
  for (Eigen::Index p = 0; p < s.size(); ++p) {
    const Eigen::Vector3d x = s.position.row(p).transpose();
    Eigen::Matrix3d G = E;
    for (int i = 0; i < 3; ++i) G.row(i) += (H[static_cast<std::size_t>(i)] * x).transpose();
    want.push_back(analytic(G, Ey, nu));
    scale = std::max(scale, want.back().cwiseAbs().maxCoeff());
  }
  for (Eigen::Index p = 0; p < s.size(); ++p)
    worst = std::max(worst, (s.modes[0].row(p).transpose() - want[static_cast<std::size_t>(p)]).cwiseAbs().maxCoeff() / scale);
  return worst;
}

const Eigen::Matrix3d kGradient = (Eigen::Matrix3d() << 1e-3, 2e-4, -3e-4, 5e-4, -7e-4, 1e-4, 2e-4, 6e-4, 4e-4).finished();

}  // namespace

TEST(StressPatch, ConstantStressOnShearedHex8Grid) {
  test::HexGrid g(4, 3, 2);
  const preproc::FeModel model = preproc::build_model(g.mesh, g.part);
  const double err = worst_error(model, kGradient, 2.1e11, 0.3);
  std::cout << "[ patch ] HEX8: max relative nodal stress error " << err << "\n";
  EXPECT_LT(err, 1e-10);
}

TEST(StressPatch, ConstantStressOnGmshTetMeshes) {
  if (std::system("command -v gmsh > /dev/null 2>&1") != 0) GTEST_SKIP() << "gmsh missing";
  test::TempDir dir("stress_patch");
  test::write_text(dir / "b.geo", R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.1, 0.04, 0.03};
Physical Volume("body") = {1};
)");
  for (int order : {1, 2}) {
    test::gmsh_mesh(dir / "b.geo", dir / "b.msh", 0.015, order);
    test::write_text(dir / "b.json", R"({"geometry": "b.msh", "materials": [{"group": "body", "E": 7e10, "nu": 0.33, "rho": 2700}],
      "reduction": {"method": "free", "modes": 1}})");
    const preproc::PartSpec part = preproc::load_part(dir / "b.json");
    const preproc::Mesh mesh = preproc::load_mesh(part);
    const preproc::FeModel model = preproc::build_model(mesh, part);
    const double err = worst_error(model, kGradient, 7e10, 0.33);
    std::cout << "[ patch ] " << (order == 1 ? "TET4" : "TET10") << ": max relative nodal stress error " << err << "\n";
    EXPECT_LT(err, 1e-9);
  }
}

TEST(StressPatch, LinearStressOnQuadraticElements) {
  if (std::system("command -v gmsh > /dev/null 2>&1") != 0) GTEST_SKIP() << "gmsh missing";
  test::TempDir dir("stress_linear");
  Curvature H;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Matrix3d A = Eigen::Matrix3d::Random();
    H[static_cast<std::size_t>(i)] = 0.02 * (A + A.transpose());
  }
  for (const bool hex : {false, true}) {
    test::write_text(dir / "b.geo", std::string(R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.1, 0.04, 0.03};
Physical Volume("body") = {1};
)") + (hex ? "Transfinite Curve{:} = 4;\nTransfinite Surface{:};\nRecombine Surface{:};\nTransfinite Volume{1};\n" : ""));
    test::gmsh_mesh(dir / "b.geo", dir / "b.msh", 0.015, 2);
    test::write_text(dir / "b.json", R"({"geometry": "b.msh", "materials": [{"group": "body", "E": 7e10, "nu": 0.33, "rho": 2700}],
      "reduction": {"method": "free", "modes": 1}})");
    const preproc::PartSpec part = preproc::load_part(dir / "b.json");
    const preproc::Mesh mesh = preproc::load_mesh(part);
    ASSERT_EQ(mesh.blocks.front().type, hex ? preproc::ElementType::Hex20 : preproc::ElementType::Tet10);
    const preproc::FeModel model = preproc::build_model(mesh, part);
    const double err = worst_error(model, kGradient, 7e10, 0.33, H);
    std::cout << "[ patch ] " << (hex ? "HEX20" : "TET10") << ", linear stress: max relative nodal stress error " << err << "\n";
    EXPECT_LT(err, 1e-9);
  }
}
